//! The `refine` section: adaptive refinement of the grid ([`crate::map::refine`]).
//!
//! ```yaml
//! refine:
//!   levels: 4                               # levels beyond the grid (1..=MAX_LEVELS)
//!   min_step: {eta_t: 1.5e-4, kappa2: 3e-4}  # optional: no cell side below these
//!   split_bistable: false                   # optional: also fill bistable bands
//! ```
//!
//! Both grid axes must be `{start, stop, step}` ranges: level 0 is that grid, and each level
//! halves the step where the class changes.
use super::context::{show, Ctx};
use crate::error::SpecError;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::spec::lattice::{Axis, Lattice, Refine};
use serde_yaml::Mapping;

/// Most refinement levels (a finest cell 1/1024 of the grid's).
pub const MAX_LEVELS: u32 = 10;

/// The grid axis `key` with `values` as the lattice's level-0 axis: a `{start, stop, step}`
/// range of at least two points (refinement halves its step).
fn grid_axis(
    ctx: &Ctx,
    top: &Mapping,
    key: &'static str,
    values: &[f64],
) -> Result<Axis, SpecError> {
    let grid = top.get("grid").and_then(|g| g.as_mapping());
    let step = grid
        .and_then(|g| g.get(key))
        .and_then(|a| a.as_mapping())
        .and_then(|a| a.get("step"))
        .and_then(|s| s.as_f64());
    match step {
        Some(step) if values.len() >= 2 => Ok(Axis {
            start: values[0],
            step,
            count: values.len() as u64,
        }),
        _ => Err(ctx.err(
            &["grid", key],
            if step.is_some() {
                "a single point".to_string()
            } else {
                "a list".to_string()
            },
            "a {start, stop, step} range of at least two points (refine: halves its step)",
        )),
    }
}

/// The `refine` section, if present, on the grid `(eta_t, kappa2)` already parsed.
pub(super) fn parse(
    ctx: &Ctx,
    top: &Mapping,
    eta_t: &[f64],
    kappa2: &[f64],
) -> Result<Option<Lattice>, SpecError> {
    let Some(v) = top.get("refine") else {
        return Ok(None);
    };
    let m = ctx.mapping(v, &["refine"], &["levels", "min_step", "split_bistable"])?;
    let levels = match m.get("levels") {
        None => return Err(ctx.err(&["refine", "levels"], "missing", "an integer 1..=10")),
        Some(x) => x
            .as_u64()
            .filter(|l| (1..=MAX_LEVELS as u64).contains(l))
            .ok_or_else(|| {
                ctx.err(
                    &["refine", "levels"],
                    show(x),
                    format!("an integer 1..={MAX_LEVELS}"),
                )
            })? as u32,
    };
    let mut min_step = (0.0, 0.0);
    if let Some(x) = m.get("min_step") {
        let ms = ctx.mapping(x, &["refine", "min_step"], &[ETA_T, KAPPA2])?;
        for (key, slot) in [(ETA_T, &mut min_step.0), (KAPPA2, &mut min_step.1)] {
            if let Some(y) = ms.get(key) {
                *slot = ctx.number(y, &["refine", "min_step", key], |s| s > 0.0, "a number > 0")?;
            }
        }
    }
    let split_bistable = match m.get("split_bistable") {
        None => false,
        Some(x) => x
            .as_bool()
            .ok_or_else(|| ctx.err(&["refine", "split_bistable"], show(x), "true or false"))?,
    };
    let lattice = Lattice {
        eta_t: grid_axis(ctx, top, ETA_T, eta_t)?,
        kappa2: grid_axis(ctx, top, KAPPA2, kappa2)?,
        refine: Refine {
            levels,
            min_step,
            split_bistable,
        },
    };
    // Both sides of a cell are halved together: a min_step above half of either grid step
    // would forbid every split, turning refinement off without a word.
    for (key, grid_step, min) in [
        (ETA_T, lattice.eta_t.step, min_step.0),
        (KAPPA2, lattice.kappa2.step, min_step.1),
    ] {
        if min > 0.5 * grid_step * (1.0 + 1e-9) {
            return Err(ctx.err(
                &["refine", "min_step", key],
                min,
                format!(
                    "at most half the grid's {key} step ({}), so that cells can be split at \
                     all (a larger min_step would turn refinement off)",
                    0.5 * grid_step
                ),
            ));
        }
    }
    Ok(Some(lattice))
}
