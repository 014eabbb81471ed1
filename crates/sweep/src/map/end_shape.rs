//! The shape a run ended with, as the K-mode columns of the runs and points tables show it
//! (`crate::tables::shape_columns`): its `K`, the mode-2 deformation `s` and the amplitudes of
//! modes `3..K`.
use crate::store::run_store::RunRecord;

/// The shape a run ended with: its `K`, `s` of mode 2 and the amplitudes of modes `3..K`
/// (`a3..aK, b3..bK`).
#[derive(Debug, Clone, PartialEq)]
pub struct EndShape {
    pub modes: usize,
    pub s: f64,
    pub higher: Vec<f64>,
}

impl EndShape {
    pub fn of(r: &RunRecord) -> Self {
        Self {
            modes: r.params.modes,
            s: r.outcome.s,
            higher: r.outcome.higher_modes.clone(),
        }
    }

    /// `(a_k, b_k)` for `k >= 3` (`None` beyond its `K`).
    pub fn amplitude(&self, k: usize) -> (Option<f64>, Option<f64>) {
        if k > self.modes {
            return (None, None);
        }
        let h = &self.higher;
        (
            h.get(k - 3).copied(),
            h.get(self.modes - 2 + k - 3).copied(),
        )
    }

    /// `sqrt(sum_k a_k^2 + b_k^2)`, all modes.
    pub fn deformation(&self) -> f64 {
        let higher: f64 = self.higher.iter().map(|x| x * x).sum();
        (self.s * self.s + higher).sqrt()
    }
}
