//! Re-diagnoses the unfinished runs of a runs table with this binary's Newton finish and
//! counts how their diagnoses change (the settled / beside-unstable flags that classification
//! and refinement read), so a change to the diagnosis can be judged on a committed map
//! without recomputing it:
//!
//!     cargo run --release -p droplet-sweep --example rediagnose -- results/fig2a-adaptive-fast/runs.parquet
//!
//! A diagnosis needs only the run's final `(vx, vy, a2, b2)` and its parameters (Newton on
//! the steady equations), not its field, so this takes about 0.1 s a run at N = 192.
use droplet_solver::newton_finish::{
    diagnosis_beside_unstable, diagnosis_settles_class, NewtonFinish,
};
use droplet_solver::{ModelParams, SolverSettings};
use polars::prelude::*;
use std::collections::BTreeMap;

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: rediagnose RUNS.parquet");
    let file = std::fs::File::open(&path).expect("a readable runs table");
    let runs = ParquetReader::new(file).finish().expect("a Parquet table");
    let f64s = |name: &str| runs.column(name).expect(name).f64().expect(name).clone();
    let strs = |name: &str| runs.column(name).expect(name).str().expect(name).clone();
    let (status, diagnosis) = (strs("status"), strs("diagnosis"));
    let [eta_t, kappa2, eta2, radius, sigma, box_len, mass, vx, vy, a2, b2] = [
        "eta_t", "kappa2", "eta2", "radius", "sigma", "box_len", "mass", "vx", "vy", "a2", "b2",
    ]
    .map(f64s);
    let n = runs.column("n").expect("n").u32().expect("n").clone();
    let t_max = f64s("t_max");
    let mut changes: BTreeMap<(&str, &str), usize> = BTreeMap::new();
    let mut examples = Vec::new();
    let flags = |d: &str| {
        if diagnosis_beside_unstable(d) {
            "beside unstable"
        } else if diagnosis_settles_class(d) {
            "settled"
        } else {
            "unsettled"
        }
    };
    for i in 0..runs.height() {
        // `saddle` runs keep the diagnosis written when they stopped (it includes the bound).
        if !matches!(status.get(i), Some("t_max" | "step_limit")) {
            continue;
        }
        let g = |c: &Float64Chunked| c.get(i).expect("a value");
        let params = ModelParams {
            eta_t: g(&eta_t),
            kappa2: g(&kappa2),
            eta2: g(&eta2),
            radius: g(&radius),
            sigma: g(&sigma),
            box_len: g(&box_len),
            mass: g(&mass),
        };
        let settings = SolverSettings {
            n: n.get(i).expect("n") as usize,
            t_max: g(&t_max),
            ..SolverSettings::default()
        };
        let z = [g(&vx), g(&vy), g(&a2), g(&b2)];
        let mut finish = NewtonFinish::new(&params, &settings);
        let now = finish.diagnose(z);
        let (before, after) = (flags(diagnosis.get(i).unwrap_or("")), flags(&now));
        let count = changes.entry((before, after)).or_default();
        *count += 1;
        if before != after && *count <= 3 {
            let ic = runs.column("ic").expect("ic").str().expect("ic").get(i);
            examples.push(format!(
                "- ({}, {}) from {}: v {:.4}, s {:.4}: {before} -> {now}",
                params.eta_t,
                params.kappa2,
                ic.unwrap_or("?"),
                z[0].hypot(z[1]),
                z[2].hypot(z[3])
            ));
        }
    }
    println!("| stored diagnosis | this binary's | runs |\n|---|---|---|");
    for ((a, b), k) in changes {
        println!("| {a} | {b} | {k} |");
    }
    println!(
        "\nThe first changed runs of each kind:\n{}",
        examples.join("\n")
    );
}
