//! `droplet simulate --modes K`: single runs of the model with shape modes 2..K from the
//! command line: the picture with every mode, a run that leaves the model, the saddle stop and
//! the leap.
use crate::common::{json, run};

#[test]
fn a_k_mode_run_draws_its_picture_with_every_mode() {
    // Fig. 1c with modes 2..3 at N = 96: the run ends MD and draws its panels (PNG and SVG),
    // listed in the JSON.
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("md3.png");
    let out = json(&run(&[
        "simulate",
        "--eta-t",
        "0.085",
        "--kappa2",
        "0.112",
        "--ic",
        "i",
        "--modes",
        "3",
        "--n",
        "96",
        "--dt",
        "0.05",
        "--t-max",
        "400",
        "--json",
        "--picture",
        png.to_str().unwrap(),
    ]));
    assert_eq!(out["class"], "MD", "{out}");
    let files: Vec<&str> = out["picture"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_str().unwrap())
        .collect();
    assert_eq!(files.len(), 2, "{out}");
    assert!(files.iter().any(|f| f.ends_with(".svg")), "{files:?}");
    for f in files {
        assert!(std::fs::metadata(f).unwrap().len() > 10_000, "{f}");
    }
}

#[test]
fn a_k_mode_droplet_whose_boundary_reaches_its_centre_has_diverged() {
    // At (0.084, 0.1) from the resting start iii, modes 2..6 stretch the droplet without
    // bound (a2, a4 and a6 grow together; with modes 2..4 it starts to move instead): the run
    // ends `diverged` once its boundary f(theta) reaches the centre, at t ~ 10, instead of
    // stepping on at ever smaller steps.
    let end = |modes: &str| {
        json(&run(&[
            "simulate", "--eta-t", "0.084", "--kappa2", "0.1", "--ic", "iii", "--modes", modes,
            "--n", "96", "--json",
        ]))
    };
    let six = end("6");
    assert_eq!(six["status"], "diverged", "{six}");
    assert_eq!(six["unsettled"], "diverged", "{six}");
    assert!(six["class"].is_null(), "{six}");
    let t = six["t_end"].as_f64().unwrap();
    assert!(t > 5.0 && t < 15.0, "{six}");
    // Every amplitude below 1 at the end, yet the boundary has reached the centre.
    let amp = |key: &str| -> Vec<f64> {
        six[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (a, b) = (amp("a_k"), amp("b_k"));
    assert!(a.iter().chain(&b).all(|c| c.abs() < 1.0), "{six}");
    let smallest = (0..3600)
        .map(|i| {
            let th = std::f64::consts::TAU * i as f64 / 3600.0;
            1.0 + (0..a.len())
                .map(|j| {
                    let k = (j + 2) as f64;
                    a[j] * (k * th).cos() + b[j] * (k * th).sin()
                })
                .sum::<f64>()
        })
        .fold(f64::INFINITY, f64::min);
    assert!(smallest < 0.05, "smallest radius {smallest}: {six}");
    let four = end("4");
    assert_eq!(four["status"], "steady", "{four}");
    assert_eq!(four["class"], "MD", "{four}");
}

#[test]
fn a_k_mode_run_takes_the_saddle_stop_and_the_leap_from_the_command_line() {
    // Modes 2..4, N = 96: beside the diagonal's resting deformed state at (0.08725, 0.115)
    // (drift growing at 1e-3, not left before t_max) --stop-beside-saddle stops the run
    // early, status `saddle`; leaving the disk at (0.07625, 0.14) from iii, --leap-departures
    // leaps over the departure and ends on the MD state the stepped run reaches.
    let at = |eta_t: &str, kappa2: &str, ic: &str, extra: &[&str]| {
        let mut args = vec![
            "simulate",
            "--eta-t",
            eta_t,
            "--kappa2",
            kappa2,
            "--ic",
            ic,
            "--modes",
            "4",
            "--n",
            "96",
            "--no-landing",
            "--json",
        ];
        args.extend_from_slice(extra);
        json(&run(&args))
    };
    let stopped = at(
        "0.08725",
        "0.115",
        "iv",
        &["--no-run-on", "--stop-beside-saddle"],
    );
    assert_eq!(stopped["status"], "saddle", "{stopped}");
    assert_eq!(stopped["unsettled"], "beside_saddle", "{stopped}");
    assert!(stopped["t_end"].as_f64().unwrap() < 1000.0, "{stopped}");
    let leapt = at(
        "0.07625",
        "0.14",
        "iii",
        &["--t-max", "4000", "--leap-departures"],
    );
    let stepped = at("0.07625", "0.14", "iii", &["--t-max", "4000"]);
    assert!(leapt["t_leapt"].as_f64().unwrap() > 500.0, "{leapt}");
    for out in [&leapt, &stepped] {
        assert_eq!(out["class"], "MD", "{out}");
    }
    let v = |o: &serde_json::Value| o["v"].as_f64().unwrap();
    assert!((v(&leapt) - v(&stepped)).abs() < 1e-9, "{leapt} {stepped}");
}
