//! A map's cost and endings from its tables, as Markdown: per refinement level the points,
//! runs and run time (sum of `wall_s`), and how the runs ended (`ended_by`, or `unsettled`),
//! overall and per level; the point labels.
//!
//!     cargo run --release -p droplet-sweep --example map_summary -- results/fig2a-map
use polars::prelude::*;
use std::collections::BTreeMap;
use std::path::Path;

fn read(path: &Path) -> DataFrame {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ParquetReader::new(file).finish().expect("a Parquet table")
}

fn strings(df: &DataFrame, name: &str) -> Vec<String> {
    let c = df.column(name).unwrap().str().unwrap().clone();
    (0..c.len())
        .map(|i| c.get(i).unwrap_or("-").to_string())
        .collect()
}

fn u32s(df: &DataFrame, name: &str) -> Vec<u32> {
    let c = df.column(name).unwrap().u32().unwrap().clone();
    (0..c.len()).map(|i| c.get(i).unwrap_or(0)).collect()
}

fn main() {
    let dir = std::env::args().nth(1).expect("usage: map_summary DIR");
    let dir = Path::new(&dir);
    let (runs, points) = (
        read(&dir.join("runs.parquet")),
        read(&dir.join("points.parquet")),
    );
    let level_of: BTreeMap<u32, u32> = u32s(&points, "point")
        .into_iter()
        .zip(u32s(&points, "level"))
        .collect();
    let wall = runs.column("wall_s").unwrap().f64().unwrap().clone();
    let (ended, unsettled) = (strings(&runs, "ended_by"), strings(&runs, "unsettled"));
    let point = u32s(&runs, "point");
    // level -> (points, runs, seconds, endings)
    let mut levels: BTreeMap<u32, (usize, usize, f64, BTreeMap<String, usize>)> = BTreeMap::new();
    for l in level_of.values() {
        levels.entry(*l).or_default().0 += 1;
    }
    for i in 0..runs.height() {
        let e = levels.entry(level_of[&point[i]]).or_default();
        e.1 += 1;
        e.2 += wall.get(i).unwrap_or(0.0);
        let how = if ended[i] != "-" {
            ended[i].clone()
        } else {
            format!("unsettled: {}", unsettled[i])
        };
        *e.3.entry(how).or_default() += 1;
    }
    let kinds: Vec<String> = {
        let mut k: Vec<String> = levels.values().flat_map(|l| l.3.keys().cloned()).collect();
        k.sort();
        k.dedup();
        k
    };
    println!(
        "| level | points | runs | run time (s) | {} |",
        kinds.join(" | ")
    );
    println!("|---|---|---|---|{}", "---|".repeat(kinds.len()));
    let (mut tp, mut tr, mut ts) = (0, 0, 0.0);
    let mut totals: BTreeMap<&str, usize> = BTreeMap::new();
    for (l, (p, r, s, e)) in &levels {
        let counts: Vec<String> = kinds
            .iter()
            .map(|k| e.get(k).copied().unwrap_or(0).to_string())
            .collect();
        println!("| {l} | {p} | {r} | {s:.0} | {} |", counts.join(" | "));
        (tp, tr, ts) = (tp + p, tr + r, ts + s);
        for k in &kinds {
            *totals.entry(k).or_default() += e.get(k).copied().unwrap_or(0);
        }
    }
    let counts: Vec<String> = kinds
        .iter()
        .map(|k| totals[k.as_str()].to_string())
        .collect();
    println!("| all | {tp} | {tr} | {ts:.0} | {} |", counts.join(" | "));
    let mut labels: BTreeMap<String, usize> = BTreeMap::new();
    for l in strings(&points, "class") {
        *labels.entry(l).or_default() += 1;
    }
    println!("\nPoint labels: {}", {
        let v: Vec<String> = labels.iter().map(|(k, n)| format!("{k} {n}")).collect();
        v.join(", ")
    });
}
