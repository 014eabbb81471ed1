//! The forces of the last few droplets `(velocity, shape)` a `K`-mode solver computed, for its
//! residuals: a nested difference Jacobian (the fold curve's `det` of an inner Jacobian, the
//! outer one's columns in `eta_t` and `kappa2`, which move no field) asks for the same
//! droplets many times. The field of a droplet depends on nothing else a solver changes
//! (`eta_t`, `kappa2` and the friction law enter only the balances), so a kept value is exact.
use crate::model::modes::Modes;
use crate::roots::mode_solver::ModeForces;

/// Droplets kept: every state of one central-difference Jacobian up to `K = 16` (`2K + 1`).
const KEPT: usize = 40;

/// The kept forces, the newest first.
#[derive(Default)]
pub(crate) struct ForcesMemo {
    kept: Vec<(f64, f64, Modes, ModeForces)>,
}

impl ForcesMemo {
    /// The forces on `m` moving at `(vx, vy)`, if kept.
    pub(crate) fn get(&self, vx: f64, vy: f64, m: &Modes) -> Option<ModeForces> {
        self.kept
            .iter()
            .find(|(x, y, k, _)| *x == vx && *y == vy && k == m)
            .map(|(.., f)| f.clone())
    }

    /// Keeps `f`, the forces on `m` moving at `(vx, vy)`, forgetting the oldest beyond
    /// [`KEPT`].
    pub(crate) fn keep(&mut self, vx: f64, vy: f64, m: &Modes, f: &ModeForces) {
        if self.kept.len() == KEPT {
            self.kept.pop();
        }
        self.kept.insert(0, (vx, vy, m.clone(), f.clone()));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_the_newest_and_matches_exactly() {
        let f = |x: f64| ModeForces {
            fx: x,
            fy: 0.0,
            ga: vec![x],
            gb: vec![0.0],
            area: 1.0,
        };
        let m = |a: f64| Modes {
            a: vec![a],
            b: vec![0.0],
        };
        let mut memo = ForcesMemo::default();
        for i in 0..=KEPT {
            memo.keep(0.1, 0.0, &m(i as f64), &f(i as f64));
        }
        assert_eq!(memo.get(0.1, 0.0, &m(3.0)), Some(f(3.0)));
        // The oldest is gone; another speed or shape is another droplet.
        assert_eq!(memo.get(0.1, 0.0, &m(0.0)), None);
        assert_eq!(memo.get(0.1 + 1e-16, 0.0, &m(3.0)), None);
        assert_eq!(memo.get(0.1, 0.0, &m(3.0 + 1e-15)), None);
    }
}
