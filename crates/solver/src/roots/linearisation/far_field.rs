//! The fast modes' part of the response `S(lambda) = Sum_k c_k b_k^T / (lambda - d_k)` as
//! moments ([`crate::roots::linearisation`]'s notes): where `|d_k| >=` [`FAR`],
//! `1 / (lambda - d_k) = -Sum_p lambda^p / d_k^(p+1)`, so the fast modes give
//! `-Sum_p lambda^p M_p` with `M_p = Sum_far c_k b_k^T / d_k^(p+1)`, made once per state; for
//! `|lambda| <=` [`SERIES_RADIUS`] the first [`TERMS`] of them leave
//! `(SERIES_RADIUS / FAR)^TERMS = 3.5e-15` of each fast mode's term. The slow modes (about
//! 1300 of the 18 624 stored at N = 192) are summed as they are.
//!
//! The response of a real perturbation is `(S(lambda) + conj S(conj lambda)) / 2`, whose fast
//! part is `-Sum_p lambda^p Re M_p`: only the real parts of the moments are formed and kept
//! (half the products), and they enter `S(lambda)` and `S(conj lambda)` alike (their
//! imaginary parts would cancel in the average). At a real `lambda` this is the real part of
//! the complex sum to the last bit.
use rustfft::num_complex::Complex64;
use std::ops::{Mul, MulAssign, SubAssign};

type C64 = Complex64;

/// Smallest `|d_k|` of a mode whose part of the response is taken from the moments.
pub const FAR: f64 = 256.0;

/// Largest `|lambda|` at which the response is summed with the moments (else every mode is
/// summed as it is).
pub const SERIES_RADIUS: f64 = 4.0;

/// Moments kept: `(SERIES_RADIUS / FAR)^TERMS = 3.5e-15`.
pub const TERMS: usize = 8;

/// The moments of the fast modes and the list of the slow ones.
pub(super) struct FarField {
    /// The stored modes with `|d_k| <` the split (summed as they are).
    pub(super) near: Vec<usize>,
    /// `Re M_p[j][i] = Re Sum_far c_ik b_jk / d_k^(p+1)` for `p < TERMS`.
    moments: Vec<Vec<Vec<f64>>>,
}

impl FarField {
    /// The moments of the modes with `|d_k| >= far` (`far = INFINITY`: none; every mode is
    /// then summed as it is), for the columns `b[j]` and the functionals `c[k * dim + i]`.
    pub(super) fn new(d: &[C64], b: &[Vec<C64>], c: &[C64], far: f64) -> Self {
        let dim = b.len();
        let mut moments = vec![vec![vec![0.0; dim]; dim]; TERMS];
        let mut near = Vec::new();
        for (k, d) in d.iter().enumerate() {
            if d.norm() < far {
                near.push(k);
                continue;
            }
            let w = d.inv();
            let ck = &c[k * dim..(k + 1) * dim];
            for (j, b) in b.iter().enumerate() {
                let mut t = b[k] * w;
                for m in moments.iter_mut() {
                    // Re (t c), as the complex product forms it.
                    for (acc, c) in m[j].iter_mut().zip(ck) {
                        *acc += t.re * c.re - t.im * c.im;
                    }
                    t *= w;
                }
            }
        }
        Self { near, moments }
    }

    /// The fast modes' part of column `j` of the response at `l` and of its first `order`
    /// derivatives (`-Sum_p l^p Re M_p`, `-Sum_p p l^(p-1) Re M_p`, ...), added to
    /// `s[0..=order]`: complex at a complex `l`, real at a real `l` (the same real parts).
    pub(super) fn add<T>(&self, j: usize, l: T, order: usize, s: &mut [&mut [T]])
    where
        T: Copy + From<f64> + SubAssign + MulAssign + Mul<f64, Output = T>,
    {
        for (o, s) in s.iter_mut().enumerate().take(order + 1) {
            // d^o/dl^o l^p = p (p-1) .. (p-o+1) l^(p-o).
            let mut power = T::from(1.0);
            for (p, m) in self.moments.iter().enumerate().skip(o) {
                let falling: f64 = (0..o).map(|q| (p - q) as f64).product();
                for (s, &m) in s.iter_mut().zip(&m[j]) {
                    *s -= power * m * falling;
                }
                power *= l;
            }
        }
    }
}
