//! Initial conditions of the paper: (i)-(iv) of Sect. 3 and the symmetric (i'), (ii') of
//! Fig. 2(b), plus custom ones. In every case `u = 0` and `r_c = 0` at `t = 0`.
use crate::error::SolverError;
use crate::model::state::DropletState;
use serde::{Deserialize, Serialize};

/// An initial velocity and shape, with the name it is reported under.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InitialCondition {
    pub name: String,
    pub vx: f64,
    pub vy: f64,
    pub a2: f64,
    pub b2: f64,
}

/// The paper's named initial conditions, in the order (i), (ii), (iii), (iv), (i'), (ii').
pub const NAMED: [(&str, [f64; 4]); 6] = [
    ("i", [1.0, 0.1, 0.1, 0.01]),
    ("ii", [1.0, 0.01, -0.25, 0.002]),
    ("iii", [0.01, 0.001, 0.1, 0.01]),
    ("iv", [0.01, 0.001, 0.01, 0.001]),
    ("i'", [1.0, 0.0, -0.1, 0.0]),
    ("ii'", [0.001, 0.0, -0.1, 0.0]),
];

/// The four initial conditions used for every point of the phase map (Fig. 2a).
pub const PAPER_FOUR: [&str; 4] = ["i", "ii", "iii", "iv"];

impl InitialCondition {
    /// A custom initial condition.
    pub fn custom(vx: f64, vy: f64, a2: f64, b2: f64) -> Self {
        Self {
            name: format!("custom:{vx},{vy},{a2},{b2}"),
            vx,
            vy,
            a2,
            b2,
        }
    }

    /// Parses `i`, `ii`, `iii`, `iv`, `i'`, `ii'` (also `ip`, `iip`) or `custom:vx,vy,a2,b2`.
    pub fn parse(text: &str) -> Result<Self, SolverError> {
        let key = match text.trim() {
            "ip" => "i'",
            "iip" => "ii'",
            other => other,
        };
        if let Some((name, [vx, vy, a2, b2])) = NAMED.iter().find(|(n, _)| *n == key) {
            return Ok(Self {
                name: name.to_string(),
                vx: *vx,
                vy: *vy,
                a2: *a2,
                b2: *b2,
            });
        }
        if let Some(rest) = key.strip_prefix("custom:") {
            let bad = |reason: String| SolverError::InvalidInitialCondition {
                text: text.to_string(),
                reason,
            };
            let parts: Vec<f64> = rest
                .split(',')
                .map(|p| p.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| bad("expected four numbers custom:vx,vy,a2,b2".into()))?;
            let [vx, vy, a2, b2] = parts[..] else {
                return Err(bad(format!(
                    "expected four numbers custom:vx,vy,a2,b2, got {}",
                    parts.len()
                )));
            };
            if !parts.iter().all(|p| p.is_finite()) {
                return Err(bad("every value must be finite".into()));
            }
            let s = a2.hypot(b2);
            if s >= 1.0 {
                return Err(bad(format!(
                    "the deformation s = sqrt(a2^2 + b2^2) = {s} must be < 1 (the small-deformation model, eq. 31)"
                )));
            }
            return Ok(Self::custom(vx, vy, a2, b2));
        }
        Err(SolverError::UnknownInitialCondition(text.to_string()))
    }

    /// The droplet state at `t = 0` (`r_c = 0`).
    pub fn state(&self) -> DropletState {
        DropletState {
            x: 0.0,
            y: 0.0,
            vx: self.vx,
            vy: self.vy,
            a2: self.a2,
            b2: self.b2,
        }
    }

    /// This condition rotated by `quarter_turns` x 90 degrees: `v` rotates by 90 degrees and
    /// `(a2, b2)` by 180 degrees per quarter turn (`f(theta - phi)` with `phi = pi/2`).
    pub fn rotated(&self, quarter_turns: u32) -> Self {
        let mut ic = self.clone();
        for _ in 0..quarter_turns % 4 {
            (ic.vx, ic.vy) = (-ic.vy, ic.vx);
            (ic.a2, ic.b2) = (-ic.a2, -ic.b2);
        }
        ic.name = format!("{}@{}x90", self.name, quarter_turns % 4);
        ic
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_paper_conditions() {
        let ii = InitialCondition::parse("ii").unwrap();
        assert_eq!((ii.vx, ii.vy, ii.a2, ii.b2), (1.0, 0.01, -0.25, 0.002));
        let ip = InitialCondition::parse("ip").unwrap();
        assert_eq!(ip.name, "i'");
        let c = InitialCondition::parse("custom:0.5,0,0.1,0").unwrap();
        assert_eq!((c.vx, c.a2), (0.5, 0.1));
        assert!(InitialCondition::parse("v").is_err());
        assert!(InitialCondition::parse("custom:1,2").is_err());
        assert!(InitialCondition::parse("custom:0,0,0.9,0.9").is_err());
    }

    #[test]
    fn four_quarter_turns_are_the_identity() {
        let i = InitialCondition::parse("i").unwrap();
        let r = i.rotated(1);
        assert_eq!((r.vx, r.vy, r.a2, r.b2), (-0.1, 1.0, -0.1, -0.01));
        let back = i.rotated(4);
        assert_eq!(
            (back.vx, back.vy, back.a2, back.b2),
            (i.vx, i.vy, i.a2, i.b2)
        );
    }
}
