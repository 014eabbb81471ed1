//! Sweeps in any parameter: one and two axes of the reduced model (fast), a small PDE sweep in
//! `(mass, kappa2)` resumed after kills and run in shards, and the refusals of bad axes.
use crate::common::{droplet, json, kill_at_random_moments, read, run, sweep};
use crate::common::{table_without_wall, write_spec};
use std::process::Stdio;

/// The column `name` of a table as floats.
pub(crate) fn floats(df: &polars::prelude::DataFrame, name: &str) -> Vec<f64> {
    let c = df.column(name).unwrap().f64().unwrap().clone();
    (0..c.len()).map(|i| c.get(i).unwrap()).collect()
}

fn columns(df: &polars::prelude::DataFrame) -> Vec<String> {
    df.get_column_names()
        .iter()
        .map(|c| c.to_string())
        .collect()
}

/// `droplet sweep SPEC --out OUT --json`, pictures included: its JSON.
fn sweep_with_pictures(spec: &std::path::Path, out: &std::path::Path) -> serde_json::Value {
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

/// The full model's onset of motion in a boundaries table over a sweep in (`other`, eta_t):
/// its `eta_t` and `other` values.
fn onset_of_motion(path: &std::path::Path, other: &str) -> (Vec<f64>, Vec<f64>) {
    let b = read(path);
    let curve = b.column("curve").unwrap().str().unwrap().clone();
    let model = b.column("model").unwrap().str().unwrap().clone();
    let (eta, o) = (floats(&b, "eta_t"), floats(&b, other));
    (0..b.height())
        .filter(|&i| curve.get(i) == Some("IC onset of motion") && model.get(i) == Some("pde"))
        .map(|i| (eta[i], o[i]))
        .unzip()
}

/// The points of the full model's curve `name` in a boundaries table, in the plane `(x, y)`.
fn pde_curve(path: &std::path::Path, name: &str, (x, y): (&str, &str)) -> Vec<(f64, f64)> {
    let b = read(path);
    let curve = b.column("curve").unwrap().str().unwrap().clone();
    let model = b.column("model").unwrap().str().unwrap().clone();
    let (xs, ys) = (floats(&b, x), floats(&b, y));
    (0..b.height())
        .filter(|&i| curve.get(i) == Some(name) && model.get(i) == Some("pde"))
        .map(|i| (xs[i], ys[i]))
        .collect()
}

/// A one-IC ODE sweep `name` of `body` (its `params` and `grid`) in `dir`, then `droplet
/// boundaries` over it at grid size `n`: the sweep's directory and the JSON, whose plane must be
/// `plane`.
fn boundaries_over(
    dir: &std::path::Path,
    name: &str,
    body: &str,
    n: &str,
    plane: (&str, &str),
) -> (std::path::PathBuf, serde_json::Value) {
    let spec = write_spec(
        dir,
        &format!("{name}.yaml"),
        &format!("model: ode\n{body}initial_conditions: [i]\n"),
    );
    let out = dir.join(name);
    sweep_with_pictures(&spec, &out);
    let b = json(&run(&[
        "boundaries",
        "--out",
        out.to_str().unwrap(),
        "--n",
        n,
        "--json",
    ]));
    assert_eq!(b["plane"], serde_json::json!([plane.0, plane.1]), "{b}");
    (out, b)
}

/// The MD fold of the branch followed in `eta_t` from 0.07 to 0.09 (`droplet continue`, an
/// independent computation) at the parameters `set`, with the options `extra`.
fn md_fold_along_eta_t(set: &str, extra: &[&str]) -> f64 {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("md");
    let mut args = vec![
        "continue",
        "--param",
        "eta_t",
        "--from",
        "0.07",
        "--to",
        "0.09",
        "--set",
        set,
        "--branch",
        "md",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    let c = json(&run(&args));
    let sn = c["events"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["kind"] == "SN");
    sn.unwrap_or_else(|| panic!("no fold: {c}"))["at"]
        .as_f64()
        .unwrap()
}

/// The resting disk's onset of motion at a point, from `droplet stability` (an independent
/// computation: one linearisation, no tracing).
fn disk_onset(eta_t: f64, kappa2: f64, set: &str, n: &str) -> f64 {
    let s = json(&run(&[
        "stability",
        "--eta-t",
        &eta_t.to_string(),
        "--kappa2",
        &kappa2.to_string(),
        "--state",
        "ic",
        "--set",
        set,
        "--n",
        n,
        "--json",
    ]));
    s["ic_thresholds"]["eta_t"].as_f64().unwrap()
}

#[test]
fn boundaries_over_a_radius_eta_t_sweep_are_continued_in_the_pair() {
    // Radius moves the states: the curves are continued in (radius, eta_t) itself. At R = 1
    // the onset of motion is the paper plane's; at every point it is the disk's threshold.
    // kappa2 = 0.16, where the onset is a supercritical pitchfork: no MD fold to trace
    // (at kappa2 = 0.13 the fold's curve is three quarters of the cost).
    let dir = tempfile::tempdir().unwrap();
    let (out, _) = boundaries_over(
        dir.path(),
        "re",
        "params: {kappa2: 0.16}\ngrid:\n  radius: [0.95, 1.0, 1.05]\n  eta_t: [0.07, 0.08, 0.09]\n",
        "96",
        ("radius", "eta_t"),
    );
    let table = out.join("boundaries.parquet");
    let onset = pde_curve(&table, "IC onset of motion", ("radius", "eta_t"));
    assert!(onset.len() > 5, "{onset:?}");
    // Across the window from radius 0.95 to 1.05, the threshold growing with the radius.
    let first = onset.first().unwrap();
    let last = onset.last().unwrap();
    assert!(
        (first.0 - 0.95).abs() < 1e-9 && (last.0 - 1.05).abs() < 1e-9,
        "{onset:?}"
    );
    assert!(onset.windows(2).all(|w| w[1].1 > w[0].1), "{onset:?}");
    let paper = dir.path().join("paper");
    let p = json(&run(&[
        "boundaries",
        "--out",
        paper.to_str().unwrap(),
        "--eta-t",
        "0.07,0.09",
        "--kappa2",
        "0.15,0.17",
        "--n",
        "96",
        "--json",
    ]));
    let at_one = p["curves"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["curve"] == "IC onset of motion" && c["model"] == "pde")
        .map(|c| c["eta_t"][0].as_f64().unwrap())
        .unwrap();
    let w = onset
        .windows(2)
        .find(|w| w[0].0 <= 1.0 && w[1].0 >= 1.0)
        .unwrap();
    let crossing = w[0].1 + (w[1].1 - w[0].1) * (1.0 - w[0].0) / (w[1].0 - w[0].0);
    assert!((crossing - at_one).abs() < 1e-6, "{crossing} vs {at_one}");
    let (r, e) = onset[onset.len() / 2];
    let th = disk_onset(e, 0.16, &format!("radius={r}"), "96");
    assert!((th - e).abs() < 1e-8, "{th} vs {e} at R = {r}");
    // The reduced model's curves are where its boundaries cross the line at each radius.
    let b = read(&table);
    let model = b.column("model").unwrap().str().unwrap().clone();
    assert!((0..b.height()).any(|i| model.get(i) == Some("ode")));
    assert!(out.join("phase_map.png").exists());
}

#[test]
fn boundaries_in_a_plane_of_two_non_paper_parameters_are_continued_in_it() {
    // (radius, sigma) at eta_t = 0.077, kappa2 = 0.14: the disk starts to move where its
    // threshold reaches 0.077 (R near 1.02), and the MD fold crosses the window too. N = 96
    // (half the cost of N = 128); at kappa2 = 0.13 the coarse grid's anisotropy would bring
    // the disk's axis deformation onset into the window as well.
    let dir = tempfile::tempdir().unwrap();
    let (out, b) = boundaries_over(
        dir.path(),
        "rs",
        "params: {eta_t: 0.077, kappa2: 0.14}\ngrid:\n  radius: [0.95, 1.0, 1.05]\n  sigma: [0.03, 0.04, 0.05]\n",
        "96",
        ("radius", "sigma"),
    );
    let names: Vec<&str> = b["curves"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["curve"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["IC onset of motion", "MD saddle-node (x axis)"],
        "{b}"
    );
    let table = out.join("boundaries.parquet");
    let onset = pde_curve(&table, "IC onset of motion", ("radius", "sigma"));
    // From the bottom edge to the top one.
    let (first, last) = (onset[0], *onset.last().unwrap());
    assert!(
        (first.1 - 0.03).abs() < 1e-9 && (last.1 - 0.05).abs() < 1e-9,
        "{onset:?}"
    );
    // Each of three points is where the disk's own threshold is 0.077.
    for &(r, s) in [first, onset[onset.len() / 2], last].iter() {
        let th = disk_onset(0.077, 0.14, &format!("radius={r},sigma={s}"), "96");
        assert!((th - 0.077).abs() < 1e-8, "{th} at R = {r}, sigma = {s}");
    }
    let fold = pde_curve(&table, "MD saddle-node (x axis)", ("radius", "sigma"));
    assert!(
        fold.len() > 5 && fold.iter().all(|p| p.0 < first.0),
        "{fold:?}"
    );
    // A point of it is where the MD branch followed in eta_t at that (radius, sigma) folds.
    let (r, s) = fold[fold.len() / 2];
    let at = md_fold_along_eta_t(&format!("kappa2=0.14,radius={r},sigma={s}"), &["--n", "96"]);
    assert!(
        (at - 0.077).abs() < 1e-6,
        "fold at eta_t = {at}, R = {r}, sigma = {s}"
    );
    // No reduced-model curve: it has no sigma.
    let t = read(&table);
    let model = t.column("model").unwrap().str().unwrap().clone();
    assert!((0..t.height()).all(|i| model.get(i) == Some("pde")));
    // Traced with two shape modes only: more are refused before anything is computed, and
    // the table stays the 2-mode one.
    let before = std::fs::read(&table).unwrap();
    let o = run(&[
        "boundaries",
        "--out",
        out.to_str().unwrap(),
        "--modes",
        "3",
        "--n",
        "96",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("`modes` = 3") && err.contains("radius and sigma") && err.contains("2-mode"),
        "{err}"
    );
    assert_eq!(std::fs::read(&table).unwrap(), before);
}

#[test]
fn boundaries_over_an_n_eta_t_sweep_are_recomputed_at_each_n() {
    // The grid moves the boundaries a little: each is computed again at each of the sweep's
    // N, and the onset of motion at each N is the disk's own threshold there.
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "ne.yaml",
        // Short PDE runs: the boundaries need the sweep's plane, not settled runs.
        "params: {kappa2: 0.13}\ngrid:\n  n: [96, 128]\n  eta_t: [0.07, 0.08, 0.09]\ninitial_conditions: [i]\nsolver: {t_max: 1, run_on: false}\n",
    );
    let out = dir.path().join("ne");
    sweep_with_pictures(&spec, &out);
    let b = json(&run(&[
        "boundaries",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(b["plane"], serde_json::json!(["n", "eta_t"]), "{b}");
    let onset = pde_curve(
        &out.join("boundaries.parquet"),
        "IC onset of motion",
        ("n", "eta_t"),
    );
    assert_eq!(onset.iter().map(|p| p.0).collect::<Vec<_>>(), [96.0, 128.0]);
    for &(n, e) in &onset {
        let th = disk_onset(0.08, 0.13, "radius=1", &n.to_string());
        assert!((th - e).abs() < 1e-9, "N = {n}: {e} vs {th}");
    }
    assert_ne!(onset[0].1, onset[1].1);
}

#[test]
fn a_three_axis_ode_sweep_draws_one_map_per_slice_and_one_with_all() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "three.yaml",
        "model: ode\ngrid:\n  mass: [0.02, 0.3]\n  eta_t: {start: 0.07, stop: 0.1, step: 0.01}\n  kappa2: [0.11, 0.15]\ninitial_conditions: [i, iii]\n",
    );
    let out = dir.path().join("three");
    let s = sweep_with_pictures(&spec, &out);
    assert_eq!(s["runs"], 2 * 4 * 2 * 2, "{s}");
    let points = read(&out.join("points.parquet"));
    let cols = columns(&points);
    assert_eq!(&cols[1..4], ["mass", "eta_t", "kappa2"], "{cols:?}");
    // Slice-major: the first slice's 8 points, then the second's.
    let kappa = floats(&points, "kappa2");
    assert!(kappa[..8].iter().all(|&k| k == 0.11) && kappa[8..].iter().all(|&k| k == 0.15));
    // The runs carry all three coordinates.
    let runs = read(&out.join("runs.parquet"));
    let point = runs.column("point").unwrap().u32().unwrap().clone();
    let (pm, pe) = (floats(&points, "mass"), floats(&points, "eta_t"));
    let (rm, re, rk) = (
        floats(&runs, "mass"),
        floats(&runs, "eta_t"),
        floats(&runs, "kappa2"),
    );
    for i in 0..runs.height() {
        let p = point.get(i).unwrap() as usize;
        assert_eq!((rm[i], re[i], rk[i]), (pm[p], pe[p], kappa[p]));
    }
    for f in [
        "phase_map.png",
        "phase_map.svg",
        "phase_map_kappa2_0.11.png",
        "phase_map_kappa2_0.15.svg",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    // Status from the store and from the tables alone, and the pictures redrawn.
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    assert_eq!(st["points"].as_u64(), Some(16), "{st}");
    std::fs::remove_dir_all(out.join("runs")).unwrap();
    std::fs::remove_file(out.join("phase_map_kappa2_0.15.png")).unwrap();
    let o = run(&["plot", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("phase_map_kappa2_0.15.png").exists());
    // Boundaries are drawn in planes of two parameters, not over slices.
    let o = run(&["boundaries", "--out", out.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("(mass, eta_t, kappa2)"));
}

#[test]
fn a_refined_three_axis_ode_sweep_refines_each_slice_on_its_own_and_resumes_equal() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "three-r.yaml",
        "model: ode\ngrid:\n  mass: {start: 0.02, stop: 0.32, step: 0.1}\n  eta_t: {start: 0.07, stop: 0.1, step: 0.01}\n  kappa2: [0.11, 0.15]\ninitial_conditions: [i, iii]\nrefine: {levels: 2}\n",
    );
    let out = dir.path().join("r");
    assert!(sweep(&spec, &out, &[]).status.success());
    let points = read(&out.join("points.parquet"));
    let (kappa, level) = (
        floats(&points, "kappa2"),
        points.column("level").unwrap().u32().unwrap().clone(),
    );
    // Each slice has its 4 x 4 level-0 points, and its own refined ones.
    for k in [0.11, 0.15] {
        let mine: Vec<u32> = (0..points.height())
            .filter(|&i| kappa[i] == k)
            .map(|i| level.get(i).unwrap())
            .collect();
        assert_eq!(mine.iter().filter(|&&l| l == 0).count(), 16, "{k}");
        assert!(mine.iter().any(|&l| l > 0), "slice {k} was not refined");
    }
    // The two slices differ (ID at the top of 0.11 only): each is refined where it changes.
    let (m, e) = (floats(&points, "mass"), floats(&points, "eta_t"));
    let refined = |k: f64| {
        (0..points.height())
            .filter(|&i| kappa[i] == k && level.get(i).unwrap() > 0)
            .map(|i| (m[i].to_bits(), e[i].to_bits()))
            .collect::<std::collections::BTreeSet<_>>()
    };
    assert_ne!(refined(0.11), refined(0.15));
    // A second sweep into its own directory gives equal tables; with half of its runs
    // removed, a third recomputes exactly those.
    let again = dir.path().join("again");
    assert!(sweep(&spec, &again, &[]).status.success());
    for t in ["runs.parquet", "points.parquet"] {
        let (a, b) = (
            table_without_wall(&out.join(t)),
            table_without_wall(&again.join(t)),
        );
        assert!(a.equals_missing(&b), "{t} differs");
    }
    let files: Vec<_> = std::fs::read_dir(again.join("runs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    for f in files.iter().step_by(2) {
        std::fs::remove_file(f).unwrap();
    }
    let done = json(&sweep(&spec, &again, &[]));
    assert_eq!(
        done["computed"].as_u64().unwrap() as usize,
        files.len().div_ceil(2),
        "{done}"
    );
    for t in ["runs.parquet", "points.parquet"] {
        let (a, b) = (
            table_without_wall(&out.join(t)),
            table_without_wall(&again.join(t)),
        );
        assert!(a.equals_missing(&b), "{t} differs after the resume");
    }
    let st = json(&run(&["status", again.to_str().unwrap(), "--json"]));
    assert_eq!(st["levels"].as_array().unwrap().len(), 3, "{st}");
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

#[test]
fn bad_axes_exit_2_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let good = "model: ode\ngrid:\n  mass: [0.05, 0.1]\n  eta_t: [0.08, 0.09]\n";
    let cases = [
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
    ];
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
