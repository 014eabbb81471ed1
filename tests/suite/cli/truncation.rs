//! `droplet truncation`: the K-mode model's results against the 2-mode commands
//! (`stability`, `continue`) at K = 2, and what the third mode changes.
use crate::cli::axes::floats;
use crate::common::{json, read, run};

/// `droplet stability ARGS --json`.
pub(crate) fn stability(args: &[&str]) -> serde_json::Value {
    let all: Vec<&str> = std::iter::once("stability")
        .chain(args.iter().copied())
        .chain(["--json"])
        .collect();
    json(&run(&all))
}

/// The names of the full model's curves in a `boundaries --json` report, in its order.
pub(crate) fn pde_curves(b: &serde_json::Value) -> Vec<&str> {
    b["curves"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["model"] == "pde")
        .map(|c| c["curve"].as_str().unwrap())
        .collect()
}

/// Runs `base` followed by each case's arguments: each must exit 2 with a message that holds
/// the case's text.
pub(crate) fn refused(base: &[&str], cases: &[(&[&str], &str)]) {
    for (args, says) in cases {
        let all: Vec<&str> = base.iter().chain(args.iter()).copied().collect();
        let o = run(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

/// Each K's fold curve of a `truncation` in `out` (its `rows`), continued in (eta_t,
/// kappa2), crosses kappa2 = 0.13 where the branch followed in eta_t folds (two
/// computations).
fn fold_curves_cross_where_the_branches_fold(out: &std::path::Path, rows: &[serde_json::Value]) {
    let f = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap();
    let b = read(&out.join("truncation_boundaries.parquet"));
    let curve = b.column("curve").unwrap().str().unwrap().clone();
    let (e, k) = (floats(&b, "eta_t"), floats(&b, "kappa2"));
    for row in rows {
        let name = format!("K = {}: MD saddle-node (x axis)", row["k_max"]);
        let pts: Vec<(f64, f64)> = (0..b.height())
            .filter(|&i| curve.get(i) == Some(name.as_str()))
            .map(|i| (e[i], k[i]))
            .collect();
        let w = pts
            .windows(2)
            .find(|w| (w[0].1 - 0.13) * (w[1].1 - 0.13) <= 0.0)
            .unwrap_or_else(|| panic!("{name}: {pts:?}"));
        let at = w[0].0 + (w[1].0 - w[0].0) * (0.13 - w[0].1) / (w[1].1 - w[0].1);
        assert!(
            (at - f(row, "fold_eta_t")).abs() < 2e-5,
            "{name}: {at} vs {row}"
        );
    }
}

#[test]
fn two_modes_are_the_two_mode_commands_and_a_third_changes_the_moving_state() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("trunc");
    // The boundaries in a window around the band's line (kappa2 = 0.13), where the fold
    // curves are checked: the full Fig. 2a window traces every curve at 4x the cost.
    let t = json(&run(&[
        "truncation",
        "--modes",
        "2,3",
        "--n",
        "96",
        "--eta-t",
        "0.075,0.085",
        "--kappa2",
        "0.125,0.135",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]));
    assert_eq!(t["kappa2"], serde_json::json!([0.125, 0.135]), "{t}");
    let rows = t["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2, "{t}");
    let (two, three) = (&rows[0], &rows[1]);
    let f = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap();
    // K = 2: the 2-mode model's MD state, onset of motion and fold, by other code paths.
    let md = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.112", "--state", "md", "--n", "96",
    ]);
    assert!((f(two, "v") - f(&md, "v")).abs() < 1e-8, "{two} {md}");
    assert!((f(two, "s") - f(&md, "s")).abs() < 1e-8, "{two} {md}");
    // ... with its stability: the same eigenvalues from the 2K x 2K problem.
    assert_eq!(two["stable"], md["stable"], "{two} {md}");
    for (a, b) in two["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .zip(md["eigenvalues"].as_array().unwrap())
    {
        assert!(
            (a[0].as_f64().unwrap() - f(b, "re")).abs() < 1e-7,
            "{two} {md}"
        );
    }
    // The 3-mode state is stable too (the rotation mode aside).
    assert_eq!(three["stable"], true, "{three}");
    let ic = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.13", "--state", "ic", "--n", "96",
    ]);
    let onset = ic["ic_thresholds"]["eta_t"].as_f64().unwrap();
    assert!(
        (f(two, "onset_eta_t") - onset).abs() < 1e-7,
        "{two} {onset}"
    );
    let c = json(&run(&[
        "continue", "--branch", "md", "--kappa2", "0.13", "--from", "0.07", "--to", "0.1", "--n",
        "96", "--json",
    ]));
    let sn = c["events"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["kind"] == "SN")
        .unwrap();
    assert!(
        (f(two, "fold_eta_t") - f(sn, "at")).abs() < 1e-7,
        "{two} {sn}"
    );
    // K = 3: a front-back asymmetric droplet (a3 != 0 on its axis of motion), another speed,
    // and the fold moved.
    let a3 = three["a"][1].as_f64().unwrap();
    assert!(a3.abs() > 1e-2, "{three}");
    assert!((f(three, "v") - f(two, "v")).abs() > 1e-2, "{three}");
    assert!(
        (f(three, "fold_eta_t") - f(two, "fold_eta_t")).abs() > 1e-4,
        "{three}"
    );
    for file in [
        "truncation.parquet",
        "truncation.png",
        "truncation.svg",
        "truncation_boundaries.parquet",
        "truncation_boundaries.png",
    ] {
        assert!(out.join(file).exists(), "{file}");
    }
    fold_curves_cross_where_the_branches_fold(&out, rows);
}

#[test]
fn bad_modes_exit_2_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t");
    let out = out.to_str().unwrap();
    refused(
        &["truncation", "--out", out],
        &[
            (&["--modes", "1", "--n", "96"], "modes"),
            (&["--modes", "0", "--n", "96"], "modes"),
            (&["--modes", "2,2", "--n", "96"], "--modes"),
            (&["--modes", "2,x", "--n", "96"], "--modes"),
            (&["--modes", "17", "--n", "192"], "modes"),
            (&["--modes", "8", "--n", "64"], "at most 7 at N = 64"),
        ],
    );
}

#[test]
fn stability_with_modes_gives_the_k_mode_state_and_its_verdict() {
    // The Fig. 1c state with modes 2..3, as `droplet truncation` finds it, and stable.
    let s = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.112", "--state", "md", "--modes", "3", "--n", "96",
    ]);
    assert_eq!(s["modes"], 3, "{s}");
    let a = s["a_k"].as_array().unwrap();
    assert_eq!(a.len(), 2, "{s}");
    assert!(a[1].as_f64().unwrap().abs() > 1e-2, "{s}");
    assert_eq!(s["stable"], true, "{s}");
    assert!(s["rotation"].is_f64(), "{s}");
    // From a seed (v, a2) near it, mode 3 started from 0: the same state; on the diagonal
    // the seed is solved there on all six balances, a state of its own (the box's).
    let base = [
        "--eta-t", "0.085", "--kappa2", "0.112", "--state", "md", "--modes", "3", "--n", "96",
    ];
    let seeded = |extra: &[&str]| {
        let all: Vec<&str> = base.iter().chain(extra).copied().collect();
        stability(&all)
    };
    let x = seeded(&["--seed", "0.35,-0.2"]);
    assert!(
        (x["v"].as_f64().unwrap() - s["v"].as_f64().unwrap()).abs() < 1e-8,
        "{x}"
    );
    let diagonal = seeded(&["--seed", "0.35,-0.2", "--axis", "diagonal"]);
    let (vx, vy) = (
        diagonal["vx"].as_f64().unwrap(),
        diagonal["vy"].as_f64().unwrap(),
    );
    assert!((vx - vy).abs() < 1e-9 && vx > 0.1, "{diagonal}");
    assert!(diagonal["residual"].as_f64().unwrap() < 1e-10, "{diagonal}");
    // With the friction law eta_k = (2/k) eta2: the same state, other eigenvalues (eta_k
    // enters only how fast the shape moves); with two modes the law is refused.
    let law = stability(&[
        "--eta-t",
        "0.085",
        "--kappa2",
        "0.112",
        "--state",
        "md",
        "--modes",
        "3",
        "--n",
        "96",
        "--eta-k-exponent",
        "-1",
    ]);
    assert_eq!(law["v"], s["v"], "{law}");
    assert_eq!(
        (law["eta_k_exponent"].as_f64(), s["eta_k_exponent"].as_f64()),
        (Some(-1.0), Some(0.0))
    );
    assert_ne!(law["eigenvalues"], s["eigenvalues"], "{law}");
    let o = run(&[
        "stability",
        "--eta-t",
        "0.085",
        "--kappa2",
        "0.112",
        "--state",
        "md",
        "--n",
        "96",
        "--eta-k-exponent",
        "-1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("eta_k_exponent"), "{err}");
    refused(
        &["stability", "--eta-t", "0.085", "--kappa2", "0.112"],
        &[
            (&["--modes", "1"], "modes"),
            (&["--modes", "8", "--n", "64"], "modes"),
        ],
    );
}

#[test]
fn the_resting_disk_has_each_modes_onset_and_two_modes_name_their_mode_alike() {
    // The resting disk: round but for the box's square symmetry (a4 small), with each
    // mode's onset.
    let ic = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.13", "--state", "ic", "--modes", "4", "--n", "96",
    ]);
    let a4 = ic["a_k"][2].as_f64().unwrap();
    assert!(a4.abs() > 0.0 && a4.abs() < 2e-3, "{ic}");
    assert_eq!(
        ic["ic_thresholds"]["kappa2_a"].as_array().unwrap().len(),
        3,
        "{ic}"
    );
    // The 2-mode report names its one mode the same way.
    let two = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.112", "--state", "md", "--n", "96",
    ]);
    assert_eq!(two["modes"], 2, "{two}");
    assert_eq!(two["a_k"][0], two["a2"], "{two}");
}

#[test]
fn the_three_mode_md_state_on_the_diagonal_is_where_a_run_started_on_it_ends() {
    // The MD state on the diagonal with 3 modes: on the mirror line (vx = vy; mode 2 along
    // it, a2 = 0; mode 3 symmetric about it, b3 = -a3), the x-axis state but for the box's
    // anisotropy, and where a 3-mode run started on the diagonal ends (an independent
    // computation: time stepping and the Newton finish). At N = 128, where it is stable (at
    // N = 96 the box's anisotropy turns it unstable, at 192 only its rotation mode grows).
    let diag = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.112", "--state", "md", "--modes", "3", "--axis",
        "diagonal", "--n", "128",
    ]);
    let f = |key: &str, i: usize| diag[key][i].as_f64().unwrap();
    assert!(
        (diag["vx"].as_f64().unwrap() - diag["vy"].as_f64().unwrap()).abs() < 1e-9,
        "{diag}"
    );
    assert!(
        f("a_k", 0).abs() < 1e-9 && (f("a_k", 1) + f("b_k", 1)).abs() < 1e-9,
        "{diag}"
    );
    let axis = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.112", "--state", "md", "--modes", "3", "--n", "128",
    ]);
    let (vd, va) = (diag["v"].as_f64().unwrap(), axis["v"].as_f64().unwrap());
    assert!(vd != va && (vd - va).abs() < 0.05, "{diag} {axis}");
    let run_d = json(&run(&[
        "simulate",
        "--eta-t",
        "0.085",
        "--kappa2",
        "0.112",
        "--modes",
        "3",
        "--n",
        "128",
        "--dt",
        "0.05",
        "--t-max",
        "400",
        "--ic",
        "custom:0.2,0.2,0,-0.25",
        "--json",
    ]));
    assert_eq!(run_d["class"], "MD", "{run_d}");
    assert!(
        (run_d["v"].as_f64().unwrap() - vd).abs() < 1e-6,
        "{run_d} {diag}"
    );
    assert!(
        (run_d["a_k"][1].as_f64().unwrap() - f("a_k", 1)).abs() < 1e-6,
        "{run_d}"
    );
}
