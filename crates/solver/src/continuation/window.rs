//! The window of the paper's plane in which the phase boundaries are computed, for a model of
//! any number of shape modes.
use crate::model::params::ModelParams;

/// A window of the paper's plane `(eta_t, kappa2)`, the resolution of its boundaries
/// ([`crate::continuation::boundaries::boundaries`]) and the model's shape modes.
#[derive(Debug, Clone)]
pub struct Window {
    /// Model parameters (`eta_t` and `kappa2` are varied).
    pub base: ModelParams,
    pub n: usize,
    /// Shape modes `2..=modes` (2: the paper's model).
    pub modes: usize,
    pub eta_t: (f64, f64),
    pub kappa2: (f64, f64),
    /// Samples of the ID onset line in `kappa2`.
    pub id_samples: usize,
}
