//! The parameters a sweep may vary, named in one place: spec keys, table columns, picture
//! axes and messages all take their names from here. A point's coordinates are the values of
//! the spec's grid axes, in the order the `grid` section gives them ([`Plane`]).
use droplet_solver::{
    contract::settings::SolverSettings, model::param::ModelParam, model::params::ModelParams,
};
use serde::Serialize;

/// Translational friction `eta_t` (the paper's phase map's horizontal axis, Fig. 2a).
pub const ETA_T: &str = "eta_t";
/// Mode-2 stiffness `kappa2` (its vertical axis).
pub const KAPPA2: &str = "kappa2";

/// A parameter a grid axis may sweep: a model parameter (paper Sect. 3, the solver's
/// [`ModelParam`]) or a solver setting whose effect on a result is worth measuring (the grid,
/// the tolerance, the largest step, the time limit).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Param {
    Model(ModelParam),
    N,
    Tol,
    DtMax,
    TMax,
}

impl Param {
    pub const ETA_T: Param = Param::Model(ModelParam::EtaT);
    pub const KAPPA2: Param = Param::Model(ModelParam::Kappa2);
    pub const ETA2: Param = Param::Model(ModelParam::Eta2);
    pub const MASS: Param = Param::Model(ModelParam::Mass);

    /// Every sweepable parameter, model parameters first.
    pub const ALL: [Param; 11] = [
        Param::ETA_T,
        Param::KAPPA2,
        Param::ETA2,
        Param::MASS,
        Param::Model(ModelParam::Radius),
        Param::Model(ModelParam::Sigma),
        Param::Model(ModelParam::BoxLen),
        Param::N,
        Param::Tol,
        Param::DtMax,
        Param::TMax,
    ];

    /// The key: the name in the spec's `params` or `solver` section and the table column.
    pub fn name(self) -> &'static str {
        match self {
            Param::Model(m) => m.name(),
            Param::N => "n",
            Param::Tol => "tol",
            Param::DtMax => "dt_max",
            Param::TMax => "t_max",
        }
    }

    /// The parameter of a key.
    pub fn parse(name: &str) -> Option<Param> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Every key, for messages: `eta_t, kappa2, ...`.
    pub fn names() -> String {
        Self::ALL.map(Param::name).join(", ")
    }

    /// A model parameter (set in `params:`), not a solver setting (`solver:`).
    pub fn is_model(self) -> bool {
        self.model().is_some()
    }

    /// A model parameter that multiplies time derivatives only (`eta2`, `mass`; paper eqs.
    /// 36-39): it moves no steady state and no boundary where a real eigenvalue crosses zero.
    pub fn rate_only(self) -> bool {
        matches!(self, Param::ETA2 | Param::MASS)
    }

    /// The model parameter, for a model parameter.
    pub fn model(self) -> Option<ModelParam> {
        match self {
            Param::Model(m) => Some(m),
            _ => None,
        }
    }

    /// Whether a value is in the parameter's domain as far as it can be told alone (finite,
    /// the sign, an integer grid size), and the rule in words. Everything that depends on
    /// other values (`sigma <= R/4`, the box holding the droplet, `n` even and resolving the
    /// interface) is the solver's own validation, run on every point of the grid.
    pub fn admits(self, x: f64) -> (bool, &'static str) {
        match self {
            Param::KAPPA2 => (x >= 0.0, "finite numbers >= 0"),
            Param::MASS => (x >= 0.0, "finite numbers >= 0 (0 = overdamped)"),
            Param::Tol => (x >= 0.0, "finite numbers >= 0 (0 = fixed step)"),
            Param::N => (
                x > 0.0 && x.fract() == 0.0 && x <= droplet_solver::model::grid::MAX_N as f64,
                "even integers from 16 to 4096 (model::grid::MAX_N)",
            ),
            _ => (x > 0.0, "finite numbers > 0"),
        }
    }

    /// Sets the parameter to `x` in `params` or `settings`.
    pub fn set(self, params: &mut ModelParams, settings: &mut SolverSettings, x: f64) {
        match self {
            Param::Model(m) => m.set(params, x),
            Param::N => settings.n = x as usize,
            Param::Tol => settings.tol = x,
            Param::DtMax => settings.dt_max = x,
            Param::TMax => settings.t_max = x,
        }
    }

    /// The parameter's value in `params` or `settings`.
    pub fn get(self, params: &ModelParams, settings: &SolverSettings) -> f64 {
        match self {
            Param::Model(m) => m.get(params),
            Param::N => settings.n as f64,
            Param::Tol => settings.tol,
            Param::DtMax => settings.dt_max,
            Param::TMax => settings.t_max,
        }
    }
}

/// A parameter is written (in a stored spec's JSON, in `--json`) as its key.
impl Serialize for Param {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl std::fmt::Display for Param {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The swept parameters of a sweep: the plane of its maps, the first grid axis `x` and the
/// second `y`, and in a 3-axis grid the slice axis `z` (one map per value). A point is
/// `[x, y, z]`; a coordinate without an axis is 0 and means nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Plane {
    pub x: Param,
    pub y: Option<Param>,
    pub z: Option<Param>,
}

/// A point's coordinates `[x, y, z]` ([`Plane`]).
pub type Point = [f64; 3];

impl Plane {
    /// The paper's plane, `(eta_t, kappa2)`.
    pub const PAPER: Plane = Plane {
        x: Param::ETA_T,
        y: Some(Param::KAPPA2),
        z: None,
    };

    /// The axes, in order.
    pub fn params(&self) -> Vec<Param> {
        std::iter::once(self.x)
            .chain(self.y)
            .chain(self.z)
            .collect()
    }

    /// The axes with their coordinate's index.
    fn indexed(&self) -> impl Iterator<Item = (usize, Param)> {
        [Some(self.x), self.y, self.z]
            .into_iter()
            .enumerate()
            .filter_map(|(i, p)| p.map(|p| (i, p)))
    }

    /// Sets a point's coordinates in `params` and `settings`.
    pub fn apply(&self, point: Point, params: &mut ModelParams, settings: &mut SolverSettings) {
        for (i, p) in self.indexed() {
            p.set(params, settings, point[i]);
        }
    }

    /// Whether this is the paper's plane, where the reduced model's analytic boundaries and
    /// the full model's exact ones (`droplet boundaries`) are drawn.
    pub fn is_paper(&self) -> bool {
        *self == Self::PAPER
    }
}

/// Rounds an axis value to 12 decimal places after the point: values on a decimal grid
/// (`0.07 + 3 * 0.01` is `0.1`), so that equal points in two specs, or on two refinement
/// levels, get equal run keys.
pub fn round12(x: f64) -> f64 {
    (x * 1e12).round() / 1e12
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_parameter_is_set_and_read_back_under_its_own_name() {
        for p in Param::ALL {
            assert_eq!(Param::parse(p.name()), Some(p));
            let (mut params, mut settings) = (ModelParams::default(), SolverSettings::default());
            p.set(&mut params, &mut settings, 64.0);
            assert_eq!(p.get(&params, &settings), 64.0, "{p}");
            // Nothing else moved.
            let others = Param::ALL.into_iter().filter(|&q| q != p);
            for q in others {
                let fresh = q.get(&ModelParams::default(), &SolverSettings::default());
                assert_eq!(q.get(&params, &settings), fresh, "{p} moved {q}");
            }
        }
        assert_eq!(Param::parse("eta_T"), None);
    }

    #[test]
    fn a_plane_applies_its_coordinates() {
        let plane = Plane {
            x: Param::MASS,
            y: Some(Param::ETA_T),
            z: Some(Param::ETA2),
        };
        let (mut p, mut s) = (ModelParams::default(), SolverSettings::default());
        plane.apply([0.3, 0.09, 0.2], &mut p, &mut s);
        assert_eq!((p.mass, p.eta_t, p.eta2), (0.3, 0.09, 0.2));
        assert!(!plane.is_paper() && Plane::PAPER.is_paper());
        let line = Plane {
            x: Param::N,
            y: None,
            z: None,
        };
        line.apply([128.0, 5.0, 7.0], &mut p, &mut s);
        // The coordinates without an axis are not applied.
        assert_eq!(
            (s.n, p.eta_t, p.kappa2),
            (128, 0.09, ModelParams::default().kappa2)
        );
    }
}
