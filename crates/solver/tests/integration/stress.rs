//! Stress test over random parameters in and beyond the paper's window: no panic, every run
//! ends with a status, outputs are finite unless the run diverged, and a diverged run stops
//! where it diverged. The seed is fixed so that the suite is deterministic.
use droplet_solver::{
    contract::outcome::RunOutcome, contract::outcome::RunStatus,
    contract::settings::SolverSettings, model::initial::InitialCondition,
    model::params::ModelParams, runs::driver::simulate,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config() -> Config {
    Config {
        cases: 40,
        rng_seed: RngSeed::Fixed(20261123),
        failure_persistence: None,
        ..Config::default()
    }
}

fn check(out: &RunOutcome, t_max: f64) {
    match out.status {
        RunStatus::Diverged => {
            assert!(out.class.is_none());
            assert!(
                !out.state.is_finite() || out.s >= 1.0,
                "diverged but fine: {out:?}"
            );
            assert!(out.t_end <= t_max + 1e-9);
        }
        RunStatus::Steady | RunStatus::TMax | RunStatus::Saddle => {
            assert!(
                out.state.is_finite() && out.v.is_finite() && out.s < 1.0,
                "{out:?}"
            );
            // Only a run that ended on a stable state has a class; the others say why not.
            let steady = out.status == RunStatus::Steady;
            assert_eq!(out.class.is_some(), steady, "{out:?}");
            assert_eq!(out.unsettled.is_none(), steady, "{out:?}");
        }
        // No random case in the paper's window should need 1e6 steps.
        RunStatus::StepLimit => panic!("a run stopped at the step cap: {out:?}"),
    }
    assert!(out.wall_s.is_finite());
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn any_parameters_end_with_a_status(
        eta_t in 0.01f64..0.3,
        kappa2 in 0.0f64..0.3,
        mass in prop_oneof![Just(0.0), 0.001f64..1.0],
        sigma in 0.025f64..0.12,
        // The droplet resolved: R >= 4 dx, sigma >= dx / 10 (droplet_solver::contract::limits).
        half_n in 16usize..32,
        dt in 0.001f64..0.4,
        ic in prop_oneof![Just("i"), Just("ii"), Just("iii"), Just("iv"), Just("i'"), Just("ii'")],
        fd in any::<bool>(),
        adaptive in any::<bool>(),
    ) {
        let p = ModelParams { eta_t, kappa2, mass, sigma, ..ModelParams::default() };
        let ic = InitialCondition::parse(ic).unwrap();
        let t_max = 8.0;
        let s = if fd {
            // The explicit scheme at a stable step for its grid (dt < dx^2 / 4).
            let n = 2 * half_n;
            let dx = p.box_len / n as f64;
            SolverSettings { n, dt: 0.2 * dx * dx, t_max: 1.0, ..SolverSettings::paper_fd() }
        } else if adaptive {
            // dt is the first step; the controller takes over.
            SolverSettings { n: 2 * half_n, dt: dt.min(0.1), t_max, ..SolverSettings::default() }
        } else {
            SolverSettings { n: 2 * half_n, dt, tol: 0.0, dt_max: dt.max(1.0), t_max, steady_window: dt.max(0.1), ..SolverSettings::default() }
        };
        // The overdamped model runs with the paper's test alone (the Newton finish's
        // stability check needs inertia, and refuses m = 0).
        let s = if mass == 0.0 {
            SolverSettings { steady: droplet_solver::contract::ending::SteadyMethod::Test, ..s }
        } else {
            s
        };
        let out = simulate(&p, &ic, &s).unwrap();
        check(&out, s.give_up_at());
        if s.adaptive() {
            // Every accepted step met the tolerance.
            prop_assert!(out.max_step_error.unwrap_or(0.0) <= s.tol, "{:?}", out);
        }
        if mass > 0.0 {
            let ode = SolverSettings { t_max, ..SolverSettings::ode() };
            check(&simulate(&p, &ic, &ode).unwrap(), t_max);
        }
    }
}

/// Small eta_t and kappa2 (the paper's warning): the deformation runs away and the run ends
/// `diverged` promptly, not at t_max.
#[test]
fn runaway_deformation_ends_as_diverged_promptly() {
    let p = ModelParams::at(0.03, 0.0);
    let s = SolverSettings {
        n: 48,
        t_max: 2000.0,
        ..SolverSettings::default()
    };
    let out = simulate(&p, &InitialCondition::parse("ii").unwrap(), &s).unwrap();
    assert_eq!(out.status, RunStatus::Diverged, "{out:?}");
    assert!(out.t_end < 200.0, "took until t = {}", out.t_end);
}
