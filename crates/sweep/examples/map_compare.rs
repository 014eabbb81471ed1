//! Compares two sweeps of the same points (e.g. Fig. 2a with the paper's steady test and with
//! the Newton finish): run counts by status, wall time, the point classes that differ, and the
//! runs that still end at t_max with their diagnosis. Prints Markdown.
//!
//! `cargo run --release -p droplet-sweep --example map_compare -- BEFORE_DIR AFTER_DIR [ELAPSED_FILE]`
//! (ELAPSED_FILE: lines `<name> <seconds>` from the benchmark script).
use polars::prelude::*;
use std::path::Path;

fn read(path: &Path) -> DataFrame {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ParquetReader::new(file).finish().expect("a Parquet table")
}

fn strings(df: &DataFrame, name: &str) -> Vec<Option<String>> {
    match df.column(name) {
        Ok(c) => {
            let c = c.str().expect("a string column").clone();
            (0..c.len()).map(|i| c.get(i).map(str::to_string)).collect()
        }
        Err(_) => vec![None; df.height()],
    }
}

fn floats(df: &DataFrame, name: &str) -> Vec<f64> {
    let c = df.column(name).expect("column").f64().expect("f64").clone();
    (0..c.len()).map(|i| c.get(i).unwrap_or(f64::NAN)).collect()
}

struct Sweep {
    name: String,
    runs: DataFrame,
    points: DataFrame,
}

fn load(dir: &str) -> Sweep {
    let d = Path::new(dir);
    Sweep {
        name: d
            .file_name()
            .map_or(dir.to_string(), |n| n.to_string_lossy().into()),
        runs: read(&d.join("runs.parquet")),
        points: read(&d.join("points.parquet")),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 2 {
        eprintln!("usage: map_compare BEFORE_DIR AFTER_DIR [ELAPSED_FILE]");
        std::process::exit(2);
    }
    let (a, b) = (load(&args[0]), load(&args[1]));
    let elapsed: Vec<(String, f64)> = args
        .get(2)
        .map(|f| std::fs::read_to_string(f).expect("elapsed file"))
        .unwrap_or_default()
        .lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            Some((it.next()?.to_string(), it.next()?.parse().ok()?))
        })
        .collect();
    cost_table(&a, &b, &elapsed);
    class_changes(&a, &b);
    for s in [&a, &b] {
        unfinished_runs(s);
    }
}

/// Runs, endings and time of both sweeps, one row each.
fn cost_table(a: &Sweep, b: &Sweep, elapsed: &[(String, f64)]) {
    println!("| sweep | runs | steady | t_max / step_limit / saddle | diverged | sweep wall (s) | sum of run wall_s (s) | mean t_end |");
    println!("|---|---|---|---|---|---|---|---|");
    for s in [a, b] {
        let status = strings(&s.runs, "status");
        let count = |w: &str| status.iter().filter(|x| x.as_deref() == Some(w)).count();
        let wall = floats(&s.runs, "wall_s").iter().sum::<f64>();
        let t_end = floats(&s.runs, "t_end");
        let sweep_wall = elapsed
            .iter()
            .find(|(n, _)| *n == s.name)
            .map_or("-".to_string(), |(_, x)| format!("{x:.0}"));
        println!(
            "| {} | {} | {} | {} | {} | {sweep_wall} | {wall:.0} | {:.1} |",
            s.name,
            s.runs.height(),
            count("steady"),
            count("t_max") + count("step_limit") + count("saddle"),
            count("diverged"),
            t_end.iter().sum::<f64>() / t_end.len().max(1) as f64
        );
    }
}

/// The points whose class differs between the two sweeps.
fn class_changes(a: &Sweep, b: &Sweep) {
    let classes = |s: &Sweep| {
        let (e, k) = (floats(&s.points, "eta_t"), floats(&s.points, "kappa2"));
        let c = strings(&s.points, "class");
        (0..e.len())
            .map(|i| ((e[i], k[i]), c[i].clone().unwrap_or_default()))
            .collect::<Vec<_>>()
    };
    let (ca, cb) = (classes(a), classes(b));
    let differ: Vec<_> = ca
        .iter()
        .filter_map(|(p, c)| {
            let other = cb.iter().find(|(q, _)| q == p)?;
            (other.1 != *c).then(|| (*p, c.clone(), other.1.clone()))
        })
        .collect();
    println!(
        "\nPoint classes: {} of {} equal; {} differ:\n",
        ca.len() - differ.len(),
        ca.len(),
        differ.len()
    );
    if !differ.is_empty() {
        println!("| eta_t | kappa2 | {} | {} |", a.name, b.name);
        println!("|---|---|---|---|");
        for ((e, k), x, y) in &differ {
            println!("| {e:.4} | {k:.4} | {x} | {y} |");
        }
    }
}

/// The runs of `s` that did not finish, with their diagnosis.
fn unfinished_runs(s: &Sweep) {
    let status = strings(&s.runs, "status");
    let diag = strings(&s.runs, "diagnosis");
    let ic = strings(&s.runs, "ic");
    let (e, k) = (floats(&s.runs, "eta_t"), floats(&s.runs, "kappa2"));
    let unfinished: Vec<usize> = (0..status.len())
        .filter(|&i| {
            matches!(
                status[i].as_deref(),
                Some("t_max") | Some("step_limit") | Some("saddle")
            )
        })
        .collect();
    println!(
        "\nRuns of `{}` that did not finish: {}\n",
        s.name,
        unfinished.len()
    );
    if unfinished.is_empty() {
        return;
    }
    println!("| eta_t | kappa2 | IC | diagnosis |");
    println!("|---|---|---|---|");
    for i in unfinished {
        println!(
            "| {:.4} | {:.4} | {} | {} |",
            e[i],
            k[i],
            ic[i].as_deref().unwrap_or("-"),
            diag[i].as_deref().unwrap_or("(not recorded)")
        );
    }
}
