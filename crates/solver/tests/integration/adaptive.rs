//! Adaptive ETD2RK stepping: same fixed points as fixed steps, error bounded by the tolerance,
//! errors falling with the tolerance, steps growing during relaxation, recording times hit,
//! large fixed steps flagged, and projective steps along a slow phase.
use droplet_solver::model::mirror::MirrorLine;
use droplet_solver::{
    contract::outcome::RunStatus, contract::settings::SolverSettings, model::classify::StateClass,
    model::initial::InitialCondition, model::params::ModelParams,
    roots::steady_solver::TwoModeSolver, runs::driver::simulate, runs::driver::Run,
};

/// Time stepping to the paper's test (what these tests are about; the Newton finish would end
/// the runs before their step sizes tell anything).
fn settings(n: usize, tol: f64) -> SolverSettings {
    SolverSettings {
        n,
        tol,
        t_max: 3000.0,
        steady: droplet_solver::contract::ending::SteadyMethod::Test,
        ..SolverSettings::default()
    }
}

/// An MD point at N = 64 (deep in the MD region at this resolution), from IC (i').
fn md() -> (ModelParams, InitialCondition) {
    (
        ModelParams::at(0.07, 0.115),
        InitialCondition::parse("i'").unwrap(),
    )
}

#[test]
fn adaptive_runs_reach_the_newton_state_in_far_fewer_steps() {
    let (p, ic) = md();
    let newton = TwoModeSolver::new(p, 64)
        .unwrap()
        .newton(0.7, -0.3, 1e-13)
        .unwrap();
    let fixed = simulate(&p, &ic, &settings(64, 0.0)).unwrap();
    let adaptive = simulate(&p, &ic, &settings(64, 1e-4)).unwrap();
    for out in [&fixed, &adaptive] {
        assert_eq!(out.status, RunStatus::Steady, "{out:?}");
        assert_eq!(out.class, Some(StateClass::MD));
        // The steady test (change < 1e-6 per 0.1) stops within ~1e-5 / (slowest decay rate)
        // of the fixed point: a few 1e-5 here.
        assert!(
            (out.v - newton.v.abs()).abs() < 1e-4,
            "{} vs {}",
            out.v,
            newton.v
        );
        assert!(
            (out.s - newton.a2.abs()).abs() < 1e-4,
            "{} vs {}",
            out.s,
            newton.a2
        );
    }
    assert!(
        adaptive.steps * 4 < fixed.steps,
        "adaptive {} steps vs fixed {}",
        adaptive.steps,
        fixed.steps
    );
    // Every accepted step met the tolerance.
    assert!(adaptive.max_step_error.unwrap() <= 1e-4);
    assert!(fixed.dt_warning(&settings(64, 0.0)).is_none());
}

#[test]
fn transient_error_falls_with_the_tolerance() {
    // t <= 6 through the MD instability from IC (i), against a small fixed step.
    let (p, _) = md();
    let ic = InitialCondition::parse("i").unwrap();
    let series = |s: SolverSettings| {
        let s = SolverSettings {
            t_max: 6.0,
            steady_tol: f64::MIN_POSITIVE,
            ..s
        };
        Run::new(&p, &ic, &s)
            .unwrap()
            .record_every(Some(0.25))
            .execute()
            .series
    };
    let reference = series(SolverSettings {
        dt: 0.001,
        ..settings(48, 0.0)
    });
    let error = |tol: f64| {
        let run = series(settings(48, tol));
        assert_eq!(run.len(), reference.len(), "samples at the recording times");
        run.iter()
            .zip(&reference)
            .map(|(a, b)| {
                assert!((a.t - b.t).abs() < 1e-9, "{} vs {}", a.t, b.t);
                (a.v - b.v).abs().max((a.s - b.s).abs())
            })
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (error(1e-3), error(1e-5));
    assert!(
        fine < coarse / 5.0,
        "tol 1e-3: {coarse:.2e}, 1e-5: {fine:.2e}"
    );
    assert!(fine < 1e-3, "{fine:.2e}");
}

#[test]
fn large_fixed_steps_are_flagged_and_adaptive_needs_the_spectral_pde() {
    let (p, ic) = md();
    let s = SolverSettings {
        n: 32,
        dt: 0.3,
        tol: 0.0,
        steady_window: 0.3,
        t_max: 30.0,
        ..SolverSettings::default()
    };
    let out = simulate(&p, &ic, &s).unwrap();
    let w = out.dt_warning(&s).expect("dt = 0.3 is flagged");
    assert!(w.contains("dt = 0.3"), "{w}");
    for bad in [
        SolverSettings {
            tol: 1e-4,
            ..SolverSettings::paper_fd()
        },
        SolverSettings {
            tol: 1e-4,
            ..SolverSettings::ode()
        },
        SolverSettings {
            dt_max: 0.01,
            ..SolverSettings::default()
        },
    ] {
        assert!(bad.validate().is_err(), "{bad:?}");
    }
}

#[test]
fn diagonal_newton_matches_the_x_axis_for_a_rotation_invariant_state() {
    // A resting droplet's deformation is the same on both mirror axes up to the box's images;
    // deep in the ID region (far from thresholds) the two agree closely.
    let p = ModelParams::at(0.1, 0.105);
    let mut s = TwoModeSolver::new(p, 64).unwrap();
    let x = s.newton_on(MirrorLine::X, 0.0, 0.2, 1e-13).unwrap();
    let d = s.newton_on(MirrorLine::Diagonal, 0.0, 0.2, 1e-13).unwrap();
    assert!(x.a2 > 0.1, "{x:?}");
    assert!((x.a2 - d.a2).abs() < 0.02 * x.a2, "{x:?} vs {d:?}");
}

#[test]
fn projective_steps_move_a_slow_run_by_less_than_the_step_cap_does() {
    // (0.088, 0.1115) from ii at N = 96: the droplet slows from v = 0.27 over hundreds of time
    // units, stepped at the cap; to t = 400 by the paper's test alone.
    let (p, ic) = (
        ModelParams::at(0.088, 0.1115),
        InitialCondition::parse("ii").unwrap(),
    );
    let run = |projective_steps: bool, dt_max: f64| {
        let s = SolverSettings {
            t_max: 400.0,
            dt_max,
            projective_steps,
            ..settings(96, 1e-4)
        };
        let out = simulate(&p, &ic, &s).unwrap();
        assert_eq!(out.status, RunStatus::TMax, "{out:?}");
        out
    };
    let (projected, plain, finer) = (run(true, 0.25), run(false, 0.25), run(false, 0.125));
    assert!(
        // More than half of the time projected, at 60 % of the steps at most.
        projected.t_projected > 200.0 && projected.steps * 5 < plain.steps * 3,
        "{} of 400 projected in {} steps, {} without",
        projected.t_projected,
        projected.steps,
        plain.steps
    );
    assert_eq!(plain.t_projected, 0.0);
    // What the projections change is less than what halving the cap changes.
    let apart = |a: &droplet_solver::contract::outcome::RunOutcome,
                 b: &droplet_solver::contract::outcome::RunOutcome| {
        (a.v - b.v).abs().max((a.s - b.s).abs())
    };
    assert!(
        apart(&projected, &plain) < apart(&plain, &finer),
        "{} vs {}",
        apart(&projected, &plain),
        apart(&plain, &finer)
    );
}
