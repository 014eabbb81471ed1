//! The window in which phase boundaries are computed: two model parameters, each an [`Axis`]
//! (the parameter and its range), the others fixed, the grid and the model's shape modes. The
//! paper's plane `(eta_t, kappa2)` is one such window ([`Window::paper`]).
use crate::contract::limits::check_modes;
use crate::error::SolverError;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;

/// One axis of a window: the parameter and its range (`q = 0` and `1` at its ends).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis {
    pub param: ModelParam,
    pub range: (f64, f64),
}

impl Axis {
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

/// A window of two model parameters, the model and the resolution of its boundaries
/// ([`crate::continuation::boundaries::boundaries`]).
#[derive(Debug, Clone)]
pub struct Window {
    /// The other parameters (the axes' values are overwritten), the shape modes
    /// `2..=base.modes` among them (2: the paper's model).
    pub base: ModelParams,
    pub n: usize,
    pub x: Axis,
    pub y: Axis,
    /// The resolution: in the paper's plane the samples in `kappa2` of its sampled lines (the
    /// ID and MC onsets); elsewhere the samples along each edge and midline where a traced
    /// curve is looked for.
    pub samples: usize,
}

impl Window {
    /// The window `eta_t` x `kappa2` of the paper's plane.
    pub fn paper(
        base: ModelParams,
        n: usize,
        eta_t: (f64, f64),
        kappa2: (f64, f64),
        samples: usize,
    ) -> Self {
        Self {
            base,
            n,
            x: Axis::new(ModelParam::EtaT, eta_t),
            y: Axis::new(ModelParam::Kappa2, kappa2),
            samples,
        }
    }

    /// Whether the window lies in the paper's plane, `eta_t` across and `kappa2` up.
    pub fn in_paper_plane(&self) -> bool {
        self.x.param == ModelParam::EtaT && self.y.param == ModelParam::Kappa2
    }

    /// A point of the plane from `q`.
    pub fn point(&self, (qx, qy): (f64, f64)) -> (f64, f64) {
        (self.x.value(qx), self.y.value(qy))
    }

    /// Refuses a window whose boundaries cannot be computed: invalid parameters, an axis that
    /// is one parameter twice or spans no range, shape modes the grid does not resolve, or
    /// more than two shape modes outside the paper's plane (there every curve is traced with
    /// the 2-mode solver; in the paper's plane every curve has a computation for every `K`).
    pub fn check(&self) -> Result<(), SolverError> {
        self.base.validate()?;
        for a in [&self.x, &self.y] {
            let (lo, hi) = a.range;
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(SolverError::InvalidChoice {
                    name: "window",
                    value: format!("{} from {lo} to {hi}", a.param.name()),
                    allowed: "a range of two finite numbers, the first the smaller".into(),
                });
            }
        }
        if self.x.param == self.y.param {
            return Err(SolverError::InvalidChoice {
                name: "window",
                value: format!("{} against itself", self.x.param.name()),
                allowed: "two different parameters".into(),
            });
        }
        check_modes(&self.base, self.n, self.base.modes)?;
        if self.base.modes > 2 && !self.in_paper_plane() {
            return Err(SolverError::InvalidChoice {
                name: "modes",
                value: self.base.modes.to_string(),
                allowed: format!(
                    "2 in a window of {} and {}: outside the paper's plane (eta_t, kappa2) the \
                     boundaries are traced with the 2-mode solver only",
                    self.x.param.name(),
                    self.y.param.name()
                ),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_is_refused_where_its_boundaries_cannot_be_computed() {
        let base = ModelParams::at(0.077, 0.14);
        let paper = Window::paper(base.with_modes(4), 96, (0.07, 0.1), (0.1, 0.17), 10);
        assert!(paper.in_paper_plane() && paper.check().is_ok());
        let pair = Window {
            x: Axis::new(ModelParam::Radius, (0.95, 1.05)),
            y: Axis::new(ModelParam::Sigma, (0.03, 0.05)),
            ..paper.clone()
        };
        let name = |w: &Window| match w.check() {
            Err(SolverError::InvalidChoice { name, .. }) => name,
            Err(SolverError::InvalidParameter { name, .. }) => name,
            other => panic!("{w:?}: {other:?}"),
        };
        assert_eq!(name(&pair), "modes");
        assert!(Window {
            base,
            ..pair.clone()
        }
        .check()
        .is_ok());
        // Turned round, the paper's parameters are traced as any other pair.
        let turned = Window {
            x: paper.y,
            y: paper.x,
            ..paper.clone()
        };
        assert!(!turned.in_paper_plane());
        assert_eq!(name(&turned), "modes");
        for bad in [
            Window {
                y: paper.x,
                base,
                ..paper.clone()
            },
            Window {
                x: Axis::new(ModelParam::EtaT, (0.1, 0.07)),
                ..paper.clone()
            },
            Window {
                x: Axis::new(ModelParam::EtaT, (0.07, f64::NAN)),
                ..paper.clone()
            },
        ] {
            assert_eq!(name(&bad), "window");
        }
        // Eight modes are not resolved at N = 64.
        assert_eq!(
            name(&Window {
                n: 64,
                base: base.with_modes(8),
                ..paper
            }),
            "modes"
        );
    }
}
