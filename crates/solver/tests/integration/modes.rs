//! The model with shape modes `2..K`: where its runs end either side of its own MD fold.
use droplet_solver::continuation::fold_curve::walk_to_fold;
use droplet_solver::continuation::window::Axis;
use droplet_solver::model::mirror::MirrorLine;
use droplet_solver::roots::balances::Balances;

use droplet_solver::contract::{outcome::RunStatus, settings::SolverSettings};
use droplet_solver::model::{
    classify::StateClass, initial::InitialCondition, param::ModelParam, params::ModelParams,
};
use droplet_solver::runs::driver::simulate;
use droplet_solver::stepping::SchemeKind;

/// The `eta_t` of the MD branch's fold at `kappa2 = 0.13` with modes `2..=k_max` at N = 96.
fn fold(k_max: usize) -> f64 {
    let balances = Balances::new(ModelParams::at(0.07, 0.13).with_modes(k_max), 96).unwrap();
    let line = Axis::new(ModelParam::EtaT, (0.07, 0.1));
    walk_to_fold(balances, MirrorLine::X, line, 0.13)
        .expect("the MD branch folds")
        .x
}

#[test]
fn with_four_modes_the_ic_md_band_ends_at_the_four_mode_fold() {
    // kappa2 = 0.13, N = 96: with modes 2..4 the MD branch folds left of the 2-mode fold
    // (measured: at eta_t = 0.0782561 against 0.0794535), so
    // eta_t = 0.0786 lies inside the 2-mode IC/MD band but right of the 4-mode fold, and
    // 0.0775 between the onset of motion and the 4-mode fold. The runs (the defaults, every
    // initial condition) agree: at 0.0786 every run rests on the disk (single-state IC); at
    // 0.0775 the moving conditions i and ii reach MD and the resting iii and iv stay IC
    // (bistable IC/MD). The same holds at N = 192 (results/k-mode-steps).
    let (two, four) = (fold(2), fold(4));
    assert!(
        four > 0.0775 && four < 0.0786 && two > 0.0786,
        "{two} {four}"
    );
    use StateClass::{IC, MD};
    for (eta_t, classes) in [(0.0786, [IC, IC, IC, IC]), (0.0775, [MD, MD, IC, IC])] {
        for (ic, class) in ["i", "ii", "iii", "iv"].into_iter().zip(classes) {
            let out = simulate(
                &ModelParams::at(eta_t, 0.13).with_modes(4),
                &InitialCondition::parse(ic).unwrap(),
                &SolverSettings {
                    n: 96,
                    ..SolverSettings::default()
                },
            )
            .unwrap();
            assert_eq!(out.status, RunStatus::Steady, "{eta_t} {ic}: {out:?}");
            assert_eq!(out.class, Some(class), "{eta_t} {ic}: {out:?}");
        }
    }
}

/// One run of `results/k-mode-endings/runs/*.json`.
pub(crate) struct Ending {
    pub(crate) eta_t: f64,
    pub(crate) kappa2: f64,
    pub(crate) ic: String,
    pub(crate) class: Option<String>,
    pub(crate) v: f64,
    pub(crate) s: f64,
    pub(crate) orientation_deg: f64,
}

/// The committed runs of `results/k-mode-endings/runs/NAME.json`.
pub(crate) fn committed(name: &str) -> Vec<Ending> {
    let path = format!(
        "{}/../../results/k-mode-endings/runs/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let rows: Vec<serde_json::Value> = serde_json::from_str(&text).unwrap();
    rows.iter()
        .map(|r| Ending {
            eta_t: r["eta_t"].as_f64().unwrap(),
            kappa2: r["kappa2"].as_f64().unwrap(),
            ic: r["ic"].as_str().unwrap().to_string(),
            class: r["class"].as_str().map(String::from),
            v: r["v"].as_f64().unwrap(),
            s: r["s"].as_f64().unwrap(),
            orientation_deg: r["orientation_deg"].as_f64().unwrap(),
        })
        .collect()
}

/// The direction of motion (degrees), or the long axis at rest.
pub(crate) fn orientation_deg(out: &droplet_solver::contract::outcome::RunOutcome) -> f64 {
    let st = &out.state;
    if out.v > 1e-9 {
        st.vy.atan2(st.vx).to_degrees()
    } else {
        0.5 * st.b2.atan2(st.a2).to_degrees()
    }
}

/// Whether a run ends where pure time stepping does: the class, `v` and `s` within 1e-4, the
/// orientation within 0.1 degree (moving states; a resting disk has none).
pub(crate) fn same_end(out: &droplet_solver::contract::outcome::RunOutcome, pure: &Ending) -> bool {
    let turn = (orientation_deg(out) - pure.orientation_deg + 180.0).rem_euclid(360.0) - 180.0;
    out.class.map(|c| c.as_str().to_string()) == pure.class
        && (out.v - pure.v).abs() < 1e-4
        && (out.s - pure.s).abs() < 1e-4
        && (pure.v < 1e-4 || turn.abs() < 0.1)
}

#[test]
fn three_mode_runs_end_where_pure_time_stepping_ends() {
    // Modes 2..3 at N = 96, the defaults, at (0.085, 0.112), (0.078, 0.13) and (0.088, 0.1095)
    // from every initial condition: the Newton finish (with its turn search) ends each run on
    // the state that pure time stepping (the paper's test alone at steady_tol 1e-9, t_max
    // 20000) reaches: results/k-mode-endings/runs/pure-k3-n96.json. Those orientations include
    // 12 degrees off the x axis at (0.078, 0.13) from i and ii, and 38.5 and 50.9 degrees from
    // iv; two of the references are recomputed here by pure time stepping.
    let pure = committed("pure-k3-n96");
    assert_eq!(pure.len(), 12);
    let settings = SolverSettings {
        n: 96,
        ..SolverSettings::default()
    };
    for end in &pure {
        let p = ModelParams::at(end.eta_t, end.kappa2).with_modes(3);
        let ic = InitialCondition::parse(&end.ic).unwrap();
        let out = simulate(&p, &ic, &settings).unwrap();
        assert_eq!(out.status, RunStatus::Steady, "{}: {out:?}", end.ic);
        assert!(
            same_end(&out, end),
            "({}, {}) {}: {out:?} against {} {} {}",
            end.eta_t,
            end.kappa2,
            end.ic,
            end.v,
            end.s,
            end.orientation_deg
        );
    }
    let stepping = SolverSettings {
        steady: droplet_solver::contract::ending::SteadyMethod::Test,
        steady_tol: 1e-9,
        t_max: 20000.0,
        ..settings
    };
    for (eta_t, kappa2, ic) in [(0.085, 0.112, "iv"), (0.088, 0.1095, "i")] {
        let end = pure
            .iter()
            .find(|e| e.eta_t == eta_t && e.kappa2 == kappa2 && e.ic == ic)
            .unwrap();
        let p = ModelParams::at(eta_t, kappa2).with_modes(3);
        let out = simulate(&p, &InitialCondition::parse(ic).unwrap(), &stepping).unwrap();
        assert!(same_end(&out, end), "{ic}: {out:?}");
    }
}

#[test]
fn a_three_mode_run_turning_to_a_root_of_the_lattice_ends_there() {
    // Modes 2..3 at N = 192, (0.085, 0.112) from iv: at t = 619 the run is 17 degrees from the
    // diagonal MD (unstable in rotation), settled in speed and deformation, and turning
    // towards it, to a root 2.25 degrees short of it where pure time stepping ends
    // (results/k-mode-endings/runs/pure-k3-n192.json). The turn search from the diagonal
    // finds the y-axis MD, which the run is turning away from; the run must not end there
    // (numerics modes-7: it did with the predictor extrapolated and the old rule).
    let pure = committed("pure-k3-n192");
    let end = pure
        .iter()
        .find(|e| e.eta_t == 0.085 && e.kappa2 == 0.112 && e.ic == "iv")
        .unwrap();
    assert!(
        (end.orientation_deg - 132.75).abs() < 0.01,
        "{}",
        end.orientation_deg
    );
    let settings = SolverSettings {
        n: 192,
        ..SolverSettings::default()
    };
    let p = ModelParams::at(0.085, 0.112).with_modes(3);
    let out = simulate(&p, &InitialCondition::parse("iv").unwrap(), &settings).unwrap();
    assert!(same_end(&out, end), "{out:?}");
}

#[test]
fn a_three_mode_run_ends_steady_on_the_three_mode_md_state() {
    // Fig. 1c with modes 2..3 at N = 96 from IC i: the Newton finish ends the run on the
    // MD state of the steady solver, a3 included, long before the rates fall to the test.
    let p = ModelParams::at(0.085, 0.112).with_modes(3);
    let settings = SolverSettings {
        n: 96,
        dt: 0.05,
        ..SolverSettings::default()
    };
    let ic = InitialCondition::parse("i").unwrap();
    let out = simulate(&p, &ic, &settings).unwrap();
    assert_eq!(out.status, RunStatus::Steady, "{out:?}");
    assert_eq!(out.class, Some(StateClass::MD), "{out:?}");
    assert_eq!(
        out.ended_by,
        Some(droplet_solver::contract::ending::Ending::Newton),
        "{out:?}"
    );
    let mut solver = droplet_solver::roots::steady_solver::SteadySolver::new(p, 96).unwrap();
    let md = droplet_solver::roots::named_state::md_state(&mut solver, 3).unwrap();
    assert!((out.v - md.v).abs() < 1e-8, "{out:?} {md:?}");
    let a3 = out.higher_modes[0].hypot(out.higher_modes[1]);
    assert!((a3 - md.a[1].abs()).abs() < 1e-8, "{out:?} {md:?}");
    assert_eq!(out.higher_modes.len(), 2);
    // With the friction law eta_k = (2/k) eta2 (mode 3 relaxes 1.5 times faster), the run
    // takes another path to the same state: eta_k enters no steady state.
    let faster = simulate(
        &ModelParams {
            eta_k_exponent: -1.0,
            ..p
        },
        &ic,
        &settings,
    )
    .unwrap();
    assert_eq!(faster.status, RunStatus::Steady, "{faster:?}");
    assert!((faster.v - md.v).abs() < 1e-8, "{faster:?} {md:?}");
    let a3 = faster.higher_modes[0].hypot(faster.higher_modes[1]);
    assert!((a3 - md.a[1].abs()).abs() < 1e-8, "{faster:?} {md:?}");
    assert_ne!(faster.steps, out.steps);
}

#[test]
fn the_friction_law_sets_how_fast_a_mode_relaxes() {
    // A mode-3 dent on the resting disk at (0.1, 0.16), where the disk is stable, with
    // both schemes: after 0.5 time units it has relaxed further with eta_3 = (2/3) eta2
    // (exponent -1) than with eta_3 = eta2, and less with eta_3 = (3/2) eta2 (exponent 1);
    // its mean rate goes about as 1 / eta_3 (ratio 1.5; measured 1.583 with the spectral
    // scheme, 1.585 with the paper's: the field building up from 0 moves it a little).
    let p = ModelParams::at(0.1, 0.16).with_modes(3);
    let ic = InitialCondition::parse("custom:0,0,0,0,0.05,0").unwrap();
    for scheme in [SchemeKind::Spectral, SchemeKind::PaperFd] {
        let a3 = |exponent: f64| {
            let settings = SolverSettings {
                n: 64,
                dt: 2e-3,
                tol: 0.0,
                t_max: 0.5,
                run_on: false,
                scheme,
                steady: match scheme {
                    SchemeKind::Spectral => droplet_solver::contract::ending::SteadyMethod::Newton,
                    SchemeKind::PaperFd => droplet_solver::contract::ending::SteadyMethod::Test,
                },
                ..SolverSettings::default()
            };
            let p = ModelParams {
                eta_k_exponent: exponent,
                ..p
            };
            simulate(&p, &ic, &settings).unwrap().higher_modes[0]
        };
        let (slow, base, fast) = (a3(1.0), a3(0.0), a3(-1.0));
        assert!(
            0.0 < fast && fast < base && base < slow && slow < 0.05,
            "{scheme}"
        );
        let rate = |a: f64| -(a / 0.05).ln();
        let ratio = rate(fast) / rate(base);
        assert!(ratio > 1.3 && ratio < 1.8, "{scheme}: {ratio}");
    }
}

#[test]
fn a_four_mode_run_leaning_off_a_line_unstable_in_rotation_ends_where_it_turns_to() {
    // Modes 2..4 at (0.072, 0.104), N = 192, from ii (leaning 0.01 rad off the x axis): the
    // run settles on the fast x-axis MD (v = 1.0403) within t = 40, whose only growing mode
    // is the rotation (+9.3e-4), and turns to the diagonal MD over some 6000 time units. The
    // committed map (results/fig2a-modes, runs.parquet, stepped through the turn) ends it
    // there: v = 1.0684356, motion along the diagonal, at t = 6237. The Newton finish's turn
    // search finds that root, 3 % faster than the one the run has settled on (the box's
    // anisotropy), and ends the run there as soon as it has settled on the axis root.
    let out = simulate(
        &ModelParams::at(0.072, 0.104).with_modes(4),
        &InitialCondition::parse("ii").unwrap(),
        &SolverSettings::default(),
    )
    .unwrap();
    assert_eq!(out.status, RunStatus::Steady, "{out:?}");
    assert_eq!(out.class, Some(StateClass::MD), "{out:?}");
    assert!((out.v - 1.0684356).abs() < 1e-6, "{out:?}");
    assert!((orientation_deg(&out) - 45.0).abs() < 1e-6, "{out:?}");
    assert!(out.t_end < 100.0, "{out:?}");
}

#[test]
fn a_four_mode_run_leaving_the_disk_lands_where_time_stepping_takes_it() {
    // Modes 2..4 at (0.076, 0.144), N = 96, from iii: the resting disk is unstable (its drift
    // pair grows at 3.8e-3) and the run leaves it slowly. Without the landing it steps to
    // t = 3055 and ends by Newton on the diagonal MD (v = 0.594758); the landing walks the
    // speed family (the shape modes 2..4 solved at each speed) to that root at t = 22.
    let settings = SolverSettings {
        n: 96,
        ..SolverSettings::default()
    };
    let run = |landing: bool| {
        simulate(
            &ModelParams::at(0.076, 0.144).with_modes(4),
            &InitialCondition::parse("iii").unwrap(),
            &SolverSettings {
                landing,
                ..settings
            },
        )
        .unwrap()
    };
    let (landed, stepped) = (run(true), run(false));
    for out in [&landed, &stepped] {
        assert_eq!(out.status, RunStatus::Steady, "{out:?}");
        assert_eq!(out.class, Some(StateClass::MD), "{out:?}");
    }
    assert_eq!(
        landed.ended_by,
        Some(droplet_solver::contract::ending::Ending::Landing),
        "{landed:?}"
    );
    assert!(
        landed.t_end < 100.0 && stepped.t_end > 1000.0,
        "{landed:?} {stepped:?}"
    );
    assert!(
        (landed.v - stepped.v).abs() < 1e-9,
        "{landed:?} {stepped:?}"
    );
    assert!(
        (landed.s - stepped.s).abs() < 1e-9,
        "{landed:?} {stepped:?}"
    );
    let turn = orientation_deg(&landed) - orientation_deg(&stepped);
    assert!(turn.abs() < 1e-6, "{landed:?} {stepped:?}");
}
