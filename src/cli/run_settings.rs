//! The model parameters and solver settings `droplet simulate`'s arguments ask for, and the
//! arguments' checks that need them: an option the run would not read is refused
//! (`SolverSettings::first_unread`, the check a spec makes too), and so are shape modes
//! outside 2..16.
use super::simulate::Args;
use super::CliError;
use droplet_solver::{
    contract::settings::SolverSettings, model::params::ModelParams, stepping::SchemeKind,
};

/// The model parameters and solver settings the arguments ask for.
pub(super) fn model_of(a: &Args) -> Result<(ModelParams, SolverSettings), CliError> {
    let scheme: SchemeKind = a.scheme.parse()?;
    let base = match scheme {
        SchemeKind::Spectral => SolverSettings::default(),
        SchemeKind::PaperFd => SolverSettings::paper_fd(),
    };
    let settings = SolverSettings {
        scheme,
        n: a.n.unwrap_or(base.n),
        dt: a.dt.unwrap_or(base.dt),
        tol: a.tol.unwrap_or(base.tol),
        dt_max: a.dt_max.unwrap_or(base.dt_max.max(a.dt.unwrap_or(base.dt))),
        t_max: a.t_max,
        steady_tol: a.steady_tol,
        steady_window: a.steady_window.unwrap_or(base.steady_window),
        pinned: a.pinned,
        steady: match (a.steady, a.pinned) {
            (Some(m), _) => m,
            (None, true) => droplet_solver::contract::ending::SteadyMethod::Test,
            (None, false) => base.steady,
        },
        stop_beside_saddle: a.stop_beside_saddle,
        leap_departures: a.leap_departures,
        landing: !a.no_landing,
        orientation_flow: !a.no_orientation_flow,
        run_on: !a.no_run_on,
        modes: a.modes,
        eta_k_exponent: a.eta_k_exponent,
        ..base
    };
    check_read(a, &settings)?;
    let most = droplet_solver::contract::limits::MAX_MODES;
    if !(2..=most).contains(&a.modes) {
        return Err(CliError::usage(format!(
            "invalid --modes {}: an integer from 2 (the paper's a2, b2) to {most}",
            a.modes
        )));
    }
    let params = ModelParams {
        eta_t: a.eta_t,
        kappa2: a.kappa2,
        eta2: a.eta2,
        radius: a.radius,
        sigma: a.sigma,
        box_len: a.box_len,
        mass: a.mass,
    };
    Ok((params, settings))
}

/// Refuses an option this run would not read (`SolverSettings::first_unread`, the check a
/// spec makes too), naming the option.
fn check_read(a: &Args, settings: &SolverSettings) -> Result<(), CliError> {
    let given = [
        (a.tol.is_some(), "tol", "--tol"),
        (a.dt_max.is_some(), "dt_max", "--dt-max"),
        (
            a.steady_window.is_some(),
            "steady_window",
            "--steady-window",
        ),
        (a.no_landing, "landing", "--no-landing"),
        (
            a.no_orientation_flow,
            "orientation_flow",
            "--no-orientation-flow",
        ),
        (a.no_run_on, "run_on", "--no-run-on"),
        (
            a.stop_beside_saddle,
            "stop_beside_saddle",
            "--stop-beside-saddle",
        ),
        (a.leap_departures, "leap_departures", "--leap-departures"),
        (a.pinned, "pinned", "--pinned"),
    ];
    let fields: Vec<&str> = given.iter().filter(|g| g.0).map(|g| g.1).collect();
    match settings.first_unread(&fields) {
        None => Ok(()),
        Some((field, why)) => {
            let flag = given.iter().find(|g| g.1 == field).map_or(field, |g| g.2);
            Err(CliError::usage(format!(
                "invalid {flag}: this run does not read it ({why})"
            )))
        }
    }
}
