//! The Newton finish against time stepping alone: the same steady states, reached in far
//! fewer time units.
use droplet_solver::newton_finish::SteadyMethod;
use droplet_solver::steady_method::Ending;
use droplet_solver::*;

#[test]
fn newton_finish_ends_at_the_time_steppers_steady_state() {
    let n = 96;
    // (eta_t, kappa2, IC): MD from a generic IC, ID, IC.
    let cases = [(0.085, 0.112, "ii"), (0.1, 0.105, "iii"), (0.09, 0.14, "i")];
    for (eta_t, kappa2, ic) in cases {
        let p = ModelParams::at(eta_t, kappa2);
        let ic = InitialCondition::parse(ic).unwrap();
        let base = SolverSettings {
            n,
            t_max: 6000.0,
            ..SolverSettings::default()
        };
        let newton = simulate(&p, &ic, &base).unwrap();
        // Time stepping alone, to a change below 1e-10 per 0.1 (the paper's 1e-6 stops a few
        // 1e-5 short of the fixed point).
        let stepped = simulate(
            &p,
            &ic,
            &SolverSettings {
                steady: SteadyMethod::Test,
                steady_tol: 1e-10,
                ..base
            },
        )
        .unwrap();
        let what = format!("({eta_t}, {kappa2}): newton {newton:?}\nstepped {stepped:?}");
        assert_eq!(newton.status, RunStatus::Steady, "{what}");
        assert_eq!(stepped.status, RunStatus::Steady, "{what}");
        assert!(newton.ended_by.is_some(), "{what}");
        assert!(
            (newton.v - stepped.v).abs() <= 1e-6 && (newton.s - stepped.s).abs() <= 1e-6,
            "{what}"
        );
        assert!(newton.t_end < 0.75 * stepped.t_end, "{what}");
    }
}

#[test]
fn the_paper_test_alone_is_kept_and_overdamped_runs_use_it() {
    let p = ModelParams::at(0.085, 0.112);
    let ic = InitialCondition::parse("i").unwrap();
    let test = SolverSettings {
        n: 64,
        steady: SteadyMethod::Test,
        ..SolverSettings::default()
    };
    let out = simulate(&p, &ic, &test).unwrap();
    assert_eq!(out.ended_by, Some(Ending::Test));
    // No inertia, no linearisation: the Newton finish falls back on the paper's test.
    let overdamped = ModelParams { mass: 0.0, ..p };
    let out = simulate(
        &overdamped,
        &ic,
        &SolverSettings {
            n: 64,
            ..SolverSettings::default()
        },
    )
    .unwrap();
    assert_eq!(out.status, RunStatus::Steady, "{out:?}");
    assert_eq!(out.ended_by, Some(Ending::Test), "{out:?}");
    // The Newton finish needs the spectral scheme.
    let bad = SolverSettings {
        steady: SteadyMethod::Newton,
        ..SolverSettings::paper_fd()
    };
    assert!(bad.validate().is_err());
}
