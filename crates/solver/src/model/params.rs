//! Model parameters of the droplet (paper Sect. 3, eqs. 31-39, with its shape modes `2..=K`)
//! and their validation.
use crate::error::{require, SolverError};
use crate::model::shape::ShapeParams;
use serde::{Deserialize, Serialize};

/// Dimensionless model parameters.
///
/// `eta_t` is the translational friction, `kappa2` the line-tension stiffness of mode 2,
/// `eta2` its friction, `radius` the droplet radius `R`, `sigma` the width of the smoothed
/// indicator `Theta_sigma` (eq. 31), `box_len` the side `L` of the periodic square, and `mass`
/// the inertia `m` (`m dv/dt = -eta_t v + F`; `m = 0` means overdamped `eta_t dr_c/dt = F`,
/// docs/model.md, "Inertia": the paper's IC/MD bistability needs `m` of at least about 0.03,
/// since with `m -> 0` the initial velocity is forgotten; default 0.1). `modes` is `K`, the
/// shape modes `2..=K` of the paper's general model (default 2, the paper's truncation), and
/// `eta_k_exponent` the friction law of the modes `k >= 3`, `eta_k = eta2 (k / 2)^p`
/// ([`crate::model::friction`], default 0). Both are always written (the same keys for every
/// `K`) and read with their defaults where absent (records and tables written before they
/// were model parameters).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelParams {
    pub eta_t: f64,
    pub kappa2: f64,
    pub eta2: f64,
    pub radius: f64,
    pub sigma: f64,
    pub box_len: f64,
    pub mass: f64,
    #[serde(default = "two_modes")]
    pub modes: usize,
    #[serde(default)]
    pub eta_k_exponent: f64,
}

fn two_modes() -> usize {
    2
}

impl Default for ModelParams {
    /// The paper's values (R = 1, eta2 = 0.1, sigma = 0.03, L = 7) with m = 0.1 and the
    /// Fig. 1(c) point (eta_t = 0.085, kappa2 = 0.112).
    fn default() -> Self {
        Self {
            eta_t: 0.085,
            kappa2: 0.112,
            eta2: 0.1,
            radius: 1.0,
            sigma: 0.03,
            box_len: 7.0,
            mass: 0.1,
            modes: 2,
            eta_k_exponent: 0.0,
        }
    }
}

impl ModelParams {
    /// Same defaults with the swept pair replaced.
    pub fn at(eta_t: f64, kappa2: f64) -> Self {
        Self {
            eta_t,
            kappa2,
            ..Self::default()
        }
    }

    /// The droplet's radius and interface width, what its indicator `Theta` is sampled with.
    pub fn shape(&self) -> ShapeParams {
        ShapeParams {
            radius: self.radius,
            sigma: self.sigma,
        }
    }

    /// The names of the fields that give the model's shape modes: `K` and the friction law of
    /// the modes `k >= 3` (solver settings in records written before they were model
    /// parameters).
    pub const SHAPE_MODE_FIELDS: [&'static str; 2] = ["modes", "eta_k_exponent"];

    /// The same model with shape modes `2..=k` (with `k = 2` the friction law of the modes
    /// `k >= 3` has nothing to act on: its exponent is 0, as [`Self::validate`] asks).
    pub fn with_modes(self, k: usize) -> Self {
        Self {
            modes: k,
            eta_k_exponent: if k == 2 { 0.0 } else { self.eta_k_exponent },
            ..self
        }
    }

    /// Checks every field; the droplet (with a margin of 20 sigma) must fit in the box.
    pub fn validate(&self) -> Result<(), SolverError> {
        require(self.eta_t > 0.0, "eta_t", self.eta_t, "a finite number > 0")?;
        require(
            self.kappa2 >= 0.0,
            "kappa2",
            self.kappa2,
            "a finite number >= 0",
        )?;
        require(self.eta2 > 0.0, "eta2", self.eta2, "a finite number > 0")?;
        require(
            self.radius > 0.0,
            "radius",
            self.radius,
            "a finite number > 0",
        )?;
        require(
            self.sigma > 0.0 && self.sigma <= 0.25 * self.radius,
            "sigma",
            self.sigma,
            format!(
                "a finite number > 0 and at most R/4 = {} (the interface must be thinner than the droplet)",
                0.25 * self.radius
            ),
        )?;
        require(
            self.mass >= 0.0,
            "mass",
            self.mass,
            "a finite number >= 0 (0 = overdamped)",
        )?;
        require(
            self.box_len > 2.0 * (self.radius + crate::model::shape::BAND_Q * self.sigma),
            "box_len",
            self.box_len,
            "a finite number > 2 (R + 16 sigma), so that the droplet and its interface fit in the box",
        )?;
        crate::model::modes::check_count(self.modes)?;
        crate::model::friction::check_exponent(self.eta_k_exponent, self.modes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_bad_values_are_named() {
        assert!(ModelParams::default().validate().is_ok());
        let bad = ModelParams {
            eta_t: f64::NAN,
            ..Default::default()
        };
        match bad.validate() {
            Err(SolverError::InvalidParameter { name, .. }) => assert_eq!(name, "eta_t"),
            other => panic!("expected eta_t error, got {other:?}"),
        }
        let small_box = ModelParams {
            box_len: 2.5,
            ..Default::default()
        };
        assert!(small_box.validate().is_err());
        let neg_mass = ModelParams {
            mass: -0.1,
            ..Default::default()
        };
        assert!(neg_mass.validate().is_err());
    }
}
