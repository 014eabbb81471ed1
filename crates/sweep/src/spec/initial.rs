//! The `initial_conditions` section: names of the paper's conditions or custom ones, each once
//! (default: the paper's four, i-iv).
use super::context::{show, Ctx};
use crate::error::SpecError;
use droplet_solver::{error::SolverError, model::initial::InitialCondition};
use serde_yaml::Mapping;

/// The `initial_conditions` section.
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<Vec<InitialCondition>, SpecError> {
    let path = ["initial_conditions"];
    let Some(v) = top.get("initial_conditions") else {
        return Ok(droplet_solver::model::initial::PAPER_FOUR
            .iter()
            .map(|n| InitialCondition::parse(n).expect("named"))
            .collect());
    };
    let seq = v.as_sequence().filter(|s| !s.is_empty()).ok_or_else(|| {
        ctx.err(
            &path,
            show(v),
            "a non-empty list of i, ii, iii, iv, i', ii', custom:vx,vy,a2,b2 (K-mode runs: \
             then a3,b3,a4,b4,...)",
        )
    })?;
    let mut out: Vec<InitialCondition> = Vec::new();
    for item in seq {
        let s = item.as_str().ok_or_else(|| {
            ctx.err(
                &path,
                show(item),
                "a name such as i or ii' (quote names with ')",
            )
        })?;
        let ic = InitialCondition::parse(s).map_err(|e| {
            ctx.err(
                &path,
                show(item),
                match e {
                    SolverError::InvalidInitialCondition { reason, .. } => reason,
                    _ => "i, ii, iii, iv, i', ii' or custom:vx,vy,a2,b2[,a3,b3,...] with s < 1"
                        .into(),
                },
            )
        })?;
        if out.iter().any(|o| o.name == ic.name) {
            return Err(ctx.err(&path, show(item), "each initial condition once"));
        }
        out.push(ic);
    }
    Ok(out)
}

/// Refuses initial conditions with amplitudes for shape modes beyond the spec's `params.modes`
/// (named under `initial_conditions`).
pub(super) fn check_modes(
    ctx: &Ctx,
    initial_conditions: &[InitialCondition],
    modes: usize,
) -> Result<(), SpecError> {
    for ic in initial_conditions {
        if let Err(SolverError::InvalidInitialCondition { reason, .. }) = ic.check_modes(modes) {
            return Err(ctx.err(&["initial_conditions"], format!("{:?}", ic.name), reason));
        }
    }
    Ok(())
}
