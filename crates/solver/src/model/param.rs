//! One model parameter by name (paper Sect. 3): what a continuation line varies, and what a
//! sweep axis sets. Which of them enter the steady states: `eta_t`, `kappa2` (the force
//! balance), `radius`, `sigma` (the droplet's indicator) and `box_len` (the periodic images);
//! `eta2` and `mass` multiply time derivatives only (eqs. 36-39), so they move the eigenvalues
//! of a steady state, never the state itself.
use crate::model::params::ModelParams;
use serde::Serialize;

/// A parameter of [`ModelParams`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ModelParam {
    EtaT,
    Kappa2,
    Eta2,
    Mass,
    Radius,
    Sigma,
    BoxLen,
}

impl ModelParam {
    /// Every model parameter.
    pub const ALL: [ModelParam; 7] = [
        ModelParam::EtaT,
        ModelParam::Kappa2,
        ModelParam::Eta2,
        ModelParam::Mass,
        ModelParam::Radius,
        ModelParam::Sigma,
        ModelParam::BoxLen,
    ];

    /// Its name (the field of [`ModelParams`], the spec key, the table column).
    pub fn name(self) -> &'static str {
        match self {
            ModelParam::EtaT => "eta_t",
            ModelParam::Kappa2 => "kappa2",
            ModelParam::Eta2 => "eta2",
            ModelParam::Mass => "mass",
            ModelParam::Radius => "radius",
            ModelParam::Sigma => "sigma",
            ModelParam::BoxLen => "box_len",
        }
    }

    /// The parameter of a name.
    pub fn parse(name: &str) -> Option<ModelParam> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Every name, for messages.
    pub fn names() -> String {
        Self::ALL.map(ModelParam::name).join(", ")
    }

    pub fn get(self, p: &ModelParams) -> f64 {
        match self {
            ModelParam::EtaT => p.eta_t,
            ModelParam::Kappa2 => p.kappa2,
            ModelParam::Eta2 => p.eta2,
            ModelParam::Mass => p.mass,
            ModelParam::Radius => p.radius,
            ModelParam::Sigma => p.sigma,
            ModelParam::BoxLen => p.box_len,
        }
    }

    pub fn set(self, p: &mut ModelParams, x: f64) {
        *match self {
            ModelParam::EtaT => &mut p.eta_t,
            ModelParam::Kappa2 => &mut p.kappa2,
            ModelParam::Eta2 => &mut p.eta2,
            ModelParam::Mass => &mut p.mass,
            ModelParam::Radius => &mut p.radius,
            ModelParam::Sigma => &mut p.sigma,
            ModelParam::BoxLen => &mut p.box_len,
        } = x;
    }

    /// `p` with this parameter at `x`.
    pub fn with(self, p: &ModelParams, x: f64) -> ModelParams {
        let mut out = *p;
        self.set(&mut out, x);
        out
    }

    /// Whether the droplet's shape or the box change with it (a steady solver must sample
    /// its indicator again), rather than only the force balance or the time scales.
    pub fn is_geometric(self) -> bool {
        matches!(
            self,
            ModelParam::Radius | ModelParam::Sigma | ModelParam::BoxLen
        )
    }
}

impl std::fmt::Display for ModelParam {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_parameter_is_its_own_field() {
        for p in ModelParam::ALL {
            assert_eq!(ModelParam::parse(p.name()), Some(p));
            let q = p.with(&ModelParams::default(), 3.25);
            assert_eq!(p.get(&q), 3.25);
            for other in ModelParam::ALL.into_iter().filter(|&o| o != p) {
                assert_eq!(other.get(&q), other.get(&ModelParams::default()), "{p}");
            }
        }
    }
}
