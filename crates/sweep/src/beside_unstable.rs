//! The classification rule for runs that stopped at `t_max` beside an unstable steady state
//! (spec `classify:`; used by [`crate::phase`], carried by [`crate::plan::Plan`]).

/// How a point counts its runs that stopped at `t_max` beside an unstable steady state.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BesideUnstable {
    /// With the class of their final state, as every other unfinished run (the paper's rule).
    #[default]
    Count,
    /// Not at all: the point's class comes from its other runs.
    Exclude,
}
