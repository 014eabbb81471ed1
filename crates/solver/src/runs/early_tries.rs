//! The record of a run's early tries (`early_try`): when the next may be made, the root with
//! an orientation the last one found, and how far below its trigger the run's rates must be.

/// A run with more than two shape modes is tried early once its rates are below this many
/// times its trigger: three times the 2-mode runs' rate (numerics `modes-15`; `modes-14`
/// tried from the 2-mode runs' rate on, and the Fig. 1c run from ii, modes 2..4, N = 192,
/// ended at t = 41.9 instead of 27.4).
pub const EARLY_FACTOR: f64 = 30.0;

/// A run whose landing at an early try found the slow flow going elsewhere than the disk is
/// tried early once more when its rates are below this many times its trigger (the 2-mode
/// runs' rate), nearer the disk; then no more: a landing costs tens of Newton solves. At
/// (0.08075, 0.11975), modes 2..4, from i, the landing at [`EARLY_FACTOR`] finds no way to the
/// disk and the one below this lands there at t = 23, where the run's own trigger would
/// have ended it at t = 1157.
pub const LATE_EARLY_FACTOR: f64 = 10.0;

/// What a run's early tries have learnt.
#[derive(Debug, Clone)]
pub struct EarlyTries {
    /// When the run may next be tried early.
    pub(super) next: f64,
    /// The root with an orientation of the last early try and the run's angle to it then.
    pub(super) last: Option<(Vec<f64>, f64)>,
    /// The number of triggers the run's rates must be below: [`EARLY_FACTOR`], then
    /// [`LATE_EARLY_FACTOR`] once a landing has found the slow flow going elsewhere.
    pub(super) factor: f64,
}

impl Default for EarlyTries {
    fn default() -> Self {
        Self {
            next: 0.0,
            last: None,
            factor: EARLY_FACTOR,
        }
    }
}
