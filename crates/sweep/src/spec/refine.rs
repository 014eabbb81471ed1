//! The `refine` section: adaptive refinement of the grid ([`crate::map::refine`]).
//!
//! ```yaml
//! refine:
//!   levels: 4                               # levels beyond the grid (1..=MAX_LEVELS)
//!   min_step: {eta_t: 1.5e-4, kappa2: 3e-4}  # optional: no cell side below these
//!   split_bistable: false                   # optional: also fill bistable bands
//!   certify_midpoints: false                # optional: certify some points without runs (true, chained)
//! ```
//!
//! The grid's first two axes must be `{start, stop, step}` ranges: level 0 is that grid, and
//! each level halves the steps where the class changes. A third axis (any values) is refined
//! slice by slice, each slice's cells split by its own points. `min_step` is keyed by the axes' names.
use super::context::{show, Ctx};
use super::grid::{Grid, Swept};
use crate::error::SpecError;
use crate::spec::lattice::{Certify, Lattice, Refine, Steps};
use droplet_solver::contract::settings::{ModelKind, SolverSettings};
use droplet_solver::stepping::SchemeKind;
use serde_yaml::Mapping;

/// Most refinement levels (a finest cell 1/1024 of the grid's).
pub const MAX_LEVELS: u32 = 10;

/// A grid axis as the lattice's level-0 axis: a `{start, stop, step}` range of at least two
/// points (refinement halves its step).
fn lattice_axis(ctx: &Ctx, axis: Option<&Swept>) -> Result<Steps, SpecError> {
    let Some(axis) = axis else {
        return Err(ctx.err(
            &["refine"],
            "a grid of one axis",
            "a grid of two {start, stop, step} range axes (refinement splits cells of a plane)",
        ));
    };
    match axis.step {
        Some(step) if axis.values.len() >= 2 => Ok(Steps {
            start: axis.values[0],
            step,
            count: axis.values.len() as u64,
        }),
        _ => Err(ctx.err(
            &["grid", axis.param.name()],
            if axis.step.is_some() {
                "a single point".to_string()
            } else {
                "a list".to_string()
            },
            "a {start, stop, step} range of at least two points (refine: halves its step)",
        )),
    }
}

/// The `refine` section, if present, on the grid already parsed.
pub(super) fn parse(
    ctx: &Ctx,
    top: &Mapping,
    grid: &Grid,
    solver: &SolverSettings,
) -> Result<Option<Lattice>, SpecError> {
    let Some(v) = top.get("refine") else {
        return Ok(None);
    };
    let m = ctx.mapping(
        v,
        &["refine"],
        &["levels", "min_step", "split_bistable", "certify_midpoints"],
    )?;
    let levels = levels_of(ctx, m)?;
    let x = lattice_axis(ctx, Some(&grid.x))?;
    let y = lattice_axis(ctx, grid.y.as_ref())?;
    let names = grid
        .plane()
        .params()
        .iter()
        .map(|p| p.name())
        .collect::<Vec<_>>();
    let min_step = min_step_of(ctx, m, &names)?;
    let split_bistable = match m.get("split_bistable") {
        None => false,
        Some(b) => b
            .as_bool()
            .ok_or_else(|| ctx.err(&["refine", "split_bistable"], show(b), "true or false"))?,
    };
    let certify_midpoints = certify_of(ctx, m, solver)?;
    let lattice = Lattice {
        x,
        y,
        refine: Refine {
            levels,
            min_step,
            split_bistable,
            certify_midpoints,
        },
    };
    check_min_step(ctx, &lattice, &names)?;
    Ok(Some(lattice))
}

/// `refine.levels`: an integer `1..=MAX_LEVELS`.
fn levels_of(ctx: &Ctx, m: &Mapping) -> Result<u32, SpecError> {
    let allowed = format!("an integer 1..={MAX_LEVELS}");
    match m.get("levels") {
        None => Err(ctx.err(&["refine", "levels"], "missing", allowed)),
        Some(x) => Ok(x
            .as_u64()
            .filter(|l| (1..=MAX_LEVELS as u64).contains(l))
            .ok_or_else(|| ctx.err(&["refine", "levels"], show(x), allowed))?
            as u32),
    }
}

/// `refine.min_step` per axis of the plane (`names`), 0 where not given.
fn min_step_of(ctx: &Ctx, m: &Mapping, names: &[&str]) -> Result<(f64, f64), SpecError> {
    let mut min_step = (0.0, 0.0);
    if let Some(v) = m.get("min_step") {
        let ms = ctx.mapping(v, &["refine", "min_step"], names)?;
        for (key, slot) in [(names[0], &mut min_step.0), (names[1], &mut min_step.1)] {
            if let Some(w) = ms.get(key) {
                *slot = ctx.number(w, &["refine", "min_step", key], |s| s > 0.0, "a number > 0")?;
            }
        }
    }
    Ok(min_step)
}

/// `refine.certify_midpoints`: false, true or chained; refused where the runs end otherwise
/// than by the spectral PDE runs' Newton finish and eigenvalues, which the certificate is.
fn certify_of(ctx: &Ctx, m: &Mapping, solver: &SolverSettings) -> Result<Certify, SpecError> {
    let certify =
        match m.get("certify_midpoints") {
            None => Certify::Off,
            Some(b) => match (b.as_bool(), b.as_str()) {
                (Some(false), _) => Certify::Off,
                (Some(true), _) => Certify::Stepped,
                (_, Some("chained")) => Certify::Chained,
                _ => return Err(ctx.err(
                    &["refine", "certify_midpoints"],
                    show(b),
                    "false, true (from stepped neighbours) or chained (from certified ones too)",
                )),
            },
        };
    let unlike_runs = if solver.model == ModelKind::Ode {
        Some("model: ode")
    } else if solver.scheme != SchemeKind::Spectral {
        Some("solver.scheme: paper-fd")
    } else if solver.steady.is_test() {
        Some("solver.steady: test (the paper's protocol)")
    } else if solver.pinned {
        Some("pinned runs")
    } else {
        None
    };
    if let (true, Some(what)) = (certify.is_on(), unlike_runs) {
        return Err(ctx.err(
            &["refine", "certify_midpoints"],
            certify.as_str(),
            format!("false with {what}: the certificate is the spectral PDE runs' Newton finish and eigenvalues"),
        ));
    }
    Ok(certify)
}

/// Both sides of a cell are halved together: a `min_step` above half of either grid step
/// would forbid every split, turning refinement off without a word.
fn check_min_step(ctx: &Ctx, lattice: &Lattice, names: &[&str]) -> Result<(), SpecError> {
    let min_step = lattice.refine.min_step;
    for (key, grid_step, min) in [
        (names[0], lattice.x.step, min_step.0),
        (names[1], lattice.y.step, min_step.1),
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
    Ok(())
}
