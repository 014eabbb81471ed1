//! Continuation checked against independent computations: the time stepper's steady states
//! and its response to small perturbations, the one-parameter fold against the
//! two-parameter fold curve, and the branches' meeting points against the exact thresholds.
use droplet_solver::continuation::arclength::ArclengthOptions;
use droplet_solver::continuation::fold_curve::md_fold_curve;
use droplet_solver::continuation::onset_lines::mc_line;
use droplet_solver::continuation::window::{Axis, Window};
use droplet_solver::continuation::{
    branch::follow, branch::Branch, branch::BranchPoint, branch::Line, problem::Family,
};
use droplet_solver::model::mirror::MirrorLine;
use droplet_solver::model::param::ModelParam;
use droplet_solver::roots::balances::Balances;
use droplet_solver::roots::steady_solver::TwoModeSolver;
use droplet_solver::roots::thresholds::{ic_thresholds, id_onset};
use droplet_solver::stepping::{comoving_etd::TwoModeEtd, Scheme, Stepper};
use droplet_solver::{
    contract::settings::SolverSettings, model::initial::InitialCondition,
    model::params::ModelParams, model::state::DropletState, runs::driver::simulate,
};

/// `family` along eta_t at fixed `kappa2` on the x axis.
fn branch(family: Family, kappa2: f64, from: f64, to: f64, n: usize) -> Branch {
    let line = Line {
        base: ModelParams::at(from, kappa2),
        n,
        parameter: ModelParam::EtaT,
        from,
        to,
        max_points: 400,
        opts: ArclengthOptions::default(),
    };
    follow(&line, family, MirrorLine::X).unwrap()
}

/// The branch's state at `eta_t` (the line's first point is located exactly at `from`).
fn at(b: &Branch, eta_t: f64) -> &BranchPoint {
    let p = b
        .points
        .iter()
        .min_by(|x, y| (x.eta_t - eta_t).abs().total_cmp(&(y.eta_t - eta_t).abs()))
        .unwrap();
    assert!((p.eta_t - eta_t).abs() < 1e-12, "{p:?}");
    p
}

#[test]
fn stable_states_are_the_time_steppers_steady_states() {
    // N = 128: at N = 96 the grid's anisotropy makes the x-axis ID's rotation mode +0.117,
    // no longer near-neutral, so that state is unstable there (it turns to the diagonal).
    let n = 128;
    // (family, eta_t, kappa2, initial condition on the mirror axis)
    let cases = [
        (Family::MdMinor, 0.085, 0.112, "i'"),
        (Family::MdMinor, 0.078, 0.13, "i'"),
        (Family::ID, 0.1, 0.105, "custom:0,0,0.1,0"),
        (Family::IC, 0.09, 0.14, "custom:0.001,0,0.001,0"),
    ];
    for (family, eta_t, kappa2, ic) in cases {
        let b = branch(family, kappa2, eta_t, eta_t + 0.002, n);
        let p = at(&b, eta_t);
        assert!(p.verdict.stable(), "{family:?} at {eta_t}: {p:?}");
        // Time stepping alone (the paper's test, tightened), the independent computation.
        let settings = SolverSettings {
            n,
            steady_tol: 1e-10,
            t_max: 5000.0,
            steady: droplet_solver::contract::ending::SteadyMethod::Test,
            ..SolverSettings::default()
        };
        let ic = InitialCondition::parse(ic).unwrap();
        let out = simulate(&ModelParams::at(eta_t, kappa2), &ic, &settings).unwrap();
        assert_eq!(
            out.status,
            droplet_solver::contract::outcome::RunStatus::Steady,
            "{out:?}"
        );
        assert!(
            (out.v - p.v).abs() <= 1e-6 && (out.s - p.s).abs() <= 1e-6,
            "{family:?} at ({eta_t}, {kappa2}): time stepping v = {}, s = {}; continuation v = {}, s = {}",
            out.v,
            out.s,
            p.v,
            p.s
        );
    }
}

/// Distance from the state `(v, a2)` on the x axis after stepping `t` time units from it,
/// perturbed by `dv` in the speed, with its own steady field.
fn departure(p: ModelParams, n: usize, v: f64, a2: f64, dv: f64, t: f64) -> f64 {
    let mut solver = TwoModeSolver::new(p, n).unwrap();
    let field = solver.field_and_forces(v, 0.0, a2, 0.0).0.to_vec();
    let start = DropletState {
        vx: v + dv,
        a2,
        ..DropletState::default()
    };
    let mut scheme = TwoModeEtd::new(p, n, start, false).unwrap();
    scheme.set_spectrum(&field);
    let dt = 0.01;
    for _ in 0..(t / dt).round() as usize {
        scheme.step(dt);
    }
    let s = scheme.state();
    (s.vx.hypot(s.vy) - v).abs() + (s.a2.hypot(s.b2) - a2.abs()).abs()
}

#[test]
fn an_unstable_state_leaves_its_branch_and_a_stable_one_returns() {
    // Between the onset of motion and the fold at kappa2 = 0.13 the MD branch has a stable
    // (fast) and an unstable (slow) state at the same eta_t.
    let n = 64;
    let b = branch(Family::MdMinor, 0.13, 0.07, 0.09, n);
    let sn = b.events.iter().find(|e| e.kind == "SN").expect("a fold");
    let eta_t = sn.point.eta_t - 0.0015;
    let near = |stable: bool| {
        b.points
            .iter()
            .filter(|p| p.verdict.stable() == stable)
            .min_by(|x, y| (x.eta_t - eta_t).abs().total_cmp(&(y.eta_t - eta_t).abs()))
            .unwrap()
            .clone()
    };
    let (up, down) = (near(true), near(false));
    assert!(up.v > down.v, "{up:?} {down:?}");
    let growth = down.verdict.max_re;
    assert!(growth > 0.0, "{down:?}");
    // Long enough for a 1e-4 perturbation to grow 1000-fold at the unstable rate.
    let t = (1000f64.ln() / growth).min(400.0);
    let away = departure(
        ModelParams::at(down.eta_t, 0.13),
        n,
        down.v,
        down.z[2],
        1e-4,
        t,
    );
    assert!(
        away > 1e-2,
        "unstable state stayed within {away} after t = {t}: {down:?}"
    );
    // The stable state's slowest decay is about 0.06: back within 1e-8 by t = 250.
    let back = departure(
        ModelParams::at(up.eta_t, 0.13),
        n,
        up.v,
        up.z[2],
        1e-4,
        250.0,
    );
    assert!(
        back < 1e-7,
        "stable state left by {back} after t = 250: {up:?}"
    );
}

#[test]
fn the_fold_curve_passes_through_the_one_parameter_folds() {
    // N = 128: coarser grids distort the shape thresholds by their anisotropy (the a2 and b2
    // onsets split by 0.015 at N = 64), and with them the fold curve's ends.
    let n = 128;
    let window = (
        Axis::new(ModelParam::EtaT, (0.07, 0.1)),
        Axis::new(ModelParam::Kappa2, (0.1, 0.17)),
    );
    let base = ModelParams::at(0.07, 0.1);
    let curve = md_fold_curve(&base, n, MirrorLine::X, window, &[0.13]).unwrap();
    assert!(curve.len() > 10, "{curve:?}");
    for &(eta_t, kappa2) in [curve[curve.len() / 4], curve[curve.len() / 2]].iter() {
        let b = branch(Family::MdMinor, kappa2, 0.07, 0.1, n);
        let sn = b.events.iter().find(|e| e.kind == "SN").expect("a fold");
        assert!(
            (sn.point.eta_t - eta_t).abs() < 1e-7,
            "kappa2 = {kappa2}: fold curve {eta_t}, branch {}",
            sn.point.eta_t
        );
    }
}

#[test]
fn the_mc_onset_line_is_where_the_moving_branch_has_s_at_the_threshold() {
    // Independent path: the arclength continuation of the moving branch along eta_t at
    // kappa2 = 0.16, and where its s crosses 0.01 between two of its points (linear
    // interpolation; the points are ~1e-4 apart there).
    let n = 128;
    let th = ic_thresholds(&ModelParams::at(0.085, 0.16), n, 2).unwrap();
    let w = Window::paper(ModelParams::at(0.07, 0.16), n, (0.07, 0.1), (0.16, 0.17), 3);
    let two = |w: &Window| Balances::new(w.base, w.n).unwrap();
    let line = mc_line(two(&w), &w, th.eta_t).unwrap();
    assert_eq!(line.len(), 3, "{line:?}");
    let (eta_mc, k) = line[2];
    assert!((k - 0.16).abs() < 1e-12);
    // MC lies between the threshold curve and the onset of motion. Below kappa2 ~ 0.154 the
    // onset is subcritical and the s = 0.01 state unstable: the line stops there.
    let low = Window {
        y: Axis::new(ModelParam::Kappa2, (0.13, 0.17)),
        samples: 5,
        ..w.clone()
    };
    let stable_part = mc_line(two(&low), &low, th.eta_t).unwrap();
    assert!(
        stable_part.len() == 2 && stable_part[1].1 == 0.16,
        "{stable_part:?}"
    );
    assert!(
        eta_mc < th.eta_t && eta_mc > th.eta_t - 1e-3,
        "{eta_mc} {}",
        th.eta_t
    );
    let b = branch(Family::MdMinor, 0.16, 0.0755, th.eta_t - 1e-6, n);
    let crossing = b
        .points
        .windows(2)
        .find(|w| (w[0].s - 0.01) * (w[1].s - 0.01) <= 0.0)
        .map(|w| {
            let t = (0.01 - w[0].s) / (w[1].s - w[0].s);
            w[0].eta_t + t * (w[1].eta_t - w[0].eta_t)
        })
        .expect("the branch's s crosses 0.01");
    assert!(
        (crossing - eta_mc).abs() < 2e-6,
        "line {eta_mc}, branch {crossing}"
    );
}

#[test]
fn branches_meet_ic_and_id_at_the_exact_thresholds() {
    let n = 128;
    let th = ic_thresholds(&ModelParams::at(0.085, 0.13), n, 2).unwrap();
    let md = branch(Family::MdMinor, 0.13, 0.07, 0.1, n);
    let meet = md.events.iter().find(|e| e.what == "meets IC").unwrap();
    assert!(
        (meet.point.eta_t - th.eta_t).abs() < 1e-9,
        "{meet:?} vs {th:?}"
    );
    // The resting disk's own eigenvalue crossing is the same point.
    let ic = branch(Family::IC, 0.13, 0.07, 0.1, n);
    let p = ic.events.iter().find(|e| e.kind == "P").unwrap();
    assert!((p.point.eta_t - th.eta_t).abs() < 1e-9, "{p:?} vs {th:?}");
    // Below the onset of deformation MD bifurcates from ID where ID's drift sets in.
    let md = branch(Family::MdMinor, 0.117, 0.07, 0.1, n);
    let meet = md.events.iter().find(|e| e.what == "meets ID").unwrap();
    let mut solver = TwoModeSolver::new(ModelParams::at(0.085, 0.117), n).unwrap();
    let (onset, _) = id_onset(&mut solver, MirrorLine::X, 0.117, 0.1).unwrap();
    assert!(
        (meet.point.eta_t - onset).abs() < 1e-9,
        "{meet:?} vs {onset}"
    );
}

#[test]
fn the_resting_disks_drift_eigenvalue_is_the_time_steppers_decay_rate() {
    // A small push along x decays at the drift eigenvalue once the field's own transients
    // (rate >= 1) are gone.
    let n = 96;
    let p = ModelParams::at(0.085, 0.13);
    let b = branch(Family::IC, 0.13, 0.085, 0.086, n);
    let drift = at(&b, 0.085).verdict.max_re;
    let settings = |t_max| SolverSettings {
        n,
        dt: 0.005,
        tol: 0.0,
        t_max,
        steady_tol: 1e-30,
        // Plain time stepping to exactly t_max.
        landing: false,
        run_on: false,
        ..SolverSettings::default()
    };
    let ic = InitialCondition::parse("custom:0.001,0,0,0").unwrap();
    let v = |t| simulate(&p, &ic, &settings(t)).unwrap().v;
    let rate = (v(30.0) / v(15.0)).ln() / 15.0;
    assert!(
        (rate - drift).abs() < 1e-3,
        "rate {rate} vs eigenvalue {drift}"
    );
}

#[test]
fn a_count_changed_by_the_rotation_mode_is_its_own_event_and_every_crossing_is_at_zero() {
    // ID on the diagonal at eta_t = 0.085, kappa2 from 0.1 to 0.17, N = 64: its rotation
    // mode's rate passes 0.05 (the most the verdict sets aside) and the count of growing
    // modes changes without any eigenvalue crossing zero: R events, located where the rate is
    // 0.05. Every P or H event's eigenvalue is zero at its located point.
    let line = Line {
        base: ModelParams::at(0.085, 0.1),
        n: 64,
        parameter: ModelParam::Kappa2,
        from: 0.1,
        to: 0.17,
        max_points: 400,
        opts: ArclengthOptions::default(),
    };
    let b = follow(&line, Family::ID, MirrorLine::Diagonal).unwrap();
    let rotations: Vec<_> = b.events.iter().filter(|e| e.kind == "R").collect();
    assert!(!rotations.is_empty(), "{:?}", b.events);
    for e in rotations {
        let l = e.eigenvalue.expect("the rotation mode's rate");
        assert!((l[0].abs() - 0.05).abs() < 1e-6, "{e:?}");
        assert!(e.precision < 1e-7, "{e:?}");
    }
    for e in b.events.iter().filter(|e| e.kind == "P" || e.kind == "H") {
        if let Some(l) = e.eigenvalue {
            assert!(l[0].abs() < 1e-6, "{e:?}");
        }
    }
}
