//! Run classes of the paper (Sect. 3): IC, ID, MD, MC from the steady `v` and `s`.
use serde::{Deserialize, Serialize};
use std::fmt;

/// The paper's threshold on `v` and `s` (0.01).
pub const CLASS_THRESHOLD: f64 = 0.01;

/// State class of a droplet from its speed and deformation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum StateClass {
    /// Immobile circular: `v <= 0.01, s <= 0.01`.
    IC,
    /// Immobile deformed: `v <= 0.01, s > 0.01`.
    ID,
    /// Mobile deformed: `v > 0.01, s > 0.01`.
    MD,
    /// Mobile circular: `v > 0.01, s <= 0.01`.
    MC,
}

impl StateClass {
    /// Classifies with the paper's threshold 0.01.
    pub fn of(v: f64, s: f64) -> Self {
        Self::with_threshold(v, s, CLASS_THRESHOLD)
    }

    /// Classifies with a custom threshold on both `v` and `s`.
    pub fn with_threshold(v: f64, s: f64, threshold: f64) -> Self {
        match (v > threshold, s > threshold) {
            (false, false) => Self::IC,
            (false, true) => Self::ID,
            (true, true) => Self::MD,
            (true, false) => Self::MC,
        }
    }

    /// Short name as printed in tables ("IC", ...).
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::IC => "IC",
            Self::ID => "ID",
            Self::MD => "MD",
            Self::MC => "MC",
        }
    }

    /// Parses the short name.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "IC" => Some(Self::IC),
            "ID" => Some(Self::ID),
            "MD" => Some(Self::MD),
            "MC" => Some(Self::MC),
            _ => None,
        }
    }
}

impl fmt::Display for StateClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thresholds_follow_the_paper() {
        assert_eq!(StateClass::of(0.0, 0.0), StateClass::IC);
        assert_eq!(StateClass::of(0.01, 0.01), StateClass::IC);
        assert_eq!(StateClass::of(0.0, 0.0101), StateClass::ID);
        assert_eq!(StateClass::of(0.5, 0.2), StateClass::MD);
        assert_eq!(StateClass::of(0.2, 0.005), StateClass::MC);
        for c in [
            StateClass::IC,
            StateClass::ID,
            StateClass::MD,
            StateClass::MC,
        ] {
            assert_eq!(StateClass::parse(c.as_str()), Some(c));
        }
    }
}
