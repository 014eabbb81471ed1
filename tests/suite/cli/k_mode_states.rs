//! The K-mode model's states through the commands: `boundaries --modes K` in the paper's
//! plane, a K-mode run settling on its steady state, and `continue --modes K` with the
//! branch's stability (the truncation table and `stability --modes K`: `truncation`).
use crate::cli::axes::floats;
use crate::cli::truncation::{pde_curves, refused, stability};
use crate::common::{json, read, run};

#[test]
fn boundaries_with_modes_draw_the_k_mode_curves_in_the_papers_plane() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b3");
    let b = json(&run(&[
        "boundaries",
        "--modes",
        "3",
        "--n",
        "64",
        "--samples",
        "10",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    let pde = pde_curves(&b);
    // No MC onset at N = 64, as for the 2-mode model there (at N = 96 it is drawn; its K = 2
    // line is the 2-mode one, crates/solver's mode_boundaries test).
    assert_eq!(
        pde,
        [
            "IC onset of motion",
            "IC onset of deformation (b2, diagonal)",
            "IC onset of deformation (a2, axis)",
            "ID onset of motion (diagonal ID)",
            "ID onset of motion (axis ID)",
            "MD saddle-node (x axis)"
        ],
        "{b}"
    );
    assert!(out.join("boundaries.png").exists());
    refused(
        &["boundaries", "--out", out.to_str().unwrap()],
        &[
            (&["--modes", "1"], "modes"),
            (&["--modes", "3", "--n", "64,96"], "--modes 3"),
        ],
    );
}

#[test]
fn a_k_mode_run_settles_on_the_k_mode_steady_state() {
    // Time stepping and the steady solver give the same moving droplet, mode 3 included.
    let stepped = json(&run(&[
        "simulate",
        "--eta-t",
        "0.085",
        "--kappa2",
        "0.112",
        "--ic",
        "custom:0.5,0,-0.1,0",
        "--modes",
        "3",
        "--n",
        "96",
        "--steady-tol",
        "1e-9",
        "--json",
    ]));
    assert_eq!(stepped["status"], "steady", "{stepped}");
    assert_eq!(stepped["class"], "MD", "{stepped}");
    let st = stability(&[
        "--eta-t", "0.085", "--kappa2", "0.112", "--state", "md", "--modes", "3", "--n", "96",
    ]);
    let f = |x: &serde_json::Value| x.as_f64().unwrap();
    for (a, b) in [
        (&stepped["v"], &st["v"]),
        (&stepped["a_k"][0], &st["a_k"][0]),
        (&stepped["a_k"][1], &st["a_k"][1]),
    ] {
        assert!((f(a) - f(b)).abs() < 1e-6, "{stepped} {st}");
    }
    assert!(f(&st["a_k"][1]).abs() > 1e-2, "{st}");
    let o = run(&[
        "simulate",
        "--eta-t",
        "0.085",
        "--kappa2",
        "0.112",
        "--modes",
        "3",
        "--no-orientation-flow",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--no-orientation-flow"));
}

/// The MD branch at kappa2 = 0.13 with shape modes 2..`modes` (N = 96), written to `dir`:
/// `continue --json`.
fn md_line(modes: &str, dir: &std::path::Path) -> serde_json::Value {
    json(&run(&[
        "continue",
        "--modes",
        modes,
        "--branch",
        "md",
        "--kappa2",
        "0.13",
        "--from",
        "0.0775",
        "--to",
        "0.1",
        "--n",
        "96",
        "--max-points",
        "24",
        "--ds-max",
        "0.08",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]))
}

/// The 3-mode MD line (`at`, `v`, `a3`, `stable` of its table) against two independent
/// computations at its first stable state.
fn agrees_with_newton_and_time_stepping(at: &[f64], v: &[f64], a3: &[f64], stable: &[bool]) {
    // The branch against two independent computations at a stable state of the table:
    // Newton at that point (`stability --modes 3`) and time stepping to it (`simulate
    // --modes 3`). (At N = 64 the 3-mode model has a second stable MD state there, v = 0.497
    // against 0.657: an under-resolved grid; at N = 96 one, which both reach to 1e-10.)
    let j = (0..stable.len())
        .filter(|&i| stable[i])
        .min_by(|&x, &y| at[x].total_cmp(&at[y]))
        .unwrap();
    let eta = format!("{}", at[j]);
    let st = stability(&[
        "--eta-t", &eta, "--kappa2", "0.13", "--state", "md", "--modes", "3", "--n", "96",
    ]);
    let f = |x: &serde_json::Value| x.as_f64().unwrap();
    assert!(
        (f(&st["v"]) - v[j]).abs() < 1e-8 && (f(&st["a_k"][1]) - a3[j]).abs() < 1e-8,
        "{st}"
    );
    assert_eq!(st["stable"], true, "{st}");
    let stepped = json(&run(&[
        "simulate",
        "--eta-t",
        &eta,
        "--kappa2",
        "0.13",
        "--ic",
        "custom:0.6,0,-0.15,0",
        "--modes",
        "3",
        "--n",
        "96",
        "--steady-tol",
        "1e-9",
        "--t-max",
        "5000",
        "--json",
    ]));
    assert_eq!(stepped["status"], "steady", "{stepped}");
    assert!((f(&stepped["v"]) - v[j]).abs() < 1e-6, "{stepped} {}", v[j]);
    assert!(
        (f(&stepped["a_k"][1]) - a3[j]).abs() < 1e-6,
        "{stepped} {}",
        a3[j]
    );
}

#[test]
fn continue_with_modes_follows_the_k_mode_branch_with_its_stability() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c3");
    let line = md_line;
    let c = line("3", &out);
    assert_eq!(c["modes"], 3, "{c}");
    assert_eq!(c["eta_k_exponent"], 0.0, "{c}");
    // The same keys as the 2-mode command's, at every level.
    let two = line("2", &dir.path().join("c2"));
    let keys =
        |v: &serde_json::Value| -> Vec<String> { v.as_object().unwrap().keys().cloned().collect() };
    let sn = |v: &serde_json::Value| {
        v["events"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["kind"] == "SN")
            .cloned()
            .unwrap()
    };
    assert_eq!(keys(&c), keys(&two), "{c} {two}");
    assert_eq!(
        keys(&c["branches"][0]),
        keys(&two["branches"][0]),
        "{c} {two}"
    );
    assert_eq!(keys(&sn(&c)), keys(&sn(&two)), "{c} {two}");
    // One fold on this line, located as every 2-mode event is.
    let events = c["events"].as_array().unwrap();
    assert_eq!(events.len(), 1, "{c}");
    assert_eq!(events[0]["kind"], "SN", "{c}");
    assert_eq!(events[0]["a_k"].as_array().unwrap().len(), 2, "{c}");
    assert!(events[0]["precision"].as_f64().unwrap() < 1e-7, "{c}");
    let fold = events[0]["at"].as_f64().unwrap();
    // The branch turns back at the fold and is stable on one side of it only: the table in
    // branch order, its 2-mode columns and a3, b3 after them.
    let t = read(&out.join("continuation_modes3_kappa2_0.13.parquet"));
    let (at, v, a3, b3) = (
        floats(&t, "at"),
        floats(&t, "v"),
        floats(&t, "a3"),
        floats(&t, "b3"),
    );
    assert!(at.iter().all(|x| *x <= fold + 1e-12), "{c}");
    assert!(b3.iter().all(|b| *b == 0.0), "{b3:?}");
    let stable: Vec<bool> = {
        let s = t.column("stable").unwrap().bool().unwrap().clone();
        (0..s.len()).map(|i| s.get(i).unwrap()).collect()
    };
    let changes = stable.windows(2).filter(|w| w[0] != w[1]).count();
    assert_eq!(changes, 1, "{stable:?}");
    let counted = c["branches"][0]["stable_points"].as_u64().unwrap() as usize;
    assert_eq!(counted, stable.iter().filter(|s| **s).count(), "{c}");
    agrees_with_newton_and_time_stepping(&at, &v, &a3, &stable);
    assert!(out.join("continuation_modes3_kappa2_0.13.png").exists());
    refused(
        &[
            "continue",
            "--kappa2",
            "0.13",
            "--from",
            "0.077",
            "--to",
            "0.1",
            "--out",
            out.to_str().unwrap(),
        ],
        &[
            (&["--modes", "1"], "modes"),
            (&["--modes", "8", "--n", "64"], "modes"),
            (
                &["--modes", "2", "--eta-k-exponent", "-1"],
                "eta_k_exponent",
            ),
        ],
    );
}
