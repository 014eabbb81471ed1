//! The forces of the last few droplets `(velocity, shape)` a steady solver computed, for its
//! residuals: a nested difference Jacobian (the fold curve's `det` of an inner Jacobian, the
//! outer one's columns in `eta_t` and `kappa2`, which move no field) asks for the same
//! droplets many times. The field of a droplet depends only on its velocity, its shape and
//! the solver's geometry (grid, box, radius, sigma); a solver forgets what it kept when its
//! geometry changes, so a kept value is exact.

/// Droplets kept: every state of one central-difference Jacobian up to `K = 16` (`2K + 1`).
const KEPT: usize = 40;

/// The kept forces `V` of droplets `D`, the newest first.
pub(crate) struct ForcesMemo<D, V> {
    kept: Vec<(D, V)>,
}

impl<D, V> Default for ForcesMemo<D, V> {
    fn default() -> Self {
        Self { kept: Vec::new() }
    }
}

impl<D: PartialEq + Clone, V: Clone> ForcesMemo<D, V> {
    /// The forces on `droplet`, if kept.
    pub(crate) fn get(&self, droplet: &D) -> Option<V> {
        self.kept
            .iter()
            .find(|(d, _)| d == droplet)
            .map(|(_, f)| f.clone())
    }

    /// Keeps `f`, the forces on `droplet`, forgetting the oldest beyond [`KEPT`].
    pub(crate) fn keep(&mut self, droplet: &D, f: &V) {
        if self.kept.len() == KEPT {
            self.kept.pop();
        }
        self.kept.insert(0, (droplet.clone(), f.clone()));
    }

    /// Forgets every droplet (the geometry changed).
    pub(crate) fn clear(&mut self) {
        self.kept.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_the_newest_and_matches_exactly() {
        let mut memo = ForcesMemo::default();
        for i in 0..=KEPT {
            memo.keep(&[0.1, i as f64], &(i as f64));
        }
        assert_eq!(memo.get(&[0.1, 3.0]), Some(3.0));
        // The oldest is gone; another speed or shape is another droplet.
        assert_eq!(memo.get(&[0.1, 0.0]), None);
        assert_eq!(memo.get(&[0.1 + 1e-16, 3.0]), None);
        assert_eq!(memo.get(&[0.1, 3.0 + 1e-15]), None);
        memo.clear();
        assert_eq!(memo.get(&[0.1, 3.0]), None);
    }
}
