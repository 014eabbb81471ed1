//! `droplet sweep`, `merge` and their directories: the smoke sweep's tables and picture, resume
//! after kills, one sweep per directory, malformed specs (shards merged: `shards`).
use crate::cli::TINY;
use crate::common::{
    droplet, json, read, run, sweep_in_background, table_without_wall, write_spec,
};
use polars::prelude::*;
use std::process::Stdio;
use std::time::Duration;

#[test]
fn smoke_sweep_produces_typed_tables_and_a_picture() {
    let (out, summary) = crate::common::smoke_sweep();
    assert_eq!(summary["runs"], 64);
    assert_eq!(summary["points"], 16);
    let runs = read(&out.join("runs.parquet"));
    let points = read(&out.join("points.parquet"));
    assert_eq!(runs.height(), 64);
    assert_eq!(points.height(), 16);
    let schema = runs.schema();
    assert_eq!(schema.get("v"), Some(&DataType::Float64));
    assert_eq!(schema.get("steps"), Some(&DataType::UInt64));
    assert_eq!(schema.get("point"), Some(&DataType::UInt32));
    assert_eq!(schema.get("class"), Some(&DataType::String));
    assert_eq!(points.schema().get("kappa2"), Some(&DataType::Float64));
    // At least two different point classes, all from the allowed vocabulary.
    let class_col = points.column("class").unwrap().str().unwrap();
    let classes: std::collections::BTreeSet<String> = (0..points.height())
        .filter_map(|i| class_col.get(i).map(String::from))
        .collect();
    assert!(classes.len() >= 2, "{classes:?}");
    for c in &classes {
        let ok = [
            "IC",
            "ID",
            "MD",
            "MC",
            "not classified",
            "diverged",
            "unsettled",
        ]
        .contains(&c.as_str())
            || c.split('/').all(|p| ["IC", "ID", "MD", "MC"].contains(&p));
        assert!(ok, "unexpected class {c}");
    }
    // The MD region is at small eta_t, IC at large eta_t and kappa2 (paper Fig. 2a layout).
    let label_at = |eta: f64, k: f64| -> String {
        let e = points.column("eta_t").unwrap().f64().unwrap();
        let kk = points.column("kappa2").unwrap().f64().unwrap();
        let c = points.column("class").unwrap().str().unwrap();
        (0..points.height())
            .find(|&i| {
                (e.get(i).unwrap() - eta).abs() < 1e-9 && (kk.get(i).unwrap() - k).abs() < 1e-9
            })
            .map(|i| c.get(i).unwrap().to_string())
            .unwrap()
    };
    assert_eq!(label_at(0.07, 0.10), "MD");
    assert_eq!(label_at(0.10, 0.16), "IC");
    // Metadata: spec, hash, versions, commit.
    let meta =
        droplet_sweep::tables::sweep_tables::read_metadata(&out.join("runs.parquet")).unwrap();
    for key in [
        "spec",
        "spec_sha256",
        "droplet_version",
        "solver_version",
        "git_commit",
    ] {
        assert!(meta.contains_key(key), "missing metadata {key}");
    }
    assert!(meta["spec"].contains("name: smoke"));
    for f in ["phase_map.png", "phase_map.svg"] {
        assert!(std::fs::metadata(out.join(f)).unwrap().len() > 1000);
    }
    // status agrees; every run settled, and the audit finds every label a stable state.
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    assert_eq!(st["runs_done"], 64);
    assert_eq!(st["complete"], true);
    assert_eq!(st["points_unsettled"], 0, "{st}");
    let audit = json(&run(&["audit", out.to_str().unwrap(), "--json"]));
    assert_eq!(audit["contradictions"], 0, "{audit}");
    assert_eq!(audit["points_clean"], 16, "{audit}");
}

#[test]
fn sigkill_at_several_moments_then_resume_gives_identical_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let reference = dir.path().join("ref");
    let started = std::time::Instant::now();
    json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        reference.to_str().unwrap(),
        "--json",
        "--jobs",
        "2",
    ]));
    // Kills at fractions of the uninterrupted sweep's own time (0.12 s on an idle 2-core VM,
    // several times that under load): fixed moments missed it on a fast machine.
    let whole = started.elapsed().as_secs_f64();

    let resumed = dir.path().join("resumed");
    let mut kills = 0;
    for fraction in [0.15, 0.35, 0.55, 0.75] {
        let mut child = sweep_in_background(&spec, &resumed);
        std::thread::sleep(Duration::from_secs_f64(fraction * whole));
        if child.try_wait().unwrap().is_none() {
            child.kill().unwrap(); // SIGKILL
            kills += 1;
        }
        child.wait().unwrap();
    }
    assert!(
        kills >= 1,
        "the sweep was never interrupted ({whole:.3} s uninterrupted); make TINY larger"
    );
    let done = json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        resumed.to_str().unwrap(),
        "--json",
    ]));
    assert!(done["reused"].as_u64().unwrap() > 0, "{done}");
    // Nothing duplicated: one record per run. (A write cut by SIGKILL may leave a `*.tmp`,
    // never read; the store removes temporaries once they are a minute old.)
    let files: Vec<_> = std::fs::read_dir(resumed.join("runs"))
        .unwrap()
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "json"))
        .collect();
    assert_eq!(files.len(), 18);
    for t in ["runs.parquet", "points.parquet"] {
        let a = table_without_wall(&reference.join(t));
        let b = table_without_wall(&resumed.join(t));
        assert!(a.equals_missing(&b), "{t} differs:\n{a}\n{b}");
    }
}

#[test]
fn a_second_sweep_on_the_same_directory_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let slow = TINY
        .replace("n: 32", "n: 64")
        .replace("t_max: 150", "t_max: 400");
    let spec = write_spec(dir.path(), "slow.yaml", &slow);
    let out = dir.path().join("o");
    let mut first = droplet()
        .args([
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--jobs",
            "1",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait until the first has taken the lock.
    for _ in 0..100 {
        if out.join(".lock").exists() {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(100));
    let second = run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let still_running = first.try_wait().unwrap().is_none();
    first.kill().ok();
    first.wait().unwrap();
    assert!(still_running, "first sweep ended before the second started");
    assert_eq!(second.status.code(), Some(2));
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(err.contains("in use by another droplet process"), "{err}");
}

/// A spec of two runs; the malformed ones change it (`OUTDIR`: the output directory).
const GOOD_SPEC: &str = "name: m\noutput: OUTDIR\ngrid:\n  eta_t: {start: 0.07, stop: 0.08, step: 0.01}\n  kappa2: [0.11]\nsolver:\n  n: 32\n  dt: 0.05\n  t_max: 10\n";

/// Malformed specs: `(what, spec, the key named)`. Unknown keys and bad solver settings.
fn malformed_solver_settings() -> Vec<(&'static str, String, &'static str)> {
    let good = GOOD_SPEC;
    vec![
        ("unknown top key", format!("{good}colour: red\n"), "colour"),
        (
            "unknown solver key",
            good.replace("  n: 32", "  nn: 32"),
            "solver.nn",
        ),
        ("odd n", good.replace("n: 32", "n: 33"), "solver.n"),
        (
            "negative tol",
            good.replace("  n: 32", "  n: 32\n  tol: -1"),
            "solver.tol",
        ),
        (
            "adaptive paper-fd",
            good.replace("  n: 32", "  scheme: paper-fd\n  n: 32\n  tol: 1.0e-4"),
            "solver.tol",
        ),
        (
            "dt_max below dt",
            good.replace("  n: 32", "  n: 32\n  dt_max: 0.01"),
            "solver.dt_max",
        ),
        ("zero n", good.replace("n: 32", "n: 0"), "solver.n"),
        (
            "negative dt",
            good.replace("dt: 0.05", "dt: -0.05"),
            "solver.dt",
        ),
        (
            "string dt",
            good.replace("dt: 0.05", "dt: fast"),
            "solver.dt",
        ),
        (
            "nan t_max",
            good.replace("t_max: 10", "t_max: .nan"),
            "solver.t_max",
        ),
    ]
}

/// Malformed specs: bad grids, initial conditions, parameters and YAML.
fn malformed_grids_and_documents() -> Vec<(&'static str, String, &'static str)> {
    let good = GOOD_SPEC;
    vec![
        (
            "zero step",
            good.replace("step: 0.01", "step: 0"),
            "grid.eta_t.step",
        ),
        (
            "reversed range",
            good.replace("stop: 0.08", "stop: 0.06"),
            "grid.eta_t.stop",
        ),
        (
            "empty list",
            good.replace("kappa2: [0.11]", "kappa2: []"),
            "grid.kappa2",
        ),
        (
            "negative kappa2",
            good.replace("kappa2: [0.11]", "kappa2: [-0.1]"),
            "grid.kappa2",
        ),
        (
            "missing grid",
            good.replace(
                "grid:\n  eta_t: {start: 0.07, stop: 0.08, step: 0.01}\n  kappa2: [0.11]\n",
                "",
            ),
            "grid",
        ),
        (
            "missing step",
            good.replace(", step: 0.01", ""),
            "grid.eta_t.step",
        ),
        (
            "unknown ic",
            format!("{good}initial_conditions: [i, v]\n"),
            "initial_conditions",
        ),
        (
            "scheme",
            good.replace("solver:\n", "solver:\n  scheme: rk4\n"),
            "solver.scheme",
        ),
        (
            "params mass",
            format!("{good}params: {{mass: -1}}\n"),
            "params.mass",
        ),
        (
            "inf eta",
            good.replace("start: 0.07", "start: .inf"),
            "grid.eta_t.start",
        ),
        (
            "grid not a mapping",
            good.replace("grid:\n", "grid: 3\nx:\n"),
            "grid",
        ),
        ("bad yaml", format!("{good}  : [\n"), "(document)"),
    ]
}

#[test]
fn malformed_specs_exit_2_name_the_key_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [malformed_solver_settings(), malformed_grids_and_documents()].concat();
    assert!(cases.len() >= 15);
    for (what, text, key) in cases {
        let outdir = dir.path().join(format!("out-{}", what.replace(' ', "_")));
        let text = text.replace("OUTDIR", outdir.to_str().unwrap());
        let spec = write_spec(dir.path(), "bad.yaml", &text);
        let o = run(&["sweep", spec.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{what}: {err}");
        assert!(
            err.contains(&format!("`{key}`")) || err.contains(key),
            "{what}: message lacks {key}: {err}"
        );
        assert!(
            err.contains("bad.yaml"),
            "{what}: message lacks the file: {err}"
        );
        assert!(!outdir.exists(), "{what}: output directory was created");
    }
}
