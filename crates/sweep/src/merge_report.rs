//! What [`crate::execution::merge::merge`] found: the runs of a sweep, those missing or unreadable, and
//! the tables written. Plain data, so that errors can carry it.
use serde::Serialize;
use std::path::PathBuf;

/// Result of [`crate::execution::merge::merge`].
#[derive(Debug, Clone, Serialize)]
pub struct MergeReport {
    pub output: PathBuf,
    pub runs_total: usize,
    /// Runs with no valid record: absent, or unreadable (see `runs_unreadable`).
    pub runs_missing: usize,
    /// Of those, runs whose file exists but cannot be used (left in place; the next sweep or
    /// shard on the directory moves it to `corrupt/` and recomputes the run).
    pub runs_unreadable: usize,
    /// Up to 20 missing runs as `eta_t, kappa2, ic` (and why, when unreadable).
    pub missing_examples: Vec<String>,
    pub tables: Vec<PathBuf>,
}
