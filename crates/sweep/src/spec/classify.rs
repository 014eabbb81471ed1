//! The `classify` section: how point classes count unfinished runs ([`crate::phase`]).
//!
//! ```yaml
//! classify:
//!   beside_unstable: count    # count (default, the paper's rule) or exclude
//! ```
//!
//! `exclude` leaves out of a point's class the runs that stopped at `t_max` beside an unstable
//! steady state (their Newton diagnosis): the point is classified from its other runs.
use super::context::{show, Ctx};
use crate::beside_unstable::BesideUnstable;
use crate::error::SpecError;
use serde_yaml::Mapping;

/// The `classify` section's rule (the default when the section is absent).
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<BesideUnstable, SpecError> {
    let Some(v) = top.get("classify") else {
        return Ok(BesideUnstable::default());
    };
    let m = ctx.mapping(v, &["classify"], &["beside_unstable"])?;
    match m.get("beside_unstable") {
        None => Ok(BesideUnstable::default()),
        Some(x) => match x.as_str() {
            Some("count") => Ok(BesideUnstable::Count),
            Some("exclude") => Ok(BesideUnstable::Exclude),
            _ => Err(ctx.err(
                &["classify", "beside_unstable"],
                show(x),
                "count or exclude",
            )),
        },
    }
}
