//! Sweeps of the paper's general model with shape modes 2..K (`params.modes: K`): the runs
//! table's extra amplitudes, the K-mode runs against `simulate --modes K`, and bad input.
use crate::cli::axes::floats;
use crate::common::{edit, json, read, run, sweep, write_spec};

/// Four points at N = 96 (where the x-axis MD state is stable in rotation): MD at Fig. 1c,
/// IC at (0.1, 0.16), far from every boundary.
fn spec(modes: &str) -> String {
    format!(
        "name: modes\nparams: {{modes: {modes}}}\ngrid:\n  eta_t: [0.085, 0.1]\n  kappa2: [0.112, 0.16]\ninitial_conditions: [i]\nsolver:\n  n: 96\n  dt: 0.05\n  t_max: 400\n"
    )
}

/// The points table of the 3-mode map in `out` has the state each initial condition's run
/// settled on: the runs' `a3` where they have a class.
fn points_hold_the_runs_amplitudes(out: &std::path::Path, a3: &[f64], classes: &[Option<&str>]) {
    // The points table has the state each initial condition's run settled on: the same
    // amplitudes as the runs table (one run per point here).
    let points = read(&out.join("points.parquet"));
    let col = points.column("a3_i").unwrap().f64().unwrap().clone();
    let mut from_points: Vec<f64> = (0..col.len()).filter_map(|i| col.get(i)).collect();
    let mut from_runs: Vec<f64> = (0..a3.len())
        .filter(|&i| classes[i].is_some())
        .map(|i| a3[i])
        .collect();
    from_points.sort_by(f64::total_cmp);
    from_runs.sort_by(f64::total_cmp);
    assert_eq!(from_points, from_runs);
    assert_eq!(from_points.len(), 4);
    assert!(points.column("deformation_i").is_ok() && points.column("b3_i").is_ok());
}

/// `droplet boundaries` onto the 3-mode map in `out`.
fn boundaries_draw_the_three_mode_curves_across(out: &std::path::Path) {
    // `droplet boundaries` onto the map draws the 3-mode model's curves that cross its
    // window (0.085-0.1 x 0.112-0.16): the disk's diagonal deformation onset and the diagonal
    // ID's onset of motion. Not drawn: the disk's onset of motion (eta_t = 0.0765) and its
    // MC onset lie left of the window; the axis deformation onset and the axis ID meet below
    // it, at kappa2 = 0.1097 at N = 96; no MD on the window's middle line, so no fold curve.
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
    let pde = crate::cli::truncation::pde_curves(&b);
    assert_eq!(
        pde,
        [
            "IC onset of deformation (b2, diagonal)",
            "ID onset of motion (diagonal ID)"
        ],
        "{b}"
    );
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
    points_hold_the_runs_amplitudes(&out, &a3, &classes);
    boundaries_draw_the_three_mode_curves_across(&out);
    // The audit checks the K-mode map with the 3-mode equations: every label a stable state.
    let o = run(&["audit", out.to_str().unwrap(), "--json"]);
    let a = json(&o);
    assert_eq!(o.status.code(), Some(0), "{a}");
    assert_eq!(a["points_clean"], 4, "{a}");
    assert!(a["states_checked"].as_u64().unwrap() >= 2, "{a}");
    // A false IC at Fig. 1c, where the 3-mode disk deforms: the audit names the run.
    let md_row = (0..runs.height())
        .find(|&i| eta[i] == 0.085 && kappa[i] == 0.112)
        .unwrap();
    let point = runs
        .column("point")
        .unwrap()
        .u32()
        .unwrap()
        .get(md_row)
        .unwrap();
    edit(&out.join("runs.parquet"), "class", |i, old| {
        if i == md_row {
            Some("IC".into())
        } else {
            old.map(str::to_string)
        }
    });
    edit(&out.join("points.parquet"), "class", |i, old| {
        if i == point as usize {
            Some("IC".into())
        } else {
            old.map(str::to_string)
        }
    });
    let o = run(&["audit", out.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1));
    let a: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(a["list"][0]["kind"], "unstable_disk", "{a}");
}

#[test]
fn two_mode_tables_have_no_higher_modes() {
    let dir = tempfile::tempdir().unwrap();
    // The 2-mode tables have none of these columns.
    let two = dir.path().join("m2");
    let o = sweep(&write_spec(dir.path(), "m2.yaml", &spec("2")), &two, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(read(&two.join("runs.parquet")).column("a3").is_err());
    assert!(read(&two.join("points.parquet")).column("a3_i").is_err());
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
    ];
    for (name, text) in cases {
        let file = write_spec(dir.path(), &format!("bad-{name}.yaml"), &text);
        let o = sweep(&file, &dir.path().join(name), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains("params.modes"), "{name}: {err}");
    }
    // The friction law: within -4..4, and only with modes > 2.
    for (name, text) in [
        (
            "law-5",
            spec("3").replace("{modes: 3}", "{modes: 3, eta_k_exponent: 5}"),
        ),
        (
            "law-k2",
            spec("2").replace("{modes: 2}", "{modes: 2, eta_k_exponent: -1}"),
        ),
        (
            "law-text",
            spec("3").replace("{modes: 3}", "{modes: 3, eta_k_exponent: fast}"),
        ),
    ] {
        let file = write_spec(dir.path(), &format!("bad-{name}.yaml"), &text);
        let o = sweep(&file, &dir.path().join(name), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains("params.eta_k_exponent"), "{name}: {err}");
    }
}

#[test]
fn the_papers_scheme_runs_k_modes_as_a_sweep_and_as_the_spectral_scheme_does() {
    // Modes 2..3 from IC i at N = 96 to t = 10 (both fields start at 0): the paper's forward
    // Euler on the lab grid and the spectral ETD2RK (adaptive) in the droplet's frame, two
    // discretisations, agree to their O(dx^2) on v, a2 and the mode 3 the motion drives
    // (measured: 0.1 %, 2.7 % and 7 %; the forces' second order is tested in the solver). The sweep's run is `simulate --scheme paper-fd`'s, to the last digit.
    let sim = |scheme: &str| {
        let mut args = vec![
            "simulate", "--eta-t", "0.085", "--kappa2", "0.112", "--modes", "3", "--n", "96",
            "--dt", "1e-3", "--t-max", "10", "--scheme", scheme, "--json",
        ];
        // The paper's scheme ends at t_max (it has no Newton finish to run on with).
        if scheme == "spectral" {
            args.push("--no-run-on");
        }
        json(&run(&args))
    };
    let (fd, spectral) = (sim("paper-fd"), sim("spectral"));
    assert_eq!(fd["status"], "t_max", "{fd}");
    assert_eq!(fd["unsettled"], "not_diagnosed", "{fd}");
    assert_eq!(fd["steps"], 10_000, "{fd}");
    let pick = |j: &serde_json::Value| {
        [
            j["v"].as_f64().unwrap(),
            j["a_k"][0].as_f64().unwrap(),
            j["a_k"][1].as_f64().unwrap(),
        ]
    };
    let (f, sp) = (pick(&fd), pick(&spectral));
    assert!(f[2] < -0.01, "mode 3 is driven: {fd}");
    for ((a, b), within) in f.iter().zip(&sp).zip([0.01, 0.05, 0.1]) {
        assert!((a - b).abs() < within * b.abs(), "{f:?} vs {sp:?}");
    }
    let dir = tempfile::tempdir().unwrap();
    let text = "name: fd3\nparams: {modes: 3}\ngrid:\n  eta_t: [0.085]\n  kappa2: [0.112]\n\
                initial_conditions: [i]\nsolver:\n  scheme: paper-fd\n  n: 96\n  dt: 1e-3\n  \
                t_max: 10\n";
    let out = dir.path().join("fd3");
    let o = sweep(&write_spec(dir.path(), "fd3.yaml", text), &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let runs = read(&out.join("runs.parquet"));
    assert_eq!(floats(&runs, "v")[0], f[0]);
    assert_eq!(floats(&runs, "a3")[0], f[2]);
}

#[test]
fn initial_amplitudes_of_higher_modes_start_the_run_and_beyond_k_exit_2() {
    // A resting disk given a mode-3 dent at (0.1, 0.16), where the disk is stable: the run
    // starts from it (the dent shows at t = 0.05) and ends IC, the dent gone.
    let ic = "custom:0,0,0,0,0.05,0";
    let out = |extra: &[&str]| {
        let mut args = vec![
            "simulate", "--eta-t", "0.1", "--kappa2", "0.16", "--modes", "3", "--n", "96", "--dt",
            "0.05", "--json", "--ic", ic,
        ];
        args.extend_from_slice(extra);
        json(&run(&args))
    };
    let early = out(&["--t-max", "0.05", "--no-run-on"]);
    let a3 = early["a_k"][1].as_f64().unwrap();
    assert!(a3 > 0.04 && a3 < 0.05, "{early}");
    let dir = tempfile::tempdir().unwrap();
    let series = dir.path().join("dent.parquet");
    let settled = out(&[
        "--t-max",
        "400",
        "--series",
        series.to_str().unwrap(),
        "--every",
        "1",
    ]);
    assert_eq!(settled["class"], "IC", "{settled}");
    assert!(
        settled["a_k"][1].as_f64().unwrap().abs() < 1e-8,
        "{settled}"
    );
    // Its time series has mode 3 too: the dent at t = 0, decaying at every sample (the
    // early try ends the run on the disk once it has settled, the dent down to a fortieth).
    let table = read(&series);
    let (t, a3) = (floats(&table, "t"), floats(&table, "a3"));
    assert_eq!((t[0], a3[0]), (0.0, 0.05));
    assert!(a3.windows(2).all(|w| w[1].abs() < w[0].abs()), "{a3:?}");
    assert!(a3[a3.len() - 1].abs() < 2e-3, "{a3:?}");
    assert_eq!(t[t.len() - 1], settled["t_end"].as_f64().unwrap());
    assert!(table.column("b3").is_ok() && table.column("a4").is_err());
    // Amplitudes beyond K: simulate names --ic, a sweep names initial_conditions.
    let o = run(&[
        "simulate",
        "--eta-t",
        "0.1",
        "--kappa2",
        "0.16",
        "--modes",
        "3",
        "--n",
        "96",
        "--ic",
        "custom:0,0,0,0,0.05,0,0.01,0",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--ic") && err.contains("mode 4"), "{err}");
    for (modes, ics) in [
        ("2", "[i, 'custom:0,0,0.1,0,0.02,0']"),
        ("3", "['custom:0,0,0.1,0,0,0,0.01,0']"),
    ] {
        let text = spec(modes).replace(
            "initial_conditions: [i]",
            &format!("initial_conditions: {ics}"),
        );
        let file = write_spec(dir.path(), &format!("beyond-{modes}.yaml"), &text);
        let o = sweep(&file, &dir.path().join(modes), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{modes}: {err}");
        assert!(err.contains("initial_conditions"), "{modes}: {err}");
    }
}

#[test]
fn mode_four_closes_the_papers_bistable_band_right_of_its_md_fold() {
    // At kappa2 = 0.13 the 2-mode MD fold lies at eta_t = 0.0793 and the K = 4 one at 0.0781
    // (N = 192; results/truncation), the disk's onset of motion left of both (0.0765).
    // (0.0775, 0.13) lies between the onset and both folds; (0.0786, 0.13) inside the 2-mode
    // band but right of the K = 4 fold. N = 96 keeps this order.
    let text = |modes: u32| {
        format!(
            "name: band{modes}\nparams: {{modes: {modes}}}\ngrid:\n  eta_t: [0.0775, 0.0786]\n  \
             kappa2: [0.13]\ninitial_conditions: [i, ii, iii, iv]\nsolver:\n  n: 96\n"
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let map = |modes: u32| {
        let out = dir.path().join(format!("band{modes}"));
        let spec = write_spec(dir.path(), &format!("band{modes}.yaml"), &text(modes));
        let o = sweep(&spec, &out, &[]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let runs = read(&out.join("runs.parquet"));
        let strings = |t: &polars::prelude::DataFrame, c: &str| -> Vec<String> {
            let s = t.column(c).unwrap().str().unwrap().clone();
            (0..s.len())
                .map(|i| s.get(i).unwrap_or("-").to_string())
                .collect()
        };
        let points = read(&out.join("points.parquet"));
        let labels: Vec<(f64, String)> = floats(&points, "eta_t")
            .into_iter()
            .zip(strings(&points, "class"))
            .collect();
        let ends: Vec<(f64, String, String, f64)> = floats(&runs, "eta_t")
            .into_iter()
            .zip(strings(&runs, "ic"))
            .zip(strings(&runs, "class"))
            .zip(floats(&runs, "v"))
            .map(|(((e, ic), c), v)| (e, ic, c, v))
            .collect();
        (labels, ends)
    };
    let label = |labels: &[(f64, String)], eta: f64| {
        labels.iter().find(|(e, _)| *e == eta).unwrap().1.clone()
    };
    // The paper's two modes: both points bistable.
    let (two, _) = map(2);
    assert_eq!(label(&two, 0.0775), "IC/MD", "{two:?}");
    assert_eq!(label(&two, 0.0786), "IC/MD", "{two:?}");
    // Modes 2..4: right of the fold every run, the moving starts i and ii too, comes to rest
    // on the disk; left of it the moving starts keep moving (MD) and the resting ones iii
    // and iv stay on the disk, whose onset of motion lies further left.
    let (four, ends) = map(4);
    assert_eq!(label(&four, 0.0786), "IC", "{four:?}");
    assert_eq!(label(&four, 0.0775), "IC/MD", "{four:?}");
    for (eta, ic, class, v) in &ends {
        let moving_start = ic == "i" || ic == "ii";
        let expect = if *eta == 0.0775 && moving_start {
            "MD"
        } else {
            "IC"
        };
        assert_eq!(class, expect, "{ends:?}");
        assert_eq!(*v > 0.1, expect == "MD", "{ends:?}");
    }
}
