//! The windows in which the phase boundaries are computed: the paper's plane for a model of
//! any number of shape modes, and the axes of a plane of any two model parameters.
use crate::model::param::ModelParam;
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
/// One axis of a window: the parameter and its range (`q = 0` and `1` at its ends).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneAxis {
    pub param: ModelParam,
    pub range: (f64, f64),
}

impl PlaneAxis {
    pub fn new(param: ModelParam, range: (f64, f64)) -> Self {
        Self { param, range }
    }

    /// The parameter's value at `q`.
    pub fn value(&self, q: f64) -> f64 {
        self.range.0 + q * (self.range.1 - self.range.0)
    }

    /// `q` of a value.
    pub fn q(&self, value: f64) -> f64 {
        (value - self.range.0) / (self.range.1 - self.range.0)
    }

    /// Whether the parameter moves steady states (all but the rate-only `eta2`, `mass`).
    pub(crate) fn moves_states(&self) -> bool {
        !matches!(self.param, ModelParam::Eta2 | ModelParam::Mass)
    }
}
