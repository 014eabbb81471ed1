//! Eigenvalues of a small dense real matrix, guarded: a matrix with a non-finite entry is
//! refused before the Schur iteration sees it (nalgebra's unbounded iteration never ends on
//! NaN), and the iteration is bounded.
use nalgebra::{Complex, DMatrix};

/// Most sweeps of the Schur iteration (a 12 x 12 matrix converges in tens).
const MAX_SWEEPS: usize = 10_000;

/// The eigenvalues of `m`, or `None` when an entry is not finite or the Schur iteration does
/// not converge within [`MAX_SWEEPS`].
pub fn complex_eigenvalues(m: &DMatrix<f64>) -> Option<Vec<Complex<f64>>> {
    if !m.iter().all(|x| x.is_finite()) {
        return None;
    }
    let schur = m.clone().try_schur(f64::EPSILON, MAX_SWEEPS)?;
    Some(schur.complex_eigenvalues().iter().copied().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotation_has_the_pair_plus_minus_i_and_nan_is_refused() {
        let m = DMatrix::from_row_slice(2, 2, &[0.0, -1.0, 1.0, 0.0]);
        let mut e = complex_eigenvalues(&m).unwrap();
        e.sort_by(|a, b| a.im.total_cmp(&b.im));
        assert!((e[0] - Complex::new(0.0, -1.0)).norm() < 1e-12, "{e:?}");
        assert!((e[1] - Complex::new(0.0, 1.0)).norm() < 1e-12, "{e:?}");
        for bad in [f64::NAN, f64::INFINITY] {
            let m = DMatrix::from_row_slice(2, 2, &[1.0, bad, 0.0, 2.0]);
            assert_eq!(complex_eigenvalues(&m), None);
        }
    }
}
