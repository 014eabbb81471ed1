//! The `classify` section, removed in numerics 4: it chose whether runs that stopped beside an
//! unstable steady state counted with the class of where they stopped. Since then no run
//! that did not end on a stable steady state counts with a class ([`crate::map::point_class`]), so
//! there is no rule left to choose, and a spec that still has the section is refused with
//! that reason rather than silently read.
use super::context::{show, Ctx};
use crate::error::SpecError;
use serde_yaml::Mapping;

/// Refuses a `classify` section.
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<(), SpecError> {
    match top.get("classify") {
        None => Ok(()),
        Some(v) => Err(ctx.err(
            &["classify"],
            show(v),
            "no classify section: it was removed (numerics 4), since a run that did not end on a stable steady state never counts with a class; delete it",
        )),
    }
}
