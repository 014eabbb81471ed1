//! Sweeps of the paper's general model with shape modes 2..K (`params.modes: K`): the runs
//! table's extra amplitudes, the K-mode runs against `simulate --modes K`, and bad input.
use crate::axes::floats;
use crate::common::{json, read, run, sweep, write_spec};

/// Four points at N = 96 (where the x-axis MD state is stable in rotation): MD at Fig. 1c,
/// IC at (0.1, 0.16), far from every boundary.
fn spec(modes: &str) -> String {
    format!(
        "name: modes\nparams: {{modes: {modes}}}\ngrid:\n  eta_t: [0.085, 0.1]\n  kappa2: [0.112, 0.16]\ninitial_conditions: [i]\nsolver:\n  n: 96\n  dt: 0.05\n  t_max: 400\n"
    )
}

#[test]
fn a_sweep_with_three_modes_runs_the_k_mode_model_and_tables_its_amplitudes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m3");
    let o = sweep(&write_spec(dir.path(), "m3.yaml", &spec("3")), &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let runs = read(&out.join("runs.parquet"));
    for col in ["modes", "a3", "b3", "deformation"] {
        assert!(runs.column(col).is_ok(), "{col}");
    }
    let (eta, v, a3) = (
        floats(&runs, "eta_t"),
        floats(&runs, "v"),
        floats(&runs, "a3"),
    );
    let class = runs.column("class").unwrap().str().unwrap().clone();
    let classes: Vec<Option<&str>> = (0..class.len()).map(|i| class.get(i)).collect();
    let kappa = floats(&runs, "kappa2");
    for i in 0..runs.height() {
        // The grid's corners: (0.085, 0.112) moves and is deformed; (0.1, 0.16) rests.
        let md = eta[i] == 0.085 && kappa[i] == 0.112;
        let rest = eta[i] == 0.1 && kappa[i] == 0.16;
        if !(md || rest) {
            continue;
        }
        assert_eq!(classes[i], Some(if md { "MD" } else { "IC" }), "row {i}");
        if md {
            // The run is `simulate --modes 3` with the same settings, to the last digit, and
            // mode 3 is there (front-back asymmetry along the axis of motion).
            let sim = json(&run(&[
                "simulate", "--eta-t", "0.085", "--kappa2", "0.112", "--modes", "3", "--n", "96",
                "--dt", "0.05", "--t-max", "400", "--json",
            ]));
            assert_eq!(sim["v"].as_f64().unwrap(), v[i], "{sim}");
            let a3_sim = sim["a_k"][1].as_f64().unwrap();
            assert_eq!(a3_sim, a3[i], "{sim}");
            assert!(a3[i].abs() > 1e-2, "{}", a3[i]);
        }
    }
    // `droplet boundaries` onto the map draws the 3-mode model's curves (those of the states
    // on the x axis; no MD on this window's middle line, so no fold curve).
    let b = json(&run(&[
        "boundaries",
        "--out",
        out.to_str().unwrap(),
        "--n",
        "96",
        "--samples",
        "8",
        "--json",
    ]));
    let pde = crate::truncation::pde_curves(&b);
    assert_eq!(
        pde,
        [
            "IC onset of motion",
            "IC onset of deformation (a2, axis)",
            "ID onset of motion (axis ID)"
        ],
        "{b}"
    );
    // The 2-mode tables have none of these columns.
    let two = dir.path().join("m2");
    let o = sweep(&write_spec(dir.path(), "m2.yaml", &spec("2")), &two, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(read(&two.join("runs.parquet")).column("a3").is_err());
    // The audit's equations are the 2-mode model's: it refuses the K-mode map.
    let o = run(&["audit", out.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("modes = 3"));
}

#[test]
fn bad_modes_in_a_spec_exit_2_naming_params_modes() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("1", spec("1")),
        ("0", spec("0")),
        ("2.5", spec("2.5")),
        ("17", spec("17")),
        // N = 96 resolves modes up to 10.
        ("11", spec("11")),
        (
            "ode",
            format!(
                "model: ode\n{}",
                spec("3").replace("  n: 96\n  dt: 0.05\n", "  dt: 0.05\n")
            ),
        ),
        (
            "fd",
            spec("3").replace("  n: 96\n", "  n: 96\n  scheme: paper-fd\n"),
        ),
    ];
    for (name, text) in cases {
        let file = write_spec(dir.path(), &format!("bad-{name}.yaml"), &text);
        let o = sweep(&file, &dir.path().join(name), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains("params.modes"), "{name}: {err}");
    }
}
