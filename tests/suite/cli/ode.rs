//! The reduced model from the CLI: its coefficients, an ODE sweep, its bifurcation diagram
//! and the h0 fit.
use crate::common::{json, read, run, write_spec};

#[test]
fn ode_coefficients_json_has_the_paper_values() {
    let j = json(&run(&["ode", "coefficients", "--json"]));
    for (key, value, tol) in [
        ("f1", 0.07812, 5e-6),
        ("f1t", 0.05980, 5e-6),
        ("f3", 0.01150, 5e-6),
        ("g0t", 0.1196, 5e-5),
        ("g2", 0.006909, 5e-7),
        ("g2t", 0.01487, 5e-6),
        ("f3t", 0.004781, 5e-7),
    ] {
        let got = j[key].as_f64().unwrap();
        assert!((got - value).abs() < tol, "{key}: {got}");
    }
    assert_eq!(
        run(&["ode", "coefficients", "--radius", "-1"])
            .status
            .code(),
        Some(2)
    );
}

#[test]
fn ode_sweep_bifurcation_and_h0_fit_from_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    // An ODE phase map through the sweep engine, with the boundaries.
    let spec = write_spec(
        dir.path(),
        "ode.yaml",
        "model: ode\ngrid:\n  eta_t: {start: 0.07, stop: 0.10, step: 0.005}\n  kappa2: {start: 0.10, stop: 0.17, step: 0.01}\n",
    );
    let out = dir.path().join("ode");
    let s = json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(s["runs"], 7 * 8 * 4);
    let points = read(&out.join("points.parquet"));
    let classes = points.column("class").unwrap().str().unwrap();
    let labels: std::collections::BTreeSet<&str> = (0..points.height())
        .filter_map(|i| classes.get(i))
        .collect();
    for want in ["IC", "ID", "MD", "IC/MD"] {
        assert!(labels.contains(want), "{want} missing from {labels:?}");
    }
    assert!(read(&out.join("boundaries.parquet")).height() > 100);
    assert!(out.join("phase_map.png").exists());
    let runs = read(&out.join("runs.parquet"));
    assert_eq!(
        runs.column("model").unwrap().str().unwrap().get(0),
        Some("ode")
    );

    // A bifurcation diagram with its saddle-node (kappa2 = 0.13, subcritical drift pitchfork).
    let b = json(&run(&[
        "ode",
        "bifurcation",
        "--kappa2",
        "0.13",
        "--from",
        "0.07",
        "--to",
        "0.10",
        "--out",
        dir.path().to_str().unwrap(),
        "--json",
    ]));
    let events = b["events"].as_array().unwrap();
    assert!(
        events
            .iter()
            .any(|e| e["kind"] == "SN" && (e["at"].as_f64().unwrap() - 0.0821).abs() < 0.001),
        "{events:?}"
    );

    // The Appendix E fit at N = 128 (fast) lands near the paper's p0 = 0.1184, p2 = 0.1436.
    let f = json(&run(&[
        "fit-h0",
        "--n",
        "128",
        "--out",
        dir.path().join("h0").to_str().unwrap(),
        "--json",
    ]));
    let (p0, p2) = (f["p0"].as_f64().unwrap(), f["p2"].as_f64().unwrap());
    assert!(
        (p0 - 0.1184).abs() < 0.001 && (p2 - 0.1436).abs() < 0.005,
        "p0 {p0} p2 {p2}"
    );
}
