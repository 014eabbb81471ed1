//! `droplet continue` and `droplet boundaries` end to end: branches, events, tables and bad
//! input (the boundaries over a sweep's map and at several grid sizes: `boundaries`).

use crate::common::{json, read, run};

#[test]
fn continue_follows_md_through_its_fold_to_the_onset_of_motion() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let args = [
        "continue", "--kappa2", "0.13", "--from", "0.07", "--to", "0.1", "--n", "96", "--out", out,
        "--json",
    ];
    let j = json(&run(&args));
    let events = j["events"].as_array().unwrap();
    let at = |kind: &str, branch: &str| {
        events
            .iter()
            .find(|e| e["kind"] == kind && e["branch"] == branch)
            .map(|e| e["eta_t"].as_f64().unwrap())
    };
    // Subcritical onset of motion: the MD branch meets IC where the disk loses stability,
    // and folds back above it (bistable IC/MD in between).
    let p_ic = at("P", "IC").expect("the disk's drift pitchfork");
    let meets = events
        .iter()
        .find(|e| e["what"] == "meets IC")
        .expect("MD meets IC");
    assert!(
        (meets["eta_t"].as_f64().unwrap() - p_ic).abs() < 1e-9,
        "{j}"
    );
    let sn = at("SN", "MD minor-axis").expect("a fold");
    assert!(sn > p_ic + 0.001 && sn < 0.085, "{j}");
    // Every located event says how precisely, and it is within the promised 1e-7 (the P by
    // eigenvalue and the fold to about 1e-13 on this line).
    for e in events {
        let precision = e["precision"].as_f64().expect("a precision");
        assert!((0.0..=1e-7).contains(&precision), "{e}");
    }
    let fold = events.iter().find(|e| e["kind"] == "SN").unwrap();
    assert!(fold["precision"].as_f64().unwrap() < 1e-10, "{fold}");
    let branches = j["branches"].as_array().unwrap();
    let md = branches
        .iter()
        .find(|b| b["branch"] == "MD minor-axis")
        .unwrap();
    assert!(md["stable_points"].as_u64().unwrap() > 5, "{md}");
    assert!(md["points"].as_u64().unwrap() > md["stable_points"].as_u64().unwrap());
    // Tables and picture.
    let df = read(&dir.path().join("continuation_kappa2_0.13.parquet"));
    let stable = df.column("stable").unwrap().bool().unwrap();
    assert!((0..stable.len()).any(|i| stable.get(i) == Some(false)));
    let ev = read(&dir.path().join("continuation_kappa2_0.13_events.parquet"));
    assert_eq!(ev.height(), events.len());
    let precision = ev.column("precision").unwrap().f64().unwrap();
    assert!((0..precision.len()).all(|i| precision.get(i).is_some_and(|p| p <= 1e-7)));
    assert!(dir.path().join("continuation_kappa2_0.13.png").exists());
    assert!(dir.path().join("continuation_kappa2_0.13.svg").exists());
}

/// `continue --param` given what it refuses: `(arguments, what the message says)`.
fn bad_param_cases() -> Vec<(Vec<&'static str>, &'static str)> {
    let line = ["--from", "0.05", "--to", "0.5"];
    let with_line =
        |head: &[&'static str]| -> Vec<&'static str> { head.iter().copied().chain(line).collect() };
    vec![
        (
            with_line(&["continue", "--param", "massive"]),
            "--param massive",
        ),
        (
            with_line(&["continue", "--param", "mass", "--set", "eta_t:0.08"]),
            "NAME=VALUE",
        ),
        (
            with_line(&["continue", "--param", "mass", "--set", "foo=1"]),
            "NAME one of",
        ),
        (
            with_line(&["continue", "--param", "mass", "--set", "mass=0.2"]),
            "varied parameter",
        ),
        (
            with_line(&["continue", "--param", "mass", "--mass", "0.2"]),
            "--mass",
        ),
        (
            with_line(&[
                "continue",
                "--param",
                "eta2",
                "--set",
                "eta_t=0.08,eta_t=0.09",
            ]),
            "twice",
        ),
        (
            vec!["continue", "--param", "mass", "--from", "0", "--to", "0.5"],
            "> 0 along the whole line",
        ),
        (
            vec![
                "continue", "--param", "sigma", "--from", "0.03", "--to", "0.5",
            ],
            "R/4",
        ),
    ]
}

#[test]
fn bad_input_exits_2_naming_the_option() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let param_cases = bad_param_cases();
    for (args, needle) in param_cases {
        let mut all = args.clone();
        all.extend(["--out", out]);
        let o = run(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    let cases: [(&[&str], &str); 6] = [
        (
            &[
                "continue", "--kappa2", "0.13", "--from", "0.1", "--to", "0.07",
            ],
            "--from",
        ),
        (
            &[
                "continue", "--kappa2", "0.13", "--from", "0.07", "--to", "0.1", "--branch", "xx",
            ],
            "--branch",
        ),
        (
            &[
                "continue", "--kappa2", "0.13", "--from", "0.07", "--to", "0.1", "--axis", "z",
            ],
            "--axis",
        ),
        (
            &[
                "continue", "--kappa2", "0.13", "--from", "0.07", "--to", "0.1", "--n", "7",
            ],
            "--n",
        ),
        (
            &[
                "continue", "--kappa2", "0.13", "--from", "-0.1", "--to", "0.1",
            ],
            "eta_t",
        ),
        (&["boundaries", "--eta-t", "0.1,0.07"], "--eta-t"),
    ];
    for (args, needle) in cases {
        let mut all = args.to_vec();
        all.extend(["--out", out]);
        let o = run(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn fig2b_class_changes_fall_between_the_committed_bifurcation_points() {
    // The committed Fig. 2b sweeps against the committed continuation of the same lines
    // (results/continuation/run.sh): every class change between neighbouring grid points has a
    // P / SN point between them, or is a resting class where that state is unstable.
    let mut bracketed = 0;
    for line in droplet_sweep::map::line_compare::FIG2B_LINES {
        let name = line.0;
        let changes = droplet_sweep::map::line_compare::compare_fig2b(line).unwrap();
        assert!(!changes.is_empty(), "line {name}");
        for c in &changes {
            assert!(c.explained(), "line {name}: {c:?}");
            bracketed += usize::from(!c.events.is_empty());
        }
    }
    assert!(bracketed >= 10, "{bracketed}");
}

/// `(at, v, stable)` of every state of a continuation table.
fn states(path: &std::path::Path) -> Vec<(f64, f64, bool)> {
    let df = read(path);
    let f = |c: &str| df.column(c).unwrap().f64().unwrap().clone();
    let (at, v) = (f("at"), f("v"));
    let stable = df.column("stable").unwrap().bool().unwrap().clone();
    (0..df.height())
        .map(|i| {
            (
                at.get(i).unwrap(),
                v.get(i).unwrap(),
                stable.get(i).unwrap(),
            )
        })
        .collect()
}

#[test]
fn continuation_in_mass_and_eta2_reproduces_the_time_stepper() {
    // eta2 and m multiply time derivatives only: along either, the MD branch is level in the
    // state, and a run at any value ends on it (to the Newton finish's 1e-10). N = 128: at
    // N = 96 the grid's anisotropy turns these runs a few degrees off the x axis.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    for (param, values) in [("eta2", [0.05, 0.12]), ("mass", [0.1, 0.5])] {
        let mut branch = Vec::new();
        {
            let axis = "x";
            let j = json(&run(&[
                "continue",
                "--param",
                param,
                "--set",
                "eta_t=0.078,kappa2=0.13",
                "--from",
                &values[0].to_string(),
                "--to",
                &values[1].to_string(),
                "--branch",
                "md",
                "--axis",
                axis,
                "--n",
                "128",
                "--out",
                out,
                "--json",
            ]));
            assert_eq!(
                j["line"],
                format!(
                    "eta_t = 0.078, kappa2 = 0.13, {param} from {} to {}",
                    values[0], values[1]
                )
            );
            let table = j["files"]
                .as_array()
                .unwrap()
                .iter()
                .map(|f| std::path::PathBuf::from(f.as_str().unwrap()))
                .find(|f| {
                    f.extension().is_some_and(|e| e == "parquet")
                        && !f.to_string_lossy().contains("_events")
                })
                .unwrap();
            branch.extend(states(&table));
        }
        for x in values {
            let s = json(&run(&[
                "simulate",
                "--eta-t",
                "0.078",
                "--kappa2",
                "0.13",
                &format!("--{param}"),
                &x.to_string(),
                "--ic",
                "i",
                "--n",
                "128",
                "--json",
            ]));
            assert_eq!(s["class"], "MD", "{param} = {x}: {s}");
            let v = s["v"].as_f64().unwrap();
            // The branch state at this value (the branch covers both ends).
            let (at, vb, stable) = branch
                .iter()
                .copied()
                .filter(|(at, _, _)| (at - x).abs() < 1e-9)
                .min_by(|a, b| (a.1 - v).abs().total_cmp(&(b.1 - v).abs()))
                .unwrap_or_else(|| panic!("no state at {param} = {x}"));
            assert!(
                (vb - v).abs() < 1e-6,
                "{param} = {at}: branch v {vb}, run v {v}"
            );
            assert!(
                stable,
                "{param} = {at}: the run's state is unstable on the branch"
            );
        }
    }
}

#[test]
fn boundaries_in_the_paper_plane_equal_the_committed_ones() {
    // `results/boundaries` was written by `droplet boundaries --out results/boundaries` (the
    // Fig. 2a window, N = 192) before sweeps and continuation took any parameter and before
    // the curves were computed on threads of their own: the same command gives the same
    // curves.
    let dir = tempfile::tempdir().unwrap();
    let o = run(&[
        "boundaries",
        "--out",
        dir.path().to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = |path: &std::path::Path| {
        let df = read(path);
        let model = df.column("model").unwrap().str().unwrap().clone();
        let curve = df.column("curve").unwrap().str().unwrap().clone();
        let e = df.column("eta_t").unwrap().f64().unwrap().clone();
        let k = df.column("kappa2").unwrap().f64().unwrap().clone();
        (0..df.height())
            .filter(|&i| model.get(i) == Some("pde"))
            .map(|i| {
                (
                    curve.get(i).unwrap().to_string(),
                    e.get(i).unwrap(),
                    k.get(i).unwrap(),
                )
            })
            .collect::<Vec<_>>()
    };
    let committed = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("results/boundaries/boundaries.parquet");
    let (want, got) = (
        rows(&committed),
        rows(&dir.path().join("boundaries.parquet")),
    );
    assert!(want.len() > 50);
    assert_eq!(want.len(), got.len());
    for (w, g) in want.iter().zip(&got) {
        assert_eq!(w.0, g.0);
        assert!(
            (w.1 - g.1).abs() < 1e-12 && (w.2 - g.2).abs() < 1e-12,
            "{w:?} != {g:?}"
        );
    }
}
