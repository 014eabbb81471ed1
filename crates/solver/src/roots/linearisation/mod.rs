//! Linear stability of a steady or steadily moving state, field included (docs/model.md,
//! "Steady states as roots"): the eigenvalues with `Re lambda > -1` solve the nonlinear
//! eigenproblem `T(lambda) dz = 0`, `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`, a
//! `2K x 2K` matrix of single sums over the field's Fourier modes. Two implementations of the
//! same construction, chosen once per model by [`crate::roots::balances::Balances`]:
//!
//! - [`general`]: [`Linearization`], the state `(vx, vy, a_2..a_K, b_2..b_K)` of any `K`;
//! - [`two_mode`]: [`TwoModeLinearization`], the fast path of `K = 2` (fixed 4 x 4 arrays, the
//!   forces by Parseval).
//!
//! At `K = 2` they give the same eigenvalues (tested in [`general`]).
pub mod general;
pub mod two_mode;

pub use general::Linearization;
pub use two_mode::TwoModeLinearization;

use rustfft::num_complex::Complex64;

/// Largest `|Im lambda|` of an eigenvalue taken to be real: Newton in the complex plane leaves
/// a real root of `det T` with an imaginary part of round-off (`1e-24` measured at K = 4),
/// and a verdict tells the rotation mode, and a continuation a real crossing from a complex
/// one, by `Im lambda == 0`.
pub const REAL_EIGENVALUE: f64 = 1e-10;

/// `lambda`, its imaginary part set to 0 where it is round-off ([`REAL_EIGENVALUE`]).
pub fn real_if_round_off(lambda: Complex64) -> Complex64 {
    if lambda.im.abs() < REAL_EIGENVALUE {
        Complex64::new(lambda.re, 0.0)
    } else {
        lambda
    }
}
