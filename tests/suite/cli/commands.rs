//! `droplet bench --quick`, `droplet bench --map` and the top-level help.
use crate::common::{json, read, run};
use polars::prelude::*;

#[test]
fn bench_quick_writes_its_table_summary_and_picture_and_rescores() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    let o = out.to_str().unwrap();
    let j = json(&run(&[
        "bench", "--quick", "--out", o, "--json", "--jobs", "2",
    ]));
    assert_eq!(j["reference_reused"], false);
    for f in [
        "bench.parquet",
        "bench.md",
        "summary.json",
        "reference.json",
        "work_precision.png",
        "work_precision.svg",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    let df = read(&out.join("bench.parquet"));
    assert_eq!(df.height() as u64, j["rows"].as_u64().unwrap());
    assert_eq!(df.column("n").unwrap().dtype(), &DataType::UInt32);
    assert_eq!(df.column("err_series").unwrap().dtype(), &DataType::Float64);
    let meta =
        droplet_sweep::tables::sweep_tables::read_metadata(&out.join("bench.parquet")).unwrap();
    for k in ["git_commit", "machine", "command", "plan"] {
        assert!(meta.contains_key(k), "{k}");
    }
    // Spatial convergence shows: the MD case's error falls from N = 32 to N = 48 (dt = 0.05).
    let err = |n: u32| {
        let case = df.column("case").unwrap().str().unwrap().clone();
        let fam = df.column("family").unwrap().str().unwrap().clone();
        let dt = df.column("dt").unwrap().f64().unwrap().clone();
        let (ev, es) = (
            df.column("err_v").unwrap().f64().unwrap().clone(),
            df.column("err_s").unwrap().f64().unwrap().clone(),
        );
        (0..df.height())
            .find(|&i| {
                case.get(i) == Some("MD")
                    && fam.get(i) == Some(format!("spectral N={n}").as_str())
                    && dt.get(i) == Some(0.05)
            })
            .map(|i| ev.get(i).unwrap().max(es.get(i).unwrap()))
            .unwrap()
    };
    assert!(err(48) < err(32) / 3.0, "{} vs {}", err(48), err(32));
    // Not overwritten without --force; re-scored against the stored reference on request.
    let again = run(&["bench", "--quick", "--out", o]);
    assert_eq!(again.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    let r = json(&run(&[
        "bench",
        "--quick",
        "--out",
        o,
        "--rescore",
        "--json",
    ]));
    assert_eq!(
        (r["reference_reused"].as_bool(), r["rows"].as_u64()),
        (Some(true), j["rows"].as_u64())
    );
    let df2 = read(&out.join("bench.parquet"));
    for name in df.get_column_names() {
        let (a, b) = (df.column(name).unwrap(), df2.column(name).unwrap());
        assert!(
            a.equals_missing(b),
            "column {name} changed by re-scoring:\n{a:?}\n{b:?}"
        );
    }
}

#[test]
fn top_level_help_lists_each_command_in_one_short_line() {
    let o = run(&["--help"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    let commands: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .collect();
    assert!(commands.len() >= 12, "{text}");
    for line in commands {
        assert!(line.len() <= 100, "too long for one line: {line}");
        assert!(!line.ends_with('.'), "a summary, not a sentence: {line}");
    }
    // The detail lives in each command's own --help.
    let o = run(&["plot", "--help"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("Refused while a sweep works on OUT"),
        "{text}"
    );
}

#[test]
fn bench_map_profiles_a_seeded_sample_of_a_committed_map() {
    // Six runs of the committed smoke map (N = 96) computed again and profiled: each ends as
    // the map's run did, its parts add up to no more than its time, and the same seed draws
    // the same runs.
    let dir = tempfile::tempdir().unwrap();
    let profile = |name: &str| {
        let out = dir.path().join(name);
        let j = json(&run(&[
            "bench",
            "--map",
            "results/smoke",
            "--sample",
            "6",
            "--seed",
            "3",
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]));
        (out, j)
    };
    let (out, j) = profile("a");
    assert_eq!(
        (j["runs"].as_u64(), j["map_runs"].as_u64()),
        (Some(6), Some(64)),
        "{j}"
    );
    let total = &j["total"];
    assert_eq!(total["same_end"], 6, "{j}");
    assert!(j["changed"].as_array().unwrap().is_empty(), "{j}");
    let parts = &total["profile"];
    let seconds: f64 = [
        "stepping_s",
        "newton_s",
        "eigen_s",
        "landing_s",
        "flow_s",
        "leap_s",
        "diagnosis_s",
    ]
    .iter()
    .map(|k| parts[k].as_f64().unwrap())
    .sum();
    let wall = total["wall_s"].as_f64().unwrap();
    assert!(
        seconds <= wall + 1e-9 && parts["stepping_s"].as_f64().unwrap() > 0.0,
        "{j}"
    );
    assert!(parts["newton_solves"].as_u64().unwrap() >= 6, "{j}");
    // Groups by ending, by level and by decade of simulated time cover every run once.
    for groups in ["by_ending", "by_level", "by_duration"] {
        let n: u64 = j[groups]
            .as_array()
            .unwrap()
            .iter()
            .map(|g| g["runs"].as_u64().unwrap())
            .sum();
        assert_eq!(n, 6, "{groups}: {j}");
    }
    let df = read(&out.join("map_profile.parquet"));
    assert_eq!(df.height(), 6);
    let runs_of = |df: &DataFrame| {
        let p = df.column("point").unwrap().u32().unwrap().clone();
        let ic = df.column("ic").unwrap().str().unwrap().clone();
        let mut v: Vec<(u32, String)> = (0..df.height())
            .map(|i| (p.get(i).unwrap(), ic.get(i).unwrap().to_string()))
            .collect();
        v.sort();
        v
    };
    let (again, _) = profile("b");
    assert_eq!(
        runs_of(&df),
        runs_of(&read(&again.join("map_profile.parquet")))
    );
}
