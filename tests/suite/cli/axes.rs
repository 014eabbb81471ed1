//! Sweeps in any parameter: one and two axes of the reduced model (fast), a small PDE sweep in
//! `(mass, kappa2)` resumed after kills and run in shards, and the refusals of bad axes.
use crate::cli::plane_boundaries::{md_fold_along_eta_t, onset_of_motion};
use crate::common::{droplet, json, kill_at_random_moments, read, run, sweep};
use crate::common::{table_without_wall, write_spec};
use std::process::Stdio;

/// The column `name` of a table as floats.
pub(crate) fn floats(df: &polars::prelude::DataFrame, name: &str) -> Vec<f64> {
    let c = df.column(name).unwrap().f64().unwrap().clone();
    (0..c.len()).map(|i| c.get(i).unwrap()).collect()
}

/// A table's column names.
pub(crate) fn columns(df: &polars::prelude::DataFrame) -> Vec<String> {
    df.get_column_names()
        .iter()
        .map(|c| c.to_string())
        .collect()
}

/// `droplet sweep SPEC --out OUT --json`, pictures included: its JSON.
pub(crate) fn sweep_with_pictures(
    spec: &std::path::Path,
    out: &std::path::Path,
) -> serde_json::Value {
    json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]))
}

#[test]
fn a_one_axis_ode_sweep_in_mass_has_a_mass_column_and_draws_lines() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "m.yaml",
        "model: ode\nparams: {eta_t: 0.08, kappa2: 0.13}\ngrid:\n  mass: [0.02, 0.05, 0.1, 0.3]\n",
    );
    let out = dir.path().join("m");
    let s = sweep_with_pictures(&spec, &out);
    assert_eq!(s["runs"], 4 * 4, "{s}");
    let points = read(&out.join("points.parquet"));
    let cols = columns(&points);
    assert!(cols.contains(&"mass".to_string()), "{cols:?}");
    assert!(!cols.contains(&"eta_t".to_string()), "{cols:?}");
    assert_eq!(floats(&points, "mass"), vec![0.02, 0.05, 0.1, 0.3]);
    // Every run has the point's mass and the fixed eta_t, kappa2.
    let runs = read(&out.join("runs.parquet"));
    let (mass, eta, kappa) = (
        floats(&runs, "mass"),
        floats(&runs, "eta_t"),
        floats(&runs, "kappa2"),
    );
    let point = runs.column("point").unwrap().u32().unwrap().clone();
    for i in 0..runs.height() {
        let p = point.get(i).unwrap() as usize;
        assert_eq!(mass[i], [0.02, 0.05, 0.1, 0.3][p]);
        assert_eq!((eta[i], kappa[i]), (0.08, 0.13));
    }
    assert!(out.join("bifurcation_lines.png").exists());
    assert!(!out.join("phase_map.png").exists());
    assert!(!out.join("boundaries.parquet").exists());
    // Status and plot read the axis back, from the store and from the tables alone.
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    assert_eq!(
        (st["points"].as_u64(), st["complete"].as_bool()),
        (Some(4), Some(true))
    );
    std::fs::remove_dir_all(out.join("runs")).unwrap();
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    assert_eq!(st["points"].as_u64(), Some(4), "{st}");
    let o = run(&["plot", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn a_refined_ode_map_in_the_mass_eta_t_plane_is_named_by_its_axes() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "me.yaml",
        "model: ode\nparams: {kappa2: 0.13}\ngrid:\n  mass: {start: 0.05, stop: 0.45, step: 0.1}\n  eta_t: {start: 0.07, stop: 0.1, step: 0.005}\nrefine: {levels: 2, min_step: {eta_t: 0.002}}\n",
    );
    let out = dir.path().join("me");
    sweep_with_pictures(&spec, &out);
    let points = read(&out.join("points.parquet"));
    let cols = columns(&points);
    for want in ["mass", "eta_t", "d_mass", "d_eta_t", "level"] {
        assert!(cols.contains(&want.to_string()), "{want} missing: {cols:?}");
    }
    assert!(!cols.contains(&"kappa2".to_string()), "{cols:?}");
    // Refinement split cells where the class changes: points beyond level 0, at half steps.
    let levels = points.column("level").unwrap().u32().unwrap().clone();
    assert!((0..levels.len()).any(|i| levels.get(i).unwrap() > 0));
    let d_eta = floats(&points, "d_eta_t");
    assert!(d_eta.iter().all(|&d| d >= 0.0025 - 1e-12), "{d_eta:?}");
    // The runs carry the point's coordinates.
    let runs = read(&out.join("runs.parquet"));
    let (pm, pe) = (floats(&points, "mass"), floats(&points, "eta_t"));
    let (rm, re) = (floats(&runs, "mass"), floats(&runs, "eta_t"));
    let point = runs.column("point").unwrap().u32().unwrap().clone();
    for i in 0..runs.height() {
        let p = point.get(i).unwrap() as usize;
        assert_eq!((rm[i], re[i]), (pm[p], pe[p]));
        assert_eq!(floats(&runs, "kappa2")[i], 0.13);
    }
    // The map shows both a moving and a resting class.
    let classes = points.column("class").unwrap().str().unwrap().clone();
    let labels: std::collections::BTreeSet<&str> =
        (0..classes.len()).filter_map(|i| classes.get(i)).collect();
    assert!(labels.iter().any(|l| l.contains("MD")), "{labels:?}");
    assert!(labels.iter().any(|l| l.starts_with("IC")), "{labels:?}");
    assert!(out.join("phase_map.png").exists() && out.join("phase_map.svg").exists());
    // `droplet boundaries` draws where the paper-plane boundaries cross the sweep's line
    // kappa2 = 0.13: lines of constant eta_t across the mass axis (mass moves none of them),
    // in the sweep's own coordinates.
    let o = run(&[
        "boundaries",
        "--out",
        out.to_str().unwrap(),
        "--n",
        "96",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (onset, mass) = onset_of_motion(&out.join("boundaries.parquet"), "mass");
    assert!((0.074..0.079).contains(&onset[0]), "{onset:?}");
    assert_eq!(onset[0], onset[1]);
    assert_eq!(mass, vec![0.05, 0.45]);
    // With shape modes 2..3 the crossings are those of the 3-mode curves: the MD fold where
    // the 3-mode branch followed in eta_t at kappa2 = 0.13 folds (N = 64).
    let b = json(&run(&[
        "boundaries",
        "--out",
        out.to_str().unwrap(),
        "--n",
        "64",
        "--modes",
        "3",
        "--json",
    ]));
    assert_eq!(b["modes"], 3, "{b}");
    let fold = b["curves"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["model"] == "pde" && c["curve"] == "MD saddle-node (x axis)")
        .unwrap_or_else(|| panic!("no fold: {b}"));
    let at = fold["eta_t"][0].as_f64().unwrap();
    assert_eq!(fold["mass"], serde_json::json!([0.05, 0.45]), "{fold}");
    let sn = md_fold_along_eta_t("kappa2=0.13", &["--modes", "3", "--n", "64"]);
    // The 2-mode fold lies at 0.0811 here: the third mode moves it by 4e-3.
    assert!((at - sn).abs() < 1e-9 && at < 0.079, "{at} vs {sn}");
}

/// A small PDE map in `(mass, kappa2)`: the CLI tests' TINY (N = 32, fixed steps, seconds)
/// with `mass` for `eta_t`.
fn tiny_mass() -> String {
    crate::cli::TINY
        .replace("name: tiny\n", "name: tiny-mass\nparams: {eta_t: 0.09}\n")
        .replace("  eta_t: [0.07, 0.09, 0.11]\n", "  mass: [0.05, 0.2]\n")
}

#[test]
fn a_pde_mass_kappa2_sweep_resumes_after_kills_and_shards_give_equal_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tm.yaml", &tiny_mass());
    let single = dir.path().join("single");
    let started = std::time::Instant::now();
    let o = sweep(&spec, &single, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let full_ms = started.elapsed().as_millis() as u64;
    let points = read(&single.join("points.parquet"));
    assert_eq!(points.height(), 6);
    assert_eq!(
        floats(&points, "mass"),
        vec![0.05, 0.05, 0.05, 0.2, 0.2, 0.2]
    );

    // Killed at random moments, then finished: the same tables.
    let resumed = dir.path().join("resumed");
    let (kills, _) = kill_at_random_moments(&spec, &resumed, full_ms, 2, 8);
    assert!(kills >= 1);
    assert!(sweep(&spec, &resumed, &[]).status.success());
    // Two shards side by side, then merged: the same tables.
    let sharded = dir.path().join("sharded");
    let shard = |k: &str| {
        droplet()
            .args(["sweep", spec.to_str().unwrap(), "--out"])
            .arg(&sharded)
            .args(["--shard", k, "--jobs", "1", "--json"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap()
    };
    let (mut a, mut b) = (shard("0/2"), shard("1/2"));
    assert!(a.wait().unwrap().success() && b.wait().unwrap().success());
    json(&run(&["merge", sharded.to_str().unwrap(), "--json"]));
    for t in ["runs.parquet", "points.parquet"] {
        let want = table_without_wall(&single.join(t));
        for other in [&resumed, &sharded] {
            let got = table_without_wall(&other.join(t));
            assert!(want.equals_missing(&got), "{t} differs in {other:?}");
        }
    }
    // `sweep` above ran with --no-plot; `plot` draws the map with its axes.
    assert!(run(&["plot", single.to_str().unwrap()]).status.success());
    assert!(single.join("phase_map.png").exists());
}

/// A spec with a two-axis grid of the reduced model, the one the bad axes change.
const GOOD_AXES: &str = "model: ode\ngrid:\n  mass: [0.05, 0.1]\n  eta_t: [0.08, 0.09]\n";

/// Bad axes: `(what, spec, the key named, what the message says)`. Unknown, doubled, too
/// many or none.
fn bad_axis_names() -> Vec<(&'static str, String, &'static str, &'static str)> {
    let good = GOOD_AXES;
    vec![
        (
            "unknown axis",
            good.replace("mass:", "massive:"),
            "grid.massive",
            "eta2",
        ),
        (
            "also fixed",
            format!("{good}params: {{mass: 0.1}}\n"),
            "grid.mass",
            "not both",
        ),
        (
            "also fixed in solver",
            format!("{good}solver: {{t_max: 100}}\n").replace("mass:", "t_max:"),
            "grid.t_max",
            "not both",
        ),
        (
            "four axes",
            format!("{good}  kappa2: [0.1]\n  eta2: [0.1]\n"),
            "grid",
            "one to three axes",
        ),
        (
            "no axis",
            "model: ode\ngrid: {}\n".to_string(),
            "grid",
            "one to three",
        ),
    ]
}

/// Bad axes: values out of range, and refinement on axes it cannot take.
fn bad_axis_values() -> Vec<(&'static str, String, &'static str, &'static str)> {
    let good = GOOD_AXES;
    vec![
        (
            "non-positive eta2",
            good.replace("mass:", "eta2:").replace("0.05", "0"),
            "grid.eta2",
            "> 0",
        ),
        (
            "negative mass",
            good.replace("0.05", "-0.05"),
            "grid.mass",
            ">= 0",
        ),
        (
            "overdamped with the Newton finish",
            "grid:\n  mass: [0, 0.1]\n".to_string(),
            "grid.mass",
            "steady: test",
        ),
        (
            "odd n",
            "grid:\n  n: [64, 65]\n".to_string(),
            "grid.n",
            "even",
        ),
        (
            "fractional n",
            "grid:\n  n: [64.5]\n".to_string(),
            "grid.n",
            "integers",
        ),
        (
            "sigma beyond R/4 at one end",
            "grid:\n  sigma: [0.03, 0.3]\n".to_string(),
            "grid.sigma",
            "R/4",
        ),
        (
            "refine on a list",
            format!("{good}refine: {{levels: 1}}\n"),
            "grid.mass",
            "range",
        ),
        (
            "refine on one axis",
            "model: ode\ngrid:\n  mass: {start: 0.1, stop: 0.3, step: 0.1}\nrefine: {levels: 1}\n"
                .to_string(),
            "refine",
            "two",
        ),
    ]
}

#[test]
fn bad_axes_exit_2_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [bad_axis_names(), bad_axis_values()].concat();
    for (what, text, key, says) in cases {
        let spec = write_spec(dir.path(), "bad.yaml", &text);
        let out = dir.path().join("never");
        let o = run(&[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{what}: {err}");
        assert!(
            err.contains(&format!("`{key}`")),
            "{what}: lacks `{key}`: {err}"
        );
        assert!(err.contains(says), "{what}: lacks {says:?}: {err}");
        assert!(!out.exists(), "{what}: wrote output");
    }
}
