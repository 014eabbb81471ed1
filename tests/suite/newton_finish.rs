//! `steady: newton` (the default) and `steady: test` end to end: no false steady state just
//! below the onset of motion, the paper's behaviour kept and flagged, the spec key.

use crate::common::{json, run, write_spec};

fn simulate(ic: &str, steady: &str) -> serde_json::Value {
    // N = 128: the onset of motion is at eta_t = 0.076486 (continuation), 0.0015 above; the
    // resting disk's drift grows at 0.0116 here (the Fig. 2b-iii point where the committed
    // time-stepped line shows a false IC/MD).
    json(&run(&[
        "simulate", "--eta-t", "0.075", "--kappa2", "0.16", "--n", "128", "--ic", ic, "--steady",
        steady, "--json",
    ]))
}

#[test]
fn no_run_ends_on_the_unstable_resting_disk_below_the_onset_of_motion() {
    for ic in ["i", "ii", "iii", "iv", "ii'"] {
        let out = simulate(ic, "newton");
        assert_eq!(out["status"], "steady", "{ic}: {out}");
        assert_eq!(out["class"], "MD", "{ic}: {out}");
    }
    // The paper's test alone stops the run from a small velocity (ii') on the resting disk,
    // and says that the state it stopped on is unstable.
    let paper = simulate("ii'", "test");
    assert_eq!(paper["status"], "steady", "{paper}");
    assert_eq!(paper["class"], "IC", "{paper}");
    assert_eq!(paper["ended_by"], "steady_by_test", "{paper}");
    assert_eq!(paper["final_state"]["stable"], false, "{paper}");
    assert!(paper["final_state"]["slowest_eigenvalue"].as_f64().unwrap() > 0.0);
}

#[test]
fn the_steady_key_is_read_checked_and_in_the_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = |steady: &str, scheme: &str| {
        format!(
            "name: k\ngrid:\n  eta_t: [0.09]\n  kappa2: [0.14]\ninitial_conditions: [i]\nsolver: {{scheme: {scheme}, n: 48, t_max: 200, steady: {steady}}}\n"
        )
    };
    let bad = write_spec(dir.path(), "bad.yaml", &spec("sometimes", "spectral"));
    let o = run(&[
        "sweep",
        bad.to_str().unwrap(),
        "--out",
        dir.path().join("b").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("solver.steady") && err.contains("newton"),
        "{err}"
    );
    let fd = write_spec(dir.path(), "fd.yaml", &spec("newton", "paper-fd"));
    let o = run(&[
        "sweep",
        fd.to_str().unwrap(),
        "--out",
        dir.path().join("f").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("steady") && err.contains("spectral"), "{err}");
    // Both methods run; their runs have different keys and say how they ended.
    for steady in ["test", "newton"] {
        let good = write_spec(
            dir.path(),
            &format!("{steady}.yaml"),
            &spec(steady, "spectral"),
        );
        let out = dir.path().join(steady);
        let o = run(&[
            "sweep",
            good.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let runs = crate::common::read(&out.join("runs.parquet"));
        let col = |name: &str| {
            runs.column(name)
                .unwrap()
                .str()
                .unwrap()
                .get(0)
                .map(str::to_string)
        };
        assert_eq!(col("steady").as_deref(), Some(steady));
        assert_eq!(
            col("ended_by").as_deref(),
            Some(if steady == "test" {
                "steady_by_test"
            } else {
                "steady_by_newton"
            })
        );
    }
}

/// The IC creeper of the refined map at (0.0875, 0.11875) from IC iv, N = 192: it sits beside
/// the unstable resting state (drift growing at 3.4e-4) and reaches `t_max` there.
fn creeper(extra: &[&str]) -> serde_json::Value {
    simulate_at("0.0875", "0.11875", "iv", extra)
}

/// `simulate --json` at `(eta_t, kappa2)` from `ic` with the defaults and `extra`.
fn simulate_at(eta_t: &str, kappa2: &str, ic: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "simulate", "--eta-t", eta_t, "--kappa2", kappa2, "--ic", ic, "--json",
    ];
    args.extend_from_slice(extra);
    json(&run(&args))
}

#[test]
fn a_run_beside_a_saddle_lands_on_its_attractor_or_stays_unsettled() {
    // With the defaults the slow flow lands it on the deformed resting state (the disk is
    // unstable to the diagonal deformation between the two deformation onsets).
    let landed = creeper(&[]);
    assert_eq!(landed["status"], "steady", "{landed}");
    assert_eq!(landed["class"], "ID", "{landed}");
    assert_eq!(landed["ended_by"], "steady_by_landing", "{landed}");
    assert!(landed["unsettled"].is_null(), "{landed}");
    // Plain time stepping, given up at t_max as the paper does, creeps beside the saddle to
    // t_max: no class, the reason typed, and where it was heading (the slow flow's root).
    // (Run on, it reaches the landing's ID at t = 7098: s = 0.014085 both ways.)
    let waited = creeper(&["--no-landing", "--no-run-on"]);
    assert_eq!(waited["status"], "t_max", "{waited}");
    assert!(waited["class"].is_null(), "{waited}");
    assert_eq!(waited["unsettled"], "beside_saddle", "{waited}");
    assert_eq!(waited["heading"], "ID", "{waited}");
    let stopped = creeper(&["--no-landing", "--no-run-on", "--stop-beside-saddle"]);
    assert_eq!(stopped["status"], "saddle", "{stopped}");
    assert!(stopped["class"].is_null(), "{stopped}");
    assert_eq!(stopped["unsettled"], "beside_saddle", "{stopped}");
    assert!(stopped["t_end"].as_f64().unwrap() < 1000.0, "{stopped}");
    for out in [&waited, &stopped] {
        let d = out["diagnosis"].as_str().unwrap();
        assert!(d.starts_with("near an unstable steady state"), "{d}");
    }
    // Only with the Newton finish, whose growth rate it uses.
    let o = run(&[
        "simulate",
        "--eta-t",
        "0.0875",
        "--kappa2",
        "0.11875",
        "--steady",
        "test",
        "--stop-beside-saddle",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--stop-beside-saddle") && err.contains("Newton finish"),
        "{err}"
    );
}

#[test]
fn the_stop_beside_saddle_key_is_read_checked_and_in_the_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = |value: &str, steady: &str| {
        format!(
            "name: k\ngrid:\n  eta_t: [0.0875]\n  kappa2: [0.11875]\ninitial_conditions: [iv]\nsolver: {{steady: {steady}, landing: false, stop_beside_saddle: {value}}}\n"
        )
    };
    for (value, steady, key) in [
        ("sometimes", "newton", "solver.stop_beside_saddle"),
        ("true", "test", "solver.stop_beside_saddle"),
    ] {
        let bad = write_spec(dir.path(), "bad.yaml", &spec(value, steady));
        let o = crate::common::sweep(&bad, &dir.path().join("b"), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(key) && err.contains("bad.yaml"), "{err}");
    }
    let good = write_spec(dir.path(), "good.yaml", &spec("true", "newton"));
    let out = dir.path().join("g");
    let o = crate::common::sweep(&good, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let runs = crate::common::read(&out.join("runs.parquet"));
    let status = runs.column("status").unwrap().str().unwrap().get(0);
    assert_eq!(status, Some("saddle"));
    let flag = runs
        .column("stop_beside_saddle")
        .unwrap()
        .bool()
        .unwrap()
        .get(0);
    assert_eq!(flag, Some(true));
    let points = crate::common::read(&out.join("points.parquet"));
    let n_unsettled = points.column("n_unsettled").unwrap().u32().unwrap().get(0);
    assert_eq!(n_unsettled, Some(1));
}

/// The departure from the resting disk at (0.07625, 0.14) from IC iii, N = 192 (the onset
/// column of the refined map): with `--leap-departures` the linear stretch is leapt, and the
/// run keeps its outcome.
fn departure(extra: &[&str]) -> serde_json::Value {
    simulate_at("0.07625", "0.14", "iii", extra)
}

#[test]
fn a_leapt_departure_keeps_its_outcome_in_fewer_steps() {
    // Plain time stepping (the slow flow's landing, the default, ends both runs at once).
    let stepped = departure(&["--no-landing"]);
    let leapt = departure(&["--no-landing", "--leap-departures"]);
    assert_eq!(stepped["t_leapt"], 0.0, "{stepped}");
    assert!(leapt["t_leapt"].as_f64().unwrap() > 1000.0, "{leapt}");
    assert_eq!(leapt["class"], stepped["class"], "{leapt}\n{stepped}");
    assert_eq!(leapt["class"], "MD", "{leapt}");
    let steps = |o: &serde_json::Value| o["steps"].as_u64().unwrap();
    assert!(steps(&leapt) < steps(&stepped) / 2, "{leapt}\n{stepped}");
    assert_eq!(leapt["settings"]["leap_departures"], true, "{leapt}");
}

#[test]
fn the_leap_departures_key_is_read_checked_and_in_the_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = |value: &str, extra: &str| {
        format!(
            "name: k\ngrid:\n  eta_t: [0.07625]\n  kappa2: [0.14]\ninitial_conditions: [iii]\nsolver: {{n: 96, landing: false, leap_departures: {value}{extra}}}\n"
        )
    };
    for (value, extra) in [
        ("often", ""),
        ("true", ", steady: test"),
        ("true", ", tol: 0"),
    ] {
        let bad = write_spec(dir.path(), "bad.yaml", &spec(value, extra));
        let o = crate::common::sweep(&bad, &dir.path().join("b"), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains("solver.leap_departures") && err.contains("bad.yaml"),
            "{err}"
        );
    }
    let good = write_spec(dir.path(), "good.yaml", &spec("true", ""));
    let out = dir.path().join("g");
    let o = crate::common::sweep(&good, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let runs = crate::common::read(&out.join("runs.parquet"));
    let flag = runs
        .column("leap_departures")
        .unwrap()
        .bool()
        .unwrap()
        .get(0);
    assert_eq!(flag, Some(true));
    let leapt = runs.column("t_leapt").unwrap().f64().unwrap().get(0);
    assert!(leapt.is_some_and(|t| t > 500.0), "{leapt:?}");
}
