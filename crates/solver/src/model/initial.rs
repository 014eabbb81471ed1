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
    /// The amplitudes `(a_k, b_k)` of shape modes `k = 3, 4, ...` (the paper's general
    /// shape, eq. 31 with `k >= 3`), for runs of the K-mode model; modes not given start at
    /// 0. Empty for every 2-mode condition (and then not serialised: run keys unchanged).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub higher: Vec<[f64; 2]>,
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

/// The form of a custom condition.
const CUSTOM_FORM: &str = "expected four numbers custom:vx,vy,a2,b2, then for K-mode runs \
                           pairs a_k,b_k for k = 3, 4, ...";

/// Largest initial speed `sqrt(vx^2 + vy^2)` a custom condition may give. The model's steady
/// states move at `v < 1.1` in the paper's window (the ODE model's fastest MD) and its named
/// conditions start at `v <= 1.005`; a start ten times faster than any state it could reach
/// only tests how the stepping fails (at `v = 1e308` the first step overflows).
pub const MAX_START_SPEED: f64 = 10.0;

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
            higher: Vec::new(),
        }
    }

    /// The highest shape mode this condition gives an amplitude for (2 without `higher`).
    pub fn highest_mode(&self) -> usize {
        2 + self.higher.len()
    }

    /// Refuses a condition with amplitudes for modes beyond `k_max` (the run's `modes`).
    pub fn check_modes(&self, k_max: usize) -> Result<(), SolverError> {
        if self.highest_mode() <= k_max {
            return Ok(());
        }
        Err(SolverError::InvalidInitialCondition {
            text: self.name.clone(),
            reason: format!(
                "amplitudes are given up to mode {}, beyond the run's shape modes 2..{k_max} \
                 (params.modes, --modes): raise modes to {} or drop them",
                self.highest_mode(),
                self.highest_mode()
            ),
        })
    }

    /// Parses `i`, `ii`, `iii`, `iv`, `i'`, `ii'` (also `ip`, `iip`) or `custom:vx,vy,a2,b2`,
    /// the latter optionally followed by `a3,b3,a4,b4,...` (amplitudes of modes 3, 4, ...).
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
                higher: Vec::new(),
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
                .map_err(|_| bad(CUSTOM_FORM.into()))?;
            if parts.len() < 4 || !parts.len().is_multiple_of(2) {
                return Err(bad(format!("{CUSTOM_FORM}, got {} numbers", parts.len())));
            }
            if !parts.iter().all(|p| p.is_finite()) {
                return Err(bad("every value must be finite".into()));
            }
            let speed = parts[0].hypot(parts[1]);
            if speed > MAX_START_SPEED {
                return Err(bad(format!(
                    "the initial speed sqrt(vx^2 + vy^2) = {speed:e} must be at most {MAX_START_SPEED} (steady states move at v < 1.1)"
                )));
            }
            let higher: Vec<[f64; 2]> = parts[4..].chunks(2).map(|c| [c[0], c[1]]).collect();
            // The shape r = R [1 + sum_k (a_k cos k theta + b_k sin k theta)] stays star-shaped
            // and small (eq. 31) only if the amplitudes' sizes add up to less than 1.
            let total: f64 = std::iter::once([parts[2], parts[3]])
                .chain(higher.iter().copied())
                .map(|[a, b]| a.hypot(b))
                .sum();
            if total >= 1.0 {
                let what = if higher.is_empty() {
                    "s = sqrt(a2^2 + b2^2)"
                } else {
                    "sum_k sqrt(a_k^2 + b_k^2)"
                };
                return Err(bad(format!(
                    "the deformation {what} = {total} must be < 1 (the small-deformation model, eq. 31)"
                )));
            }
            let mut ic = Self::custom(parts[0], parts[1], parts[2], parts[3]);
            if !higher.is_empty() {
                ic.name = format!("custom:{}", rest.trim());
                ic.higher = higher;
            }
            return Ok(ic);
        }
        Err(SolverError::UnknownInitialCondition(text.to_string()))
    }

    /// The unknowns `(vx, vy, a_2..a_K, b_2..b_K)` of the droplet with shape modes
    /// `2..=k_max`: the amplitudes of modes `3..K` given ([`Self::higher`]), 0 for the others.
    pub fn unknowns(&self, k_max: usize) -> Vec<f64> {
        let mode = |k: usize| self.higher.get(k - 3).copied().unwrap_or([0.0; 2]);
        let mut z = vec![self.vx, self.vy, self.a2];
        z.extend((3..=k_max).map(|k| mode(k)[0]));
        z.push(self.b2);
        z.extend((3..=k_max).map(|k| mode(k)[1]));
        z
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
            // Mode k turns by k quarter turns: (a, b) -> (a cos k pi/2 - b sin k pi/2, ...).
            for (i, [a, b]) in ic.higher.iter_mut().enumerate() {
                let k = i + 3;
                (*a, *b) = match k % 4 {
                    0 => (*a, *b),
                    1 => (-*b, *a),
                    2 => (-*a, -*b),
                    _ => (*b, -*a),
                };
            }
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
        // Speeds up to the bound are accepted, beyond it refused (1e308 overflowed the
        // first step's field and hung the K-mode eigenvalues on NaN).
        assert!(InitialCondition::parse("custom:6,-8,0.1,0").is_ok());
        let e = InitialCondition::parse("custom:1e308,0,0.1,0")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("initial speed") && e.contains("at most 10"),
            "{e}"
        );
        assert!(InitialCondition::parse("custom:0,10.001,0.1,0").is_err());
    }

    #[test]
    fn custom_conditions_give_higher_modes_in_pairs() {
        let c = InitialCondition::parse("custom:0.01,0,0.1,0,0.02,-0.01,0,0.005").unwrap();
        assert_eq!(c.higher, vec![[0.02, -0.01], [0.0, 0.005]]);
        assert_eq!(c.highest_mode(), 4);
        assert!(c.check_modes(4).is_ok() && c.check_modes(6).is_ok());
        let e = c.check_modes(3).unwrap_err().to_string();
        assert!(e.contains("mode 4") && e.contains("modes"), "{e}");
        // A 2-mode condition is unchanged (no `higher` in its serialised form).
        let two = InitialCondition::parse("custom:0.5,0,0.1,0").unwrap();
        assert!(two.higher.is_empty() && two.check_modes(2).is_ok());
        // Odd counts, and shapes too large in sum.
        assert!(InitialCondition::parse("custom:0,0,0.1,0,0.02").is_err());
        assert!(InitialCondition::parse("custom:0,0,0.5,0,0.4,0.4").is_err());
    }

    #[test]
    fn a_quarter_turn_turns_mode_k_by_k_quarter_turns() {
        let c = InitialCondition::parse("custom:0,0,0.1,0,0.02,0.01,0.03,0.004").unwrap();
        let r = c.rotated(1);
        // Mode 3 by 270 degrees: (a, b) -> (b, -a); mode 4 by 360 degrees: unchanged.
        assert_eq!(r.higher, vec![[0.01, -0.02], [0.03, 0.004]]);
        assert_eq!(c.rotated(4).higher, c.higher);
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
