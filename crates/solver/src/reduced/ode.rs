//! The reduced ODE (paper eqs. 58-59) for `v = (vx, vy)` and `S = [[a2, b2], [b2, -a2]]`:
//!
//! `m dv/dt = (-eta_t + f1) v - f1~ S v - f3 |v|^2 v`,
//! `eta2 dS/dt = (-kappa2 + g0~) S - g2 (2 v v^T - |v|^2 I) - g2~ |v|^2 S - h0 S^3`, `S^3 = s^2 S`.
//!
//! Integrated with classical RK4 at a fixed step, with the same stop rules and classification
//! as the PDE runs, and the PDE runs' guard against false steady states: a state the paper's
//! test accepts ends the run only if it is linearly stable (the Jacobian of eqs. 58-59 has no
//! eigenvalue above [`UNSTABLE`]). Without it, a run creeping away from an unstable resting
//! state (e.g. the deformed disk past its onset of motion, eq. idmd) stopped there as `ID`.
use crate::contract::outcome::{RunOutcome, RunStatus};
use crate::contract::settings::SolverSettings;
use crate::contract::stop_rule::{diverged, SteadyTest};
use crate::error::{require, SolverError};
use crate::model::classify::StateClass;
use crate::model::initial::InitialCondition;
use crate::model::params::ModelParams;
use crate::model::state::DropletState;
use crate::reduced::coefficients::Coefficients;
use std::time::Instant;

/// Right-hand side `d(vx, vy, a2, b2)/dt` of eqs. (58)-(59).
pub fn rhs(c: &Coefficients, p: &ModelParams, y: [f64; 4]) -> [f64; 4] {
    let [vx, vy, a2, b2] = y;
    let v2 = vx * vx + vy * vy;
    let s2 = a2 * a2 + b2 * b2;
    let (svx, svy) = (a2 * vx + b2 * vy, b2 * vx - a2 * vy);
    let lin_v = -p.eta_t + c.f1 - c.f3 * v2;
    let lin_s = -p.kappa2 + c.g0t - c.g2t * v2 - c.h0 * s2;
    [
        (lin_v * vx - c.f1t * svx) / p.mass,
        (lin_v * vy - c.f1t * svy) / p.mass,
        (lin_s * a2 - c.g2 * (vx * vx - vy * vy)) / p.eta2,
        (lin_s * b2 - c.g2 * 2.0 * vx * vy) / p.eta2,
    ]
}

/// Growth rates above this make a state the steady test accepts unstable: the run goes on.
/// (The rotation mode's eigenvalue is 0 up to the difference quotient's error, ~1e-9; a mode
/// growing more slowly than 1e-6 changes a state by under 0.3 % over t = 3000.)
pub const UNSTABLE: f64 = 1e-6;

/// Largest real part of the eigenvalues of the Jacobian of [`rhs`] at `y` (central
/// differences); `NaN` where the Jacobian is not finite.
pub fn max_growth(c: &Coefficients, p: &ModelParams, y: [f64; 4]) -> f64 {
    let mut j = nalgebra::DMatrix::<f64>::zeros(4, 4);
    for col in 0..4 {
        let h = 1e-6 * y[col].abs().max(1e-3);
        let (mut a, mut b) = (y, y);
        a[col] += h;
        b[col] -= h;
        let (fa, fb) = (rhs(c, p, a), rhs(c, p, b));
        for row in 0..4 {
            j[(row, col)] = (fa[row] - fb[row]) / (2.0 * h);
        }
    }
    crate::numerics::eigen::complex_eigenvalues(&j).map_or(f64::NAN, |e| {
        e.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max)
    })
}

/// One RK4 step.
pub fn rk4(c: &Coefficients, p: &ModelParams, y: [f64; 4], h: f64) -> [f64; 4] {
    let add = |a: [f64; 4], b: [f64; 4], s: f64| {
        [
            a[0] + s * b[0],
            a[1] + s * b[1],
            a[2] + s * b[2],
            a[3] + s * b[3],
        ]
    };
    let k1 = rhs(c, p, y);
    let k2 = rhs(c, p, add(y, k1, h / 2.0));
    let k3 = rhs(c, p, add(y, k2, h / 2.0));
    let k4 = rhs(c, p, add(y, k3, h));
    let mut out = y;
    for i in 0..4 {
        out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    out
}

/// Runs the ODE from `ic` with the stop rules of `settings` (its `n` and `scheme` are unused).
pub fn simulate(
    p: &ModelParams,
    ic: &InitialCondition,
    settings: &SolverSettings,
) -> Result<RunOutcome, SolverError> {
    p.validate()?;
    settings.validate()?;
    require(
        p.mass > 0.0,
        "mass",
        p.mass,
        "a finite number > 0 for the ODE model (eq. 58 has inertia)",
    )?;
    require(settings.h0 > 0.0, "h0", settings.h0, "a finite number > 0")?;
    let started = Instant::now();
    let c = Coefficients::new(p.radius, settings.h0);
    let dt = settings.dt;
    let max_steps = (settings.t_max / dt).round() as u64;
    let mut y = [ic.vx, ic.vy, ic.a2, ic.b2];
    let mut steady_test = SteadyTest::new(settings, 0.0, y);
    let (mut x, mut yy) = (0.0, 0.0);
    let mut steps = 0;
    let mut status = RunStatus::TMax;
    let mut t_steady = None;
    while steps < max_steps {
        let next = rk4(&c, p, y, dt);
        x += dt * 0.5 * (y[0] + next[0]);
        yy += dt * 0.5 * (y[1] + next[1]);
        y = next;
        steps += 1;
        if diverged(y, &[]) {
            status = RunStatus::Diverged;
            break;
        }
        let t = steps as f64 * dt;
        if steady_test.is_steady(t, y) && max_growth(&c, p, y) <= UNSTABLE {
            status = RunStatus::Steady;
            t_steady = Some(t);
            break;
        }
    }
    let state = DropletState {
        x,
        y: yy,
        vx: y[0],
        vy: y[1],
        a2: y[2],
        b2: y[3],
    };
    Ok(outcome(
        status,
        state,
        (steps, dt),
        t_steady,
        started.elapsed().as_secs_f64(),
    ))
}

/// The outcome of a reduced-model run that ended with `status` at `state` after `steps` steps
/// of `dt`, its wall time `wall_s` (all of it stepping).
fn outcome(
    status: RunStatus,
    state: DropletState,
    (steps, dt): (u64, f64),
    t_steady: Option<f64>,
    wall_s: f64,
) -> RunOutcome {
    let (v, s) = (state.speed(), state.deformation());
    RunOutcome {
        status,
        class: (status == RunStatus::Steady).then(|| StateClass::of(v, s)),
        state,
        v,
        s,
        t_end: steps as f64 * dt,
        t_steady,
        steps,
        rejected: 0,
        max_step_error: None,
        wall_s,
        ended_by: (status == RunStatus::Steady).then_some(crate::contract::ending::Ending::Test),
        diagnosis: None,
        t_leapt: 0.0,
        t_projected: 0.0,
        unsettled: match status {
            RunStatus::Steady => None,
            RunStatus::Diverged => Some(crate::contract::outcome::Unsettled::Diverged),
            _ => Some(crate::contract::outcome::Unsettled::NotDiagnosed),
        },
        heading: None,
        higher_modes: Vec::new(),
        series: Vec::new(),
        higher_series: Vec::new(),
        // The reduced model's run is its time stepping.
        profile: crate::contract::profile::RunProfile {
            stepping_s: wall_s,
            ..Default::default()
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simulate_dispatches_to_the_ode_model() {
        // Through the public entry point: an ODE run takes microseconds per step, and its
        // class at a deep MD point is MD.
        let p = ModelParams::at(0.07, 0.1);
        let out = crate::runs::driver::simulate(
            &p,
            &InitialCondition::parse("i").unwrap(),
            &SolverSettings::ode(),
        )
        .unwrap();
        assert_eq!(out.class, Some(StateClass::MD));
        assert!(
            out.wall_s < 0.5,
            "ODE run took {} s: not the ODE model?",
            out.wall_s
        );
        assert!(crate::runs::driver::Run::new(
            &p,
            &InitialCondition::parse("i").unwrap(),
            &SolverSettings::ode()
        )
        .is_err());
    }

    #[test]
    fn an_unstable_resting_state_does_not_end_a_run() {
        // Just past ID's onset of motion (eq. idmd): the analytic ID state grows, the stable
        // one is stable, and the run from iv, which creeps near the ID state slowly enough for
        // the steady test (it stopped there as ID, v ~ 1e-4, before the guard), ends MD.
        let c = Coefficients::paper();
        let id = |p: &ModelParams| [0.0, 0.0, ((c.g0t - p.kappa2) / c.h0).sqrt(), 0.0];
        let past = ModelParams::at(0.086563, 0.114375);
        assert!(max_growth(&c, &past, id(&past)) > 10.0 * UNSTABLE);
        let before = ModelParams::at(0.1, 0.11);
        assert!(max_growth(&c, &before, id(&before)) < 0.0);
        let out = simulate(
            &past,
            &InitialCondition::parse("iv").unwrap(),
            &SolverSettings::ode(),
        )
        .unwrap();
        assert_eq!(
            (out.status, out.class),
            (RunStatus::Steady, Some(StateClass::MD)),
            "v {} s {} t {}",
            out.v,
            out.s,
            out.t_end
        );
    }

    #[test]
    fn id_state_is_the_analytic_one() {
        // kappa2 < g0~, eta_t > the ID stability line: ID with s = sqrt((g0~ - kappa2) / h0).
        let c = Coefficients::paper();
        let p = ModelParams::at(0.1, 0.11);
        let s = SolverSettings {
            dt: 0.05,
            t_max: 5000.0,
            steady_tol: 1e-12,
            ..SolverSettings::ode()
        };
        let out = simulate(&p, &InitialCondition::parse("iv").unwrap(), &s).unwrap();
        assert_eq!(out.class, Some(StateClass::ID));
        assert!(
            (out.s - ((c.g0t - 0.11) / c.h0).sqrt()).abs() < 1e-8,
            "{}",
            out.s
        );
    }

    #[test]
    fn md_state_solves_the_reduced_balance() {
        // Minor-axis MD: (-eta_t + f1) + f1~ s - f3 v^2 = 0 and
        // (g0~ - kappa2) s + g2 v^2 - g2~ s v^2 - h0 s^3 = 0.
        let c = Coefficients::paper();
        let p = ModelParams::at(0.075, 0.13);
        let s = SolverSettings {
            dt: 0.05,
            t_max: 5000.0,
            steady_tol: 1e-12,
            ..SolverSettings::ode()
        };
        let out = simulate(&p, &InitialCondition::parse("i").unwrap(), &s).unwrap();
        assert_eq!(out.class, Some(StateClass::MD));
        let (v2, sd) = (out.v * out.v, out.s);
        assert!(((-p.eta_t + c.f1) + c.f1t * sd - c.f3 * v2).abs() < 1e-8);
        assert!(
            ((c.g0t - p.kappa2) * sd + c.g2 * v2 - c.g2t * sd * v2 - c.h0 * sd.powi(3)).abs()
                < 1e-8
        );
        // Moving along the minor axis: S v is antiparallel to v (v . S v = -s v^2).
        let st = out.state;
        let vsv = st.vx * (st.a2 * st.vx + st.b2 * st.vy) + st.vy * (st.b2 * st.vx - st.a2 * st.vy);
        assert!((vsv + sd * v2).abs() < 1e-8);
    }
}
