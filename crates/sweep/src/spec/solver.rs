//! The `solver` section: the types are read here (a scheme name, an integer `n`, finite
//! numbers); every range and consistency check is `SolverSettings::validate` and
//! `droplet_solver::contract::limits::check_run`, the same checks `droplet simulate` makes, run
//! at the grid's points ([`super::grid::check_points`]) with the offending field mapped back to
//! its key.
use super::context::{show, Ctx};
use crate::error::SpecError;
use droplet_solver::{
    contract::settings::ModelKind, contract::settings::SolverSettings, stepping::SchemeKind,
};
use serde_yaml::Mapping;

/// The keys of the section.
const KEYS: [&str; 15] = [
    "scheme",
    "steady",
    "stop_beside_saddle",
    "leap_departures",
    "landing",
    "orientation_flow",
    "run_on",
    "n",
    "dt",
    "tol",
    "dt_max",
    "t_max",
    "steady_tol",
    "steady_window",
    "h0",
];

/// The on/off settings: each key, what `true` means, and its field.
type Flag = (
    &'static str,
    &'static str,
    fn(&mut SolverSettings) -> &mut bool,
);

const FLAGS: [Flag; 5] = [
    (
        "stop_beside_saddle",
        "stop a run beside a saddle it cannot leave before t_max",
        |s| &mut s.stop_beside_saddle,
    ),
    (
        "leap_departures",
        "leap along the linear stretch of a departure from a saddle",
        |s| &mut s.leap_departures,
    ),
    (
        "landing",
        "end a slow run where its one-dimensional quasi-steady flow lands; the default",
        |s| &mut s.landing,
    ),
    (
        "orientation_flow",
        "end a leaning run where the orientation's slow flow takes it (2-mode runs); the default",
        |s| &mut s.orientation_flow,
    ),
    (
        "run_on",
        "run a run not yet on a stable state on to 64 t_max (4 t_max with fixed steps); the default",
        |s| &mut s.run_on,
    ),
];

/// Reads the on/off settings of the `solver` section `m` into `solver`.
fn flags(ctx: &Ctx, m: &Mapping, solver: &mut SolverSettings) -> Result<(), SpecError> {
    for (key, meaning, field) in FLAGS {
        if let Some(x) = m.get(key) {
            *field(solver) = x.as_bool().ok_or_else(|| {
                ctx.err(
                    &["solver", key],
                    show(x),
                    format!("true ({meaning}) or false"),
                )
            })?;
        }
    }
    Ok(())
}

/// The `solver` section for `model` (its types; the ranges are checked at the grid's points).
pub(super) fn parse(
    ctx: &Ctx,
    top: &Mapping,
    model: ModelKind,
) -> Result<SolverSettings, SpecError> {
    let mut solver = match model {
        ModelKind::Pde => SolverSettings::default(),
        ModelKind::Ode => SolverSettings::ode(),
    };
    if let Some(v) = top.get("solver") {
        let m = ctx.mapping(v, &["solver"], &KEYS)?;
        if let Some(x) = m.get("scheme") {
            solver.scheme = x
                .as_str()
                .and_then(|s| s.parse::<SchemeKind>().ok())
                .ok_or_else(|| ctx.err(&["solver", "scheme"], show(x), "spectral or paper-fd"))?;
            if solver.scheme == SchemeKind::PaperFd {
                let fd = SolverSettings::paper_fd();
                (solver.n, solver.dt, solver.tol, solver.steady) = (fd.n, fd.dt, fd.tol, fd.steady);
            }
        }
        if let Some(x) = m.get("n") {
            solver.n = x
                .as_u64()
                .and_then(|n| usize::try_from(n).ok())
                .ok_or_else(|| ctx.err(&["solver", "n"], show(x), "an even integer"))?;
        }
        if let Some(x) = m.get("steady") {
            solver.steady = x.as_str().and_then(|s| s.parse().ok()).ok_or_else(|| {
                ctx.err(
                    &["solver", "steady"],
                    show(x),
                    "newton (default for the spectral scheme) or test (the paper's test alone)",
                )
            })?;
        }
        flags(ctx, m, &mut solver)?;
        ctx.numbers(m, "solver", &KEYS[7..], |key, val| match key {
            "dt" => solver.dt = val,
            "tol" => solver.tol = val,
            "dt_max" => solver.dt_max = val,
            "t_max" => solver.t_max = val,
            "steady_tol" => solver.steady_tol = val,
            "steady_window" => solver.steady_window = val,
            _ => solver.h0 = val,
        })?;
    }
    Ok(solver)
}
