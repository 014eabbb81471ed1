//! Boundaries over sweeps in other planes than the paper's: continued in a pair of model
//! parameters (`radius`, `eta_t`; two non-paper parameters) and recomputed at each grid size
//! of an `(n, eta_t)` sweep.
use crate::cli::axes::{floats, sweep_with_pictures};
use crate::common::{json, read, run, write_spec};

/// The full model's onset of motion in a boundaries table over a sweep in (`other`, eta_t):
/// its `eta_t` and `other` values.
pub(crate) fn onset_of_motion(path: &std::path::Path, other: &str) -> (Vec<f64>, Vec<f64>) {
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
pub(crate) fn md_fold_along_eta_t(set: &str, extra: &[&str]) -> f64 {
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
