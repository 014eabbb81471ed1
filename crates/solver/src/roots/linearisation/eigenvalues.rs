//! The eigenvalues of a [`Linearization`]: the roots of `det T(lambda)` with `Re lambda > -1`,
//! each root found divided out before the next is sought, started from the eigenvalues of the
//! problem linear in `lambda`, `T(0) + lambda T'(0) = 0` (`T'(0) = M + C D^(-2) B`: the inertia
//! with the field's lag, which the guesses of the `lambda = 0` problem `M^(-1) (E + C (-D)^(-1)
//! B)` left out; at K = 4 about half the evaluations of `T`, the same roots): Newton on `det T` (its logarithmic
//! derivative `tr(T^(-1) T')`, exact) until the steps fall below [`POLISH`], then Schroeder's
//! method (Newton on `f / f'`, with `T''` exact), which is quadratic at the resting disk's
//! double roots too. Schroeder's step alone took ten times the iterations from the guesses
//! whose roots lie beyond `Re lambda = -1` (the 4-mode disk at (0.085, 0.12), N = 192: 1041
//! against 103); Newton's alone converges only linearly at a double root (its two copies
//! then 1e-11 apart, 4e-14 with the polish).
use super::{real_if_round_off, Linearization};
use nalgebra::DMatrix;
use rustfft::num_complex::Complex64;

type C64 = Complex64;

/// Most Schroeder iterations from one guess.
const MAX_ITERATIONS: usize = 100;

/// Iterations in a row that push a guess out to `Re lambda <= -1`, where no root is sought,
/// after which it is given up (its root lies there): 95 % of the K-mode iterations went to
/// such guesses before.
const PUSHED_OUT: usize = 3;

/// Largest step of one iteration (damped: never more than this at once).
const MAX_STEP: f64 = 0.2;

/// Steps below which the iteration is close enough to a root for Schroeder's step.
const POLISH: f64 = 1e-3;

/// Puts the member with `Im > 0` first in each conjugate pair of `sorted` (sorted by
/// decreasing real part): the two are found separately, so their real parts differ in the
/// last digits and the sort alone would order them by round-off.
fn pairs_upper_first(sorted: &mut [C64]) {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-8 * (1.0 + a.abs());
    let mut i = 0;
    while i + 1 < sorted.len() {
        let (a, b) = (sorted[i], sorted[i + 1]);
        if a.im != 0.0 && close(a.re, b.re) && close(a.im, -b.im) {
            if a.im < 0.0 {
                sorted.swap(i, i + 1);
            }
            i += 2;
        } else {
            i += 1;
        }
    }
}

impl Linearization {
    /// The eigenvalues with `Re lambda > -1` (the only ones the field's decay leaves), with
    /// multiplicity, sorted by decreasing real part (a conjugate pair with `Im > 0` first);
    /// one `NaN` when the state or its response is not finite (counted as growing by
    /// [`Self::verdict`]).
    ///
    /// With `f = det T / prod (lambda - r)` over the roots `r` found, `L = f' / f =
    /// tr(T^(-1) T') - Sum 1 / (lambda - r)` and `L' = tr(T^(-1) T'') - tr((T^(-1) T')^2) +
    /// Sum 1 / (lambda - r)^2`, Newton's step is `1 / L` and Schroeder's `-L / L'`.
    /// Complex guesses come in conjugate pairs, so pairs are found as pairs.
    pub fn eigenvalues(&self) -> Vec<C64> {
        let dim = self.dim();
        // The guesses: the eigenvalues of the problem linear in lambda, `T(0) + lambda T'(0)`
        // (both real), `-T'(0)^(-1) T(0)`; `T'(0) = M - R'(0)` holds the field's lag.
        let t0 = self.t_derivatives(C64::default(), 1, false);
        let slope = DMatrix::from_fn(dim, dim, |i, j| t0[1][(i, j)].re);
        let minus_t0 = DMatrix::from_fn(dim, dim, |i, j| -t0[0][(i, j)].re);
        // Where T'(0) is singular, the lambda = 0 problem's `M^(-1) (-T(0))`.
        let k0 = slope
            .lu()
            .solve(&minus_t0)
            .unwrap_or_else(|| DMatrix::from_fn(dim, dim, |i, j| minus_t0[(i, j)] / self.m[i]));
        let Some(guesses) = crate::numerics::eigen::complex_eigenvalues(&k0) else {
            return vec![C64::new(f64::NAN, 0.0)];
        };
        let mut found: Vec<C64> = Vec::new();
        // Each guess once; then once more each guess that found no root (another guess's
        // iteration may have taken the root it was heading for).
        let mut again = Vec::new();
        for guess in &guesses {
            if found.len() == dim {
                break;
            }
            match self.root_from(*guess, &found) {
                Some(root) => found.push(real_if_round_off(root)),
                // A guess beyond -1 from which no root was found: its root lies there.
                None if guess.re <= -1.0 => {}
                None => again.push(*guess),
            }
        }
        for guess in again {
            if found.len() == dim {
                break;
            }
            if let Some(root) = self.root_from(guess, &found) {
                found.push(real_if_round_off(root));
            }
        }
        found.sort_by(|a, b| b.re.total_cmp(&a.re));
        pairs_upper_first(&mut found);
        found
    }

    /// The root of `det T / prod (lambda - r)` (`r` in `found`) the iteration reaches from
    /// `guess`, if it has `Re > -1` and `det T` vanishes there.
    fn root_from(&self, guess: C64, found: &[C64]) -> Option<C64> {
        let mut lambda = C64::new(guess.re.max(-0.99), guess.im);
        let mut pushed_out = 0;
        let mut last_step = f64::INFINITY;
        for _ in 0..MAX_ITERATIONS {
            // Newton on det T far from a root, Schroeder's step close to one.
            let schroeder = last_step < POLISH;
            let t = self.t_derivatives(lambda, if schroeder { 2 } else { 1 }, false);
            let lu = t[0].clone().lu();
            let Some(x1) = lu.solve(&t[1]) else {
                break; // T singular: lambda is a root
            };
            let poles = found.iter().map(|r| (lambda - r).inv());
            let l1 = x1.trace() - poles.clone().sum::<C64>();
            let mut step = if schroeder {
                let Some(x2) = lu.solve(&t[2]) else {
                    break;
                };
                let slope = x2.trace() - (&x1 * &x1).trace() + poles.map(|p| p * p).sum::<C64>();
                -l1 / slope
            } else {
                l1.inv()
            };
            if !step.is_finite() {
                break;
            }
            if step.norm() > MAX_STEP {
                step *= MAX_STEP / step.norm();
            }
            lambda -= step;
            if lambda.re < -0.999 {
                lambda.re = -0.999;
                pushed_out += 1;
                if pushed_out == PUSHED_OUT {
                    return None;
                }
            } else {
                pushed_out = 0;
            }
            last_step = step.norm();
            if last_step < 1e-12 {
                break;
            }
        }
        let det = |l: C64| self.t_matrix(l).lu().determinant().norm();
        (lambda.re > -0.999 && det(lambda) <= 1e-9 * det(lambda + 0.1)).then_some(lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conjugate_pairs_are_ordered_upper_member_first() {
        // A pair whose lower member's real part came out larger by round-off, a real root, a
        // pair already in order, and two complex roots that are not a pair.
        let mut roots = vec![
            C64::new(-0.01 + 1e-15, -0.3),
            C64::new(-0.01, 0.3),
            C64::new(-0.05, 0.0),
            C64::new(-0.2, 0.1),
            C64::new(-0.2, -0.1),
            C64::new(-0.4, -0.5),
            C64::new(-0.4 - 1e-3, 0.5),
        ];
        let expected = [
            C64::new(-0.01, 0.3),
            C64::new(-0.01 + 1e-15, -0.3),
            C64::new(-0.05, 0.0),
            C64::new(-0.2, 0.1),
            C64::new(-0.2, -0.1),
            C64::new(-0.4, -0.5),
            C64::new(-0.4 - 1e-3, 0.5),
        ];
        pairs_upper_first(&mut roots);
        assert_eq!(roots, expected);
    }
}
