//! `droplet boundaries` end to end: a sweep's phase map redrawn with the boundaries, and the
//! boundaries at several grid sizes with each curve's shift from the previous one.

use crate::common::{json, read, run};

#[test]
fn boundaries_are_written_and_drawn_over_a_sweeps_map() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = dir.path().join("smoke");
    crate::common::copy_sweep(&crate::common::smoke_sweep().0, &sweep);
    let s = sweep.to_str().unwrap();
    let j = json(&run(&[
        "boundaries",
        "--out",
        s,
        "--n",
        "96",
        "--samples",
        "6",
        "--json",
    ]));
    // The sweep's window is the default.
    assert_eq!(j["eta_t"][0].as_f64(), Some(0.07), "{j}");
    let curves = j["curves"].as_array().unwrap();
    let fold = curves
        .iter()
        .find(|c| c["model"] == "pde" && c["curve"] == "MD saddle-node (x axis)")
        .expect("the fold curve");
    assert!(fold["points"].as_u64().unwrap() > 10, "{fold}");
    let df = read(&sweep.join("boundaries.parquet"));
    let model = df.column("model").unwrap().str().unwrap();
    let models: Vec<&str> = (0..model.len()).filter_map(|i| model.get(i)).collect();
    assert!(models.contains(&"pde") && models.contains(&"ode"));
    // Redrawing the sweep keeps the full model's rows.
    assert!(run(&["plot", s]).status.success());
    let again = read(&sweep.join("boundaries.parquet"));
    assert_eq!(again.height(), df.height());
    for f in ["boundaries.png", "boundaries.svg", "phase_map.png"] {
        assert!(sweep.join(f).exists(), "{f}");
    }
}

#[test]
fn boundaries_at_several_grid_sizes_give_each_curves_shift_from_the_previous_one() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("conv");
    let o = out.to_str().unwrap();
    let r = json(&run(&[
        "boundaries",
        "--n",
        "64,48",
        "--samples",
        "8",
        "--out",
        o,
        "--json",
    ]));
    assert_eq!(r["ns"], serde_json::json!([48, 64]), "{r}");
    let curves = r["curves"].as_array().unwrap();
    // The onset of motion is a vertical line: its shift is the change of its threshold, read
    // here from each N's own table.
    let onset = |n: usize| -> f64 {
        let df = read(&out.join(format!("n{n}/boundaries.parquet")));
        let (model, curve) = (
            df.column("model").unwrap().str().unwrap().clone(),
            df.column("curve").unwrap().str().unwrap().clone(),
        );
        let eta = df.column("eta_t").unwrap().f64().unwrap().clone();
        (0..df.height())
            .find(|&i| model.get(i) == Some("pde") && curve.get(i) == Some("IC onset of motion"))
            .map(|i| eta.get(i).unwrap())
            .expect("the onset of motion at every N")
    };
    let expected = (onset(64) - onset(48)).abs();
    let at = |n: u64, name: &str| {
        curves
            .iter()
            .find(|c| c["n"] == n && c["curve"] == name)
            .unwrap_or_else(|| panic!("{name} at N = {n}: {r}"))
    };
    assert!(at(48, "IC onset of motion")["shift"].is_null());
    let shift = at(64, "IC onset of motion")["shift"].as_f64().unwrap();
    assert!((shift - expected).abs() < 1e-12, "{shift} vs {expected}");
    assert!(expected > 0.0);
    for c in curves.iter().filter(|c| c["n"] == 64) {
        if let Some(s) = c["shift"].as_f64() {
            assert!(s.is_finite() && s >= 0.0, "{c}");
        }
    }
    let table = read(&out.join("convergence.parquet"));
    assert_eq!(table.height(), curves.len());
    assert!(out.join("boundaries_by_n.png").is_file());
    // Bad lists are refused, naming the option.
    for bad in ["64,65", "64,abc", "64,8192", "64,64"] {
        let o = run(&["boundaries", "--n", bad, "--out", o]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("--n"), "{bad}");
    }
}
