//! `droplet simulate`: refusals, the JSON report, the series and the picture, the Fig. 1
//! points.
use crate::common::{json, read, run};

#[test]
fn simulate_rejects_bad_arguments_with_exit_2() {
    for args in [
        vec!["simulate", "--eta-t", "-1", "--kappa2", "0.1"],
        vec![
            "simulate", "--eta-t", "0.08", "--kappa2", "0.1", "--ic", "vii",
        ],
        vec![
            "simulate", "--eta-t", "0.08", "--kappa2", "0.1", "--scheme", "rk4",
        ],
        vec![
            "simulate", "--eta-t", "0.08", "--kappa2", "0.1", "--n", "31",
        ],
        vec!["simulate", "--eta-t", "0.08"],
        vec!["simulate", "--eta-t", "x", "--kappa2", "0.1"],
    ] {
        let o = run(&args);
        assert_eq!(
            o.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(!o.stderr.is_empty());
    }
}

#[test]
fn simulate_json_series_and_picture() {
    let dir = tempfile::tempdir().unwrap();
    let series = dir.path().join("s.parquet");
    let pic = dir.path().join("p.png");
    let o = run(&[
        "simulate",
        "--eta-t",
        "0.07",
        "--kappa2",
        "0.12",
        "--ic",
        "i",
        "--n",
        "48",
        "--t-max",
        "20",
        // Given up at t_max (not run on to 4 t_max), so that the run ends exactly there.
        "--no-run-on",
        "--json",
        "--series",
        series.to_str().unwrap(),
        "--picture",
        pic.to_str().unwrap(),
        "--every",
        "1",
    ]);
    let j = json(&o);
    for key in [
        "status",
        "class",
        "v",
        "s",
        "vx",
        "vy",
        "a2",
        "b2",
        "t_end",
        "t_steady",
        "steps",
        "rejected",
        "max_step_error",
        "dt_warning",
        "wall_s",
        "settings",
        "params",
    ] {
        assert!(j.get(key).is_some(), "missing {key}");
    }
    // Adaptive by default: fewer steps than dt = 0.02 would take, ending exactly at t_max.
    let steps = j["steps"].as_u64().unwrap();
    assert!(steps > 20 && steps < 1000, "{steps}");
    assert!((j["t_end"].as_f64().unwrap() - 20.0).abs() < 1e-9);
    assert!(j["max_step_error"].as_f64().unwrap() <= 1e-4);
    assert!(j["dt_warning"].is_null());
    // Where the run's time went: stepping, and no more than the run's wall time in all.
    let profile = &j["profile"];
    let stepping = profile["stepping_s"].as_f64().unwrap();
    let parts: f64 = ["stepping_s", "newton_s", "eigen_s", "landing_s", "flow_s"]
        .iter()
        .map(|k| profile[k].as_f64().unwrap())
        .sum();
    assert!(
        stepping > 0.0 && parts <= j["wall_s"].as_f64().unwrap() + 1e-9,
        "{profile}"
    );
    assert!((j["mass_integral"].as_f64().unwrap() - (1.0 - (-20f64).exp())).abs() < 1e-9);
    let df = read(&series);
    assert_eq!(df.height(), 21);
    assert!(std::fs::metadata(&pic).unwrap().len() > 1000);
    assert!(dir.path().join("p.svg").exists());
}

/// The paper's Fig. 1 at the default settings (N = 192, dt = 0.02) from IC (i):
/// kappa2 = 0.120 -> IC, 0.116 -> ID, 0.112 -> MD moving along its minor axis.
#[test]
fn fig1_points_classify_as_in_the_paper() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fig1");
    json(&run(&[
        "sweep",
        "sweeps/fig1.yaml",
        "--out",
        out.to_str().unwrap(),
        "--json",
        "--no-plot",
    ]));
    let runs = read(&out.join("runs.parquet"));
    let k = runs.column("kappa2").unwrap().f64().unwrap();
    let class = runs.column("class").unwrap().str().unwrap();
    let status = runs.column("status").unwrap().str().unwrap();
    let col = |c: &str| runs.column(c).unwrap().f64().unwrap().clone();
    let (vx, vy, a2, b2) = (col("vx"), col("vy"), col("a2"), col("b2"));
    for i in 0..runs.height() {
        let kappa = k.get(i).unwrap();
        let want = if kappa > 0.118 {
            "IC"
        } else if kappa > 0.114 {
            "ID"
        } else {
            "MD"
        };
        assert_eq!(status.get(i), Some("steady"), "kappa2 {kappa}");
        assert_eq!(class.get(i), Some(want), "kappa2 {kappa}");
        if want == "MD" {
            // Minor axis along the motion: v . S v = -s v^2 (S v antiparallel to v).
            let (vx, vy, a2, b2) = (
                vx.get(i).unwrap(),
                vy.get(i).unwrap(),
                a2.get(i).unwrap(),
                b2.get(i).unwrap(),
            );
            let vsv = vx * (a2 * vx + b2 * vy) + vy * (b2 * vx - a2 * vy);
            let (v2, s) = (vx * vx + vy * vy, a2.hypot(b2));
            assert!(
                (vsv / (s * v2) + 1.0).abs() < 1e-3,
                "not minor-axis motion: {vsv} vs {}",
                -s * v2
            );
        }
    }
}
