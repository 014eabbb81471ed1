//! Which points two maps of one window label differently, and why: the points both maps have
//! (same `(eta_t, kappa2)` to 1e-9), counted by `(old label -> new label)`, each changed point
//! put down to what `droplet audit` said about it in the old map (the kinds of its
//! contradictions, or "none" when the old label was proven), as a Markdown table:
//!
//!     droplet audit OLD --json > old_audit.json
//!     cargo run --release -p droplet-sweep --example map_diff -- OLD/points.parquet NEW/points.parquet old_audit.json
use polars::prelude::*;
use std::collections::{BTreeMap, BTreeSet};

fn read(path: &str) -> DataFrame {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    ParquetReader::new(file)
        .finish()
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `(eta_t, kappa2)` in units of 1e-9 -> label.
fn labels(df: &DataFrame) -> BTreeMap<(i64, i64), String> {
    let e = df.column("eta_t").unwrap().f64().unwrap().clone();
    let k = df.column("kappa2").unwrap().f64().unwrap().clone();
    let c = df.column("class").unwrap().str().unwrap().clone();
    (0..df.height())
        .map(|i| {
            let key = |x: Option<f64>| (x.unwrap() * 1e9).round() as i64;
            (
                (key(e.get(i)), key(k.get(i))),
                c.get(i).unwrap_or("").to_string(),
            )
        })
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [old, new, audit] = args.as_slice() else {
        eprintln!("usage: map_diff OLD/points.parquet NEW/points.parquet OLD_AUDIT.json");
        std::process::exit(2);
    };
    let (old, new) = (labels(&read(old)), labels(&read(new)));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(audit).unwrap()).unwrap();
    let mut kinds: BTreeMap<(i64, i64), BTreeSet<String>> = BTreeMap::new();
    for c in report["list"].as_array().unwrap() {
        let key = |x: &serde_json::Value| (x.as_f64().unwrap() * 1e9).round() as i64;
        kinds
            .entry((key(&c["eta_t"]), key(&c["kappa2"])))
            .or_default()
            .insert(c["kind"].as_str().unwrap().to_string());
    }
    let (mut same, mut changes) = (0, BTreeMap::<(String, String, String), usize>::new());
    // Points whose old label was proven and still changed: listed by coordinates.
    let mut proven = Vec::new();
    for (p, was) in &old {
        let Some(now) = new.get(p) else { continue };
        if was == now {
            same += 1;
            continue;
        }
        let why = kinds.get(p).map_or("none".to_string(), |k| {
            k.iter().cloned().collect::<Vec<_>>().join(" + ")
        });
        if why == "none" {
            proven.push(format!(
                "({}, {}) {was} -> {now}",
                p.0 as f64 * 1e-9,
                p.1 as f64 * 1e-9
            ));
        }
        *changes.entry((was.clone(), now.clone(), why)).or_default() += 1;
    }
    let changed: usize = changes.values().sum();
    println!(
        "{} points in both maps: {same} same label, {changed} changed\n",
        same + changed
    );
    println!("| old label | new label | old audit of the point | points |");
    println!("|---|---|---|---|");
    let mut rows: Vec<_> = changes.into_iter().collect();
    rows.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    for ((was, now, why), n) in rows {
        println!("| {was} | {now} | {why} | {n} |");
    }
    if !proven.is_empty() {
        println!(
            "\nChanged although the old label was proven: {}",
            proven.join("; ")
        );
    }
}
