//! The `grid` section: the two swept axes ([`crate::spec::axes`]), each an inclusive
//! `{start, stop, step}` range or an explicit list.
use super::context::{show, Ctx};
use crate::error::SpecError;
use crate::spec::axes::{round12, ETA_T, KAPPA2};
use serde_yaml::{Mapping, Value};

/// Most points one axis may have.
pub const MAX_AXIS_POINTS: usize = 100_000;

/// The `grid` section: `(eta_t, kappa2)` values.
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<(Vec<f64>, Vec<f64>), SpecError> {
    let grid_v = top.get("grid").ok_or_else(|| {
        ctx.err(
            &["grid"],
            "missing",
            format!("a mapping with {ETA_T} and {KAPPA2} axes"),
        )
    })?;
    let grid = ctx.mapping(grid_v, &["grid"], &[ETA_T, KAPPA2])?;
    let axis = |key: &'static str,
                lower_ok: fn(f64) -> bool,
                lower: &str|
     -> Result<Vec<f64>, SpecError> {
        let v = grid.get(key).ok_or_else(|| {
            ctx.err(
                &["grid", key],
                "missing",
                "{start, stop, step} or a list of numbers",
            )
        })?;
        parse_axis(ctx, v, key, lower_ok, lower)
    };
    Ok((
        axis(ETA_T, |x| x > 0.0, "> 0")?,
        axis(KAPPA2, |x| x >= 0.0, ">= 0")?,
    ))
}

pub(super) fn parse_axis(
    ctx: &Ctx,
    v: &Value,
    key: &'static str,
    lower_ok: fn(f64) -> bool,
    lower: &str,
) -> Result<Vec<f64>, SpecError> {
    let path = ["grid", key];
    if let Some(seq) = v.as_sequence() {
        if seq.is_empty() {
            return Err(ctx.err(&path, "[]", "a non-empty list"));
        }
        if seq.len() > MAX_AXIS_POINTS {
            return Err(ctx.err(&path, show(v), format!("at most {MAX_AXIS_POINTS} values")));
        }
        let mut out = Vec::with_capacity(seq.len());
        // Seen values by their bits (every value is finite, and -0.0 is read as 0.0): one
        // look-up per value, so a long list is checked in linear time.
        let mut seen = std::collections::HashSet::with_capacity(seq.len());
        for item in seq {
            let x = ctx.number(item, &path, lower_ok, &format!("finite numbers {lower}"))? + 0.0;
            if !seen.insert(x.to_bits()) {
                return Err(ctx.err(&path, x, "distinct values"));
            }
            out.push(x);
        }
        return Ok(out);
    }
    let m = ctx.mapping(v, &path, &["start", "stop", "step"])?;
    let get =
        |k: &'static str, ok: &dyn Fn(f64) -> bool, allowed: &str| -> Result<f64, SpecError> {
            let x = m.get(k).ok_or_else(|| {
                ctx.err(
                    &["grid", key, k],
                    "missing",
                    "start, stop and step are all required",
                )
            })?;
            ctx.number(x, &["grid", key, k], ok, allowed)
        };
    let start = get(
        "start",
        &|x| lower_ok(x),
        &format!("a finite number {lower}"),
    )?;
    let stop = get(
        "stop",
        &|x| x >= start,
        &format!("a finite number >= start ({start})"),
    )?;
    let step = get("step", &|x| x > 0.0, "a finite number > 0")?;
    let count = ((stop - start) / step + 1e-9).floor() + 1.0;
    if count > MAX_AXIS_POINTS as f64 {
        return Err(ctx.err(
            &["grid", key, "step"],
            step,
            format!("a step giving at most {MAX_AXIS_POINTS} points (this gives {count})"),
        ));
    }
    // Values on a decimal grid: start + i step, rounded to 12 digits so that 0.07 + 3 * 0.01
    // is 0.1 and equal points in two specs get equal run keys.
    Ok((0..count as usize)
        .map(|i| round12(start + i as f64 * step))
        .collect())
}
