//! How a run decides that it is steady ([`SteadyMethod`], a solver setting and part of the run
//! key) and what ended a steady run ([`Ending`], part of its outcome). The Newton finish
//! itself is [`crate::runs::finish`].
use serde::{Deserialize, Serialize};

/// How a run decides that it is steady.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum SteadyMethod {
    /// The paper's test alone (max change of `vx, vy, a2, b2` per window below the tolerance).
    #[default]
    Test,
    /// The Newton finish of this module (spectral PDE runs).
    Newton,
}

impl SteadyMethod {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Test => "test",
            Self::Newton => "newton",
        }
    }

    pub fn is_test(&self) -> bool {
        *self == Self::Test
    }

    /// The method runs get unless they say otherwise.
    pub fn default_for_runs() -> Self {
        Self::Newton
    }
}

impl std::str::FromStr for SteadyMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "test" => Ok(Self::Test),
            "newton" => Ok(Self::Newton),
            other => Err(format!("unknown steady method `{other}`: test or newton")),
        }
    }
}

/// What ended a steady run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Ending {
    /// The paper's test fired (with `steady: newton`, the root's stability confirmed it and
    /// the state is polished to the root).
    Test,
    /// Newton found a stable root that the run was approaching.
    Newton,
    /// The run's one-dimensional quasi-steady flow lands on a stable root
    /// ([`crate::runs::landing`]), which Newton and the root's eigenvalues confirmed.
    Landing,
    /// Not stepped: a point of a refined map midway between two coarser points whose runs all
    /// ended on one state, certified by that state's root and stability at the point (a
    /// sweep's `refine.certify_midpoints`): the end is the root continued from the
    /// neighbours' runs from the same initial condition.
    Certified,
}

impl Ending {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Certified => "certified_midway",
            Self::Test => "steady_by_test",
            Self::Newton => "steady_by_newton",
            Self::Landing => "steady_by_landing",
        }
    }
}
