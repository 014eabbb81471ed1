//! The benchmark's references, computed once per plan and stored beside the results
//! (`reference.json`): steady MD / ID states by Newton on the exact co-moving steady equations
//! at `n_newton`, seeded from a fine time integration that also gives the reference class; IC
//! states exactly `v = s = 0`; the transient by the spectral scheme at `n_ref` with a small
//! fixed step.
use crate::bench::plan::{BenchPlan, Case, Profile};
use crate::error::SweepError;
use droplet_solver::model::mirror::MirrorLine;
use droplet_solver::{
    contract::outcome::RunOutcome, contract::outcome::RunStatus,
    contract::settings::SolverSettings, model::classify::StateClass,
    model::initial::InitialCondition, model::params::ModelParams,
    roots::steady_solver::TwoModeSolver, runs::driver::simulate,
};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// The reference of one case.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Reference {
    pub case: String,
    pub class: String,
    pub v: f64,
    pub s: f64,
    /// Time the reference run met the steady test (steady cases).
    pub t_steady: Option<f64>,
    /// `(t, v, s)` every `plan.every` (transient case).
    pub series: Vec<[f64; 3]>,
    /// How the values were obtained.
    pub how: String,
}

/// The stored references of a plan.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct References {
    pub plan: BenchPlan,
    pub cases: Vec<Reference>,
    pub wall_s: f64,
}

fn params(c: &Case) -> ModelParams {
    ModelParams::at(c.eta_t, c.kappa2)
}

fn ic(c: &Case) -> Result<InitialCondition, SweepError> {
    Ok(InitialCondition::parse(&c.ic)?)
}

/// Runs `settings` on `c`, recording the series in a transient case.
pub(crate) fn run_case(
    c: &Case,
    settings: &SolverSettings,
    every: f64,
) -> Result<RunOutcome, SweepError> {
    let mut s = *settings;
    let p = params(c);
    let ic = ic(c)?;
    match c.window {
        Some(t) => {
            s.t_max = t;
            s.steady_tol = f64::MIN_POSITIVE; // never steady: the whole window
            Ok(droplet_solver::runs::driver::Run::new(&p, &ic, &s)?
                .record_every(Some(every))
                .execute())
        }
        None => Ok(simulate(&p, &ic, &s)?),
    }
}

pub(crate) fn series_of(out: &RunOutcome) -> Vec<[f64; 3]> {
    out.series.iter().map(|r| [r.t, r.v, r.s]).collect()
}

/// Computes the references of `plan` (minutes for the full profile), in parallel.
pub fn references(plan: &BenchPlan) -> Result<References, SweepError> {
    let started = Instant::now();
    let cases = plan
        .cases
        .par_iter()
        .map(|c| reference(plan, c))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(References {
        plan: plan.clone(),
        cases,
        wall_s: started.elapsed().as_secs_f64(),
    })
}

/// The box's mirror line nearest to a run's final orientation: its motion (MD) or its long
/// axis (ID). The periodic images make x and diagonal states differ.
fn nearest_mirror(
    st: &droplet_solver::model::state::DropletState,
    class: StateClass,
) -> MirrorLine {
    let diagonal = if class == StateClass::MD {
        let ang = st.vy.atan2(st.vx).rem_euclid(std::f64::consts::FRAC_PI_2);
        (ang - std::f64::consts::FRAC_PI_4).abs() < std::f64::consts::FRAC_PI_8
    } else {
        st.b2.abs() > st.a2.abs()
    };
    if diagonal {
        MirrorLine::Diagonal
    } else {
        MirrorLine::X
    }
}

/// The reference of case `c`: the transient by accurate fixed steps; a steady case classed by
/// a fine run, its `v` and `s` by Newton on the exact steady equations (0 for the disk).
fn reference(plan: &BenchPlan, c: &Case) -> Result<Reference, SweepError> {
    if c.window.is_some() {
        let s = plan.transient_reference;
        let out = run_case(c, &s, plan.every)?;
        return Ok(Reference {
            case: c.name.clone(),
            class: out.class.map_or("-", |k| k.as_str()).into(),
            v: out.v,
            s: out.s,
            t_steady: None,
            series: series_of(&out),
            how: format!("spectral N = {}, fixed dt = {}", s.n, s.dt),
        });
    }
    let out = run_case(c, &plan.reference_run, plan.every)?;
    if out.status == RunStatus::Diverged
        || (out.status != RunStatus::Steady && plan.profile == Profile::Full)
    {
        return Err(SweepError::Invalid(format!(
            "bench reference for {} did not reach the steady test ({})",
            c.name,
            out.status.as_str()
        )));
    }
    let class = out.class.expect("runs that did not diverge have a class");
    let run_how = format!(
        "class from spectral N = {}, dt = {} ({} at t = {:.1})",
        plan.reference_run.n,
        plan.reference_run.dt,
        out.status.as_str(),
        out.t_end
    );
    let (v, s, how) = match class {
        StateClass::IC => (
            0.0,
            0.0,
            format!("{run_how}; resting disk v = s = 0 exactly"),
        ),
        StateClass::MD | StateClass::ID => {
            let mut newton = TwoModeSolver::new(params(c), plan.n_newton)?;
            let st = &out.state;
            let axis = nearest_mirror(st, class);
            // Moving droplets are elongated across the motion (amplitude < 0 on the axis).
            let (v0, c0) = if class == StateClass::MD {
                (out.v, -out.s)
            } else {
                (0.0, out.s)
            };
            let sol = newton.newton_on(axis, v0, c0, 1e-12)?;
            (
                sol.v.abs(),
                sol.a2.abs(),
                format!(
                    "{run_how}; Newton on the exact steady equations on the {axis:?} mirror axis at N = {} (residual {:.1e})",
                    plan.n_newton, sol.residual
                ),
            )
        }
        StateClass::MC => (out.v, out.s, format!("{run_how}; its final state")),
    };
    Ok(Reference {
        case: c.name.clone(),
        class: class.as_str().into(),
        v,
        s,
        t_steady: out.t_steady,
        series: Vec::new(),
        how,
    })
}

/// Max over common sample times of `max(|v - v_ref|, |s - s_ref|)`.
pub(crate) fn series_error(series: &[[f64; 3]], reference: &[[f64; 3]], every: f64) -> f64 {
    let index = |t: f64| (t / every).round() as i64;
    let mut err: f64 = 0.0;
    let mut matched = 0;
    for r in series {
        if let Some(q) = reference.iter().find(|q| index(q[0]) == index(r[0])) {
            if (q[0] - r[0]).abs() < 1e-6 * every {
                err = err.max((r[1] - q[1]).abs()).max((r[2] - q[2]).abs());
                matched += 1;
            }
        }
    }
    if matched == 0 || matched < reference.len() {
        f64::NAN
    } else {
        err
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_error_compares_matching_sample_times() {
        let r = vec![[0.0, 1.0, 0.1], [0.1, 1.0, 0.2], [0.2, 1.0, 0.3]];
        let s = vec![[0.0, 1.0, 0.1], [0.1, 1.5, 0.2], [0.2, 1.0, 0.25]];
        assert!((series_error(&s, &r, 0.1) - 0.5).abs() < 1e-15);
        // Missing samples are an error, not a silent match on fewer points.
        assert!(series_error(&s[..1], &r, 0.1).is_nan());
    }
}
