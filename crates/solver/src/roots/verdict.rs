//! The stability verdict of one state: its eigenvalues (docs/model.md, "Steady states as roots"), the
//! near-neutral rotation mode told apart from the rest by its shape, and the count of unstable
//! eigenvalues that decides stability.
//!
//! Neutral modes. Translation is removed exactly by the co-moving frame (the centre is not an
//! unknown of the `2K x 2K` problem, so its zero eigenvalue never appears). Rotation is not a
//! symmetry of the periodic square box, only nearly one: a moving or deformed state has one
//! eigenvalue near zero whose mode turns the direction of motion and the long axis together,
//! `g = d/dtheta (R v, R2 s) = (-vy, vx, -2 b2, 2 a2)`. Its sign says which orientation the box
//! prefers (axis or diagonal) over thousands of time units, not which class the state has:
//! it is reported as `rotation` and left out of the decision. A mode counts as the rotation
//! when it is real and parallel to `g` (|cos| >= 0.9): it lies in the antisymmetric block of a
//! mirror-symmetric state, whose other mode is orthogonal to `g` in the free plane.
use rustfft::num_complex::Complex64;
use serde::Serialize;

/// Smallest |cos| between a mode and the rotation generator for the mode to be the rotation.
pub const ROTATION_COS: f64 = 0.9;

/// Smallest size of the rotation generator `|g|` for a state to have a rotation mode. Below
/// it the state is the resting disk to within Newton's round-off (a root polished to
/// `|a2| ~ 1e-9` is the disk), whose deformation pair is degenerate up to the box's
/// anisotropy: either of its modes is then parallel to `g` by chance, and before numerics
/// version 4 a growing deformation mode could be left out as the "rotation" (IC labels
/// between the two deformation onsets).
pub const ROTATION_MIN_NORM: f64 = 1e-6;

/// Largest |eigenvalue| of a rotation mode: the box breaks rotation only weakly (images
/// `~ e^(-L)` away), so the mode is near-neutral (-0.0084 at MD (0.085, 0.112), N = 192;
/// -0.028 at N = 128). A faster mode is never left out of a verdict.
pub const ROTATION_MAX: f64 = 0.05;

/// A state's eigenvalues and what they say.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// Eigenvalues with `Re > -1`, decreasing real part (`[re, im]` pairs), rotation included.
    pub eigenvalues: Vec<[f64; 2]>,
    /// The near-neutral rotation mode's eigenvalue, if the state has one.
    pub rotation: Option<f64>,
    /// Eigenvalues with a positive real part, the rotation mode excluded.
    pub unstable: usize,
    /// Largest real part, the rotation mode excluded (`-1` when there is none above the
    /// field's spectrum).
    pub max_re: f64,
}

impl Verdict {
    pub fn stable(&self) -> bool {
        self.unstable == 0
    }

    /// Largest real part of all eigenvalues, the rotation mode included (`-1` when there is
    /// none above the field's spectrum).
    pub fn slowest(&self) -> f64 {
        self.eigenvalues.first().map_or(-1.0, |l| l[0])
    }

    /// Every eigenvalue decays, the rotation mode included: a state the runs stay on, not
    /// only one of a stable class (a state stable but for its rotation mode is left, slowly,
    /// for another orientation).
    pub fn decays(&self) -> bool {
        self.slowest() < 0.0
    }

    /// The non-rotation eigenvalues, decreasing real part.
    pub fn decisive(&self) -> Vec<Complex64> {
        let mut skipped = false;
        self.eigenvalues
            .iter()
            .filter(|[re, im]| {
                let is_rot = !skipped && *im == 0.0 && self.rotation.is_some_and(|r| r == *re);
                if is_rot {
                    skipped = true;
                }
                !is_rot
            })
            .map(|[re, im]| Complex64::new(*re, *im))
            .collect()
    }
}

/// A linearisation a verdict reads: its eigenvalues and the mode of each (the `2K x 2K`
/// problem of [`crate::roots::linearisation::Linearization`], made for any `K`; the verdict
/// reads it through this trait, so that it does not depend on how they are computed).
pub trait Spectrum {
    /// Eigenvalues with `Re > -1`, decreasing real part.
    fn eigenvalues(&self) -> Vec<Complex64>;
    /// The eigenmode of `lambda` over the unknowns `(vx, vy, a_2..a_K, b_2..b_K)`.
    fn eigenmode(&self, lambda: Complex64) -> Vec<Complex64>;
}

/// The rotation generator at `z = (vx, vy, a_2..a_K, b_2..b_K)`: the velocity turns once,
/// shape mode `k` `k` times, `g = (-vy, vx, -k b_k, k a_k)` (for `K = 2`,
/// `(-vy, vx, -2 b2, 2 a2)`).
pub fn rotation_generator(z: &[f64]) -> Vec<f64> {
    let k_max = z.len() / 2;
    let mut g = vec![-z[1], z[0]];
    g.extend((2..=k_max).map(|k| -(k as f64) * z[k_max - 1 + k]));
    g.extend((2..=k_max).map(|k| k as f64 * z[k]));
    g
}

/// Eigenvalues, rotation mode and count of unstable ones at the state `z` of `lin` (any `K`).
pub fn assess(lin: &impl Spectrum, z: &[f64]) -> Verdict {
    let eigenvalues = lin.eigenvalues();
    let g = rotation_generator(z);
    let g_norm = g.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut rotation = None;
    if g_norm > ROTATION_MIN_NORM {
        let mut best = (ROTATION_COS, None);
        for l in eigenvalues
            .iter()
            .filter(|l| l.im == 0.0 && l.re.abs() <= ROTATION_MAX)
        {
            let mode = lin.eigenmode(*l);
            let overlap: Complex64 = mode.iter().zip(&g).map(|(m, gi)| m * gi).sum();
            let norm: f64 = mode.iter().map(|m| m.norm_sqr()).sum::<f64>().sqrt();
            let cos = overlap.norm() / (norm * g_norm);
            if cos >= best.0 {
                best = (cos, Some(l.re));
            }
        }
        rotation = best.1;
    }
    let verdict = Verdict {
        eigenvalues: eigenvalues.iter().map(|l| [l.re, l.im]).collect(),
        rotation,
        unstable: 0,
        max_re: -1.0,
    };
    let decisive = verdict.decisive();
    Verdict {
        unstable: decisive.iter().filter(|l| l.re > 0.0).count(),
        // The largest real part in total order: the list's first but within a conjugate
        // pair, whose upper member comes first whichever real part is larger by round-off.
        max_re: decisive
            .iter()
            .map(|l| l.re)
            .max_by(f64::total_cmp)
            .unwrap_or(-1.0),
        ..verdict
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;
    use crate::roots::linearisation::Linearization;
    use crate::roots::steady_solver::TwoModeSolver;

    #[test]
    fn the_rotation_mode_is_found_and_left_out() {
        // Design notes Sect. 6: MD at (0.085, 0.112) has the rotation-like -0.008436 first; at
        // (0.076, 0.16) the rotation-like +0.000340, which must not make the state unstable.
        let p = ModelParams::at(0.085, 0.112);
        let mut s = TwoModeSolver::new(p, 192).unwrap();
        let st = s.newton(0.59, -0.27, 1e-12).unwrap();
        let z = [st.v, 0.0, st.a2, 0.0];
        let v = assess(&Linearization::of_two_modes(&mut s, z), &z);
        assert!((v.rotation.unwrap() + 0.008436).abs() < 2e-6, "{v:?}");
        assert!((v.max_re + 0.052054).abs() < 2e-6, "{v:?}");
        assert!(v.stable());

        let p = ModelParams::at(0.076, 0.16);
        let mut s = TwoModeSolver::new(p, 192).unwrap();
        let st = s.newton(0.43, -0.03, 1e-12).unwrap();
        let z = [st.v, 0.0, st.a2, 0.0];
        let v = assess(&Linearization::of_two_modes(&mut s, z), &z);
        assert!((v.rotation.unwrap() - 0.000340).abs() < 2e-6, "{v:?}");
        assert!(v.stable() && v.max_re < 0.0, "{v:?}");
        // The resting disk has no rotation mode: its drift pair decides (unstable below the
        // onset of motion, eta_t = 0.07648).
        let z = [0.0; 4];
        let v = assess(&Linearization::of_two_modes(&mut s, z), &z);
        assert!(v.rotation.is_none() && v.unstable == 2, "{v:?}");
        let mut s = TwoModeSolver::new(ModelParams::at(0.085, 0.13), 192).unwrap();
        let v = assess(&Linearization::of_two_modes(&mut s, z), &z);
        assert!(v.rotation.is_none() && v.stable(), "{v:?}");
    }
}
