//! The Jacobians of the force balances at the last few roots Newton found, kept for the
//! chord method: a run's later finish tries usually start near a root found before, and a
//! chord step costs one evaluation of the balances where a Newton step by central
//! differences costs `2 n + 1` (`n` unknowns: 9 for `K = 2`, 17 for `K = 4`).
use crate::error::SolverError;
use crate::numerics::newton::{self, NewtonOptions};

/// The Jacobians at up to [`KeptJacobians::KEPT`] roots, the newest last.
#[derive(Debug, Clone, Default)]
pub struct KeptJacobians {
    entries: Vec<(Vec<f64>, Vec<Vec<f64>>)>,
}

impl KeptJacobians {
    /// Roots whose Jacobians are kept.
    const KEPT: usize = 4;
    /// Largest distance (max over the unknowns) of a start from a kept root for its Jacobian
    /// to be tried.
    const REACH: f64 = 0.05;

    /// The Jacobian kept at the root nearest `z` (with as many unknowns), if within
    /// [`Self::REACH`].
    pub fn near(&self, z: &[f64]) -> Option<&[Vec<f64>]> {
        let distance = |at: &[f64]| {
            at.iter()
                .zip(z)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        };
        self.entries
            .iter()
            .filter(|(at, _)| at.len() == z.len())
            .map(|(at, jac)| (distance(at), jac))
            .filter(|(d, _)| *d <= Self::REACH)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, jac)| jac.as_slice())
    }

    /// Keeps the Jacobian `jac` of the root `at` (the oldest dropped beyond [`Self::KEPT`]).
    pub fn keep(&mut self, at: &[f64], jac: Vec<Vec<f64>>) {
        if self.entries.len() == Self::KEPT {
            self.entries.remove(0);
        }
        self.entries.push((at.to_vec(), jac));
    }

    /// The root of `balance` from `z`: by the chord method ([`newton::chord`], at most 40
    /// steps) with the Jacobian kept nearest `z`, and by Newton under `opts` when none is
    /// near or the chord steps do not converge; a Newton solve's last Jacobian is kept.
    pub fn solve(
        &mut self,
        mut balance: impl FnMut(&[f64]) -> Vec<f64>,
        z: &[f64],
        opts: &NewtonOptions,
    ) -> Result<Vec<f64>, SolverError> {
        let chord = NewtonOptions {
            max_iter: 40,
            ..opts.clone()
        };
        if let Some(sol) = self
            .near(z)
            .and_then(|jac| newton::chord(&mut balance, z, jac, &chord).ok())
        {
            return Ok(sol.x);
        }
        let mut last = None;
        let sol = newton::solve_keeping(&mut balance, z, opts, &mut last);
        if let (Ok(sol), Some(jac)) = (&sol, last) {
            self.keep(&sol.x, jac);
        }
        Ok(sol?.x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_jacobian_solves_a_nearby_start_in_fewer_evaluations_to_the_same_root() {
        // x^2 + y^2 + z^2 = 3, x y = 1, y z = 1: the root (1, 1, 1).
        let count = std::cell::Cell::new(0);
        let f = |v: &[f64]| {
            count.set(count.get() + 1);
            vec![
                v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - 3.0,
                v[0] * v[1] - 1.0,
                v[1] * v[2] - 1.0,
            ]
        };
        let opts = NewtonOptions {
            tol: 1e-12,
            max_iter: 30,
            fd_step: 1e-7,
            max_step: vec![f64::INFINITY; 3],
            one_sided: false,
            backtrack: false,
        };
        let mut kept = KeptJacobians::default();
        let first = kept.solve(f, &[1.2, 0.9, 1.1], &opts).unwrap();
        let newton_evaluations = count.replace(0);
        assert!(kept.near(&[1.01, 0.99, 1.0]).is_some());
        assert!(kept.near(&[1.1, 1.0, 1.0]).is_none(), "beyond the reach");
        assert!(kept.near(&[1.0, 1.0]).is_none(), "other unknowns");
        let second = kept.solve(f, &[1.01, 0.99, 1.0], &opts).unwrap();
        let chord_evaluations = count.get();
        for (a, b) in first.iter().chain(&second).zip([1.0; 6]) {
            assert!((a - b).abs() < 1e-11, "{first:?} {second:?}");
        }
        assert!(
            chord_evaluations < newton_evaluations / 2,
            "{chord_evaluations} chord against {newton_evaluations} Newton evaluations"
        );
    }
}
