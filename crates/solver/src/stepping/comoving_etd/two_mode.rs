//! The fast path of `K = 2` of the pseudo-spectral ETD2RK in the droplet's co-moving frame (docs/model.md, "Solving it in the droplet's frame": the lab-frame
//! version with the moving source explicit gave steady v = 0.613 / 0.643 at dt = 0.01 / 0.02
//! against the exact 0.597; in the co-moving frame a steadily moving droplet is an exact fixed
//! point).
//!
//! With `w(xi, t) = u(xi + r_c(t), t)` the concentration equation (paper eq. 34) becomes
//! `w_t = Lap w - w + v . grad w + Theta(a2, b2) / A`, in Fourier space
//! `w_t = -(1 + k^2) w + i k.v w + Theta_hat / A`. The stiff part `-(1 + k^2)` is integrated
//! exactly (ETD2RK, [`crate::stepping::etd`]); advection and the source form the explicit part. The
//! droplet's own linear parts (`-eta_t / m`, `-kappa2 / eta2`) get the same exact treatment.
//! Every ETD-RK step keeps the ODE's fixed points, so a steadily moving droplet is an exact
//! fixed point of the scheme and its steady `v`, `s` do not depend on `dt`.
//!
//! Adaptive steps ([`Scheme::attempt`], [`crate::stepping::step_control`]): the corrector minus the
//! ETD1 predictor of the droplet's integrated scalars is the embedded error estimate. It is
//! known after the first half of the step (the predictor pass gives the forces the scalar
//! corrector needs), so a refused step costs half a step and changes nothing.
//!
//! Cost per step: one shape transform (the new state's, [`crate::model::shape_transform`]: the
//! point-symmetric half of the window, three row-pruned row transforms, one complex and one
//! half-length real column transform; no inverse transform: forces by Parseval,
//! [`crate::model::forces::parseval`]) and two fused passes over the spectrum that advance the field and
//! accumulate the forces ([`super::spectral_pass`]), with no exponential or division per mode.
//! The predictor's shape is extrapolated from the last two states
//! ([`TwoModeEtd::predictor_shape`]) rather than transformed.
//!
//! Profile at N = 192: the two passes about 46 %, transforms 27 %, sampling `Theta` 13 %
//! (half of it `exp` in the tanh band); measured step times and what was tried and not kept
//! are in docs/performance.md, "Speed".
//!
//! One step ([`Scheme::attempt`]) is [`TwoModeEtd::predict`] (the first pass),
//! [`TwoModeEtd::correct_scalars`] and [`TwoModeEtd::step_error`] (where a step may be
//! refused), then [`TwoModeEtd::correct_field`] (the second pass).
use crate::model::dynamics;
use crate::model::forces::parseval::Forces;
use crate::model::grid::Grid;
use crate::model::params::ModelParams;
use crate::model::shape_transform::ShapeTransform;
use crate::model::state::DropletState;
use crate::numerics::fft2::PrunedFft2;
use crate::stepping::etd::SeparableExp;
use crate::stepping::{scale_displacement, Attempt, Field, Scheme, Stepper};
use rustfft::num_complex::Complex64;

/// Packed transforms of one droplet shape (`p`: `Theta + X Theta`, `y`: `Y Theta`), its
/// area and the shape `(a2, b2)` they belong to.
pub(super) struct ShapeSpectra {
    pub(super) p: Vec<Complex64>,
    pub(super) y: Vec<Complex64>,
    pub(super) area: f64,
    pub(super) a2: f64,
    pub(super) b2: f64,
}

impl ShapeSpectra {
    fn new(len: usize) -> Self {
        let z = Complex64::default();
        Self {
            p: vec![z; len],
            y: vec![z; len],
            area: 0.0,
            a2: 0.0,
            b2: 0.0,
        }
    }
}

/// The co-moving spectral integrator of one run.
pub struct TwoModeEtd {
    pub(super) params: ModelParams,
    pub(super) grid: Grid,
    pub(super) fft: PrunedFft2,
    pub(super) shapes: ShapeTransform,
    /// Hold the centre fixed (deformation-only runs, Appendix E).
    pub(super) pinned: bool,
    pub(super) state: DropletState,
    /// Normalised Fourier coefficients of `w`, `[kx][ky]`.
    pub(super) w_hat: Vec<Complex64>,
    pub(super) w_new: Vec<Complex64>,
    pub(super) a_hat: Vec<Complex64>,
    /// Explicit part of the field at the step's start.
    pub(super) n0: Vec<Complex64>,
    /// Shape spectra at the current state, at the state before it (valid when
    /// `prev_valid`), and at the candidate new state (or the predictor, see
    /// [`TwoModeEtd::predictor_shape`]).
    pub(super) cur: ShapeSpectra,
    pub(super) prev: ShapeSpectra,
    pub(super) prev_valid: bool,
    pub(super) next: ShapeSpectra,
    /// `Theta_hat` (raw, real) at the predictor.
    pub(super) pred_th: Vec<f64>,
    /// Forces at the current state, if known.
    pub(super) forces0: Option<Forces>,
    pub(super) exp: SeparableExp,
    /// `1 / c` with `c = -(1 + k^2)` per mode.
    pub(super) inv_c: Vec<f64>,
}

impl TwoModeEtd {
    /// A run from `state` with `u = 0`, on an `n x n` grid.
    pub fn new(
        params: ModelParams,
        n: usize,
        state: DropletState,
        pinned: bool,
    ) -> Result<Self, crate::error::SolverError> {
        params.validate()?;
        let grid = Grid::new(n, params.box_len)?;
        let len = grid.spectral_len();
        let shape = params.shape();
        let mut state = state;
        if pinned {
            state.vx = 0.0;
            state.vy = 0.0;
        }
        let zero = Complex64::default();
        Ok(Self {
            params,
            fft: PrunedFft2::new(n),
            shapes: ShapeTransform::new(&grid, shape),
            pinned,
            state,
            w_hat: vec![zero; len],
            w_new: vec![zero; len],
            a_hat: vec![zero; len],
            n0: vec![zero; len],
            cur: ShapeSpectra::new(len),
            prev: ShapeSpectra::new(len),
            prev_valid: false,
            next: ShapeSpectra::new(len),
            pred_th: vec![0.0; len],
            forces0: None,
            exp: SeparableExp::default(),
            inv_c: grid.inverse_rates(),
            grid,
        })
    }

    /// The grid of the co-moving frame.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Replaces the co-moving field (normalised coefficients, `[kx][ky]`).
    pub fn set_spectrum(&mut self, w_hat: &[Complex64]) {
        self.w_hat.copy_from_slice(w_hat);
        self.forces0 = None;
    }

    /// The co-moving field (normalised coefficients, `[kx][ky]`).
    pub fn spectrum(&self) -> &[Complex64] {
        &self.w_hat
    }

    /// Forces and area at the current state.
    pub fn forces(&mut self) -> Forces {
        self.ensure_current()
    }

    /// Samples the shape `(a2, b2)` and transforms it into `out`.
    pub(super) fn shape_spectra(
        shapes: &mut ShapeTransform,
        a2: f64,
        b2: f64,
        out: &mut ShapeSpectra,
    ) {
        out.area = shapes.transform(a2, b2, &mut out.p, &mut out.y);
        (out.a2, out.b2) = (a2, b2);
    }

    /// Shape spectra and forces at the current state (computed once per state).
    pub(super) fn ensure_current(&mut self) -> Forces {
        if let Some(f) = self.forces0 {
            return f;
        }
        self.prev_valid = false;
        let st = self.state;
        Self::shape_spectra(&mut self.shapes, st.a2, st.b2, &mut self.cur);
        let f = crate::model::forces::parseval::spectral_forces(
            &self.grid,
            &self.w_hat,
            &self.cur.p,
            &self.cur.y,
            self.cur.area,
        );
        self.set_overdamped_velocity(&f);
        self.forces0 = Some(f);
        f
    }

    /// The predictor's shape spectra for the shape `(a2, b2)`: `Some(alpha)` when they are the
    /// extrapolation `cur + alpha (cur - prev)` along the last accepted step, else `None`
    /// after transforming them into `next` (which the new state overwrites later).
    ///
    /// `alpha` projects the predictor's shape change onto the last step's; the part across it
    /// is `O(h^2)`, as is the curvature of the path, so the predictor's shape is off by
    /// `O(h^2)`. It enters the step only through the corrector's `h phi2 (N(a) - N(y_n))`, so
    /// the local error stays `O(h^3)` and the scheme second order; at a fixed point the shape
    /// does not change and the extrapolation is exact. Extrapolating further than
    /// `MAX_ALPHA` steps, or with no previous state, transforms the shape instead.
    pub(super) fn predictor_shape(&mut self, a2: f64, b2: f64) -> Option<f64> {
        const MAX_ALPHA: f64 = 2.0;
        if self.prev_valid {
            let (c, q) = (&self.cur, &self.prev);
            let back = (c.a2 - q.a2, c.b2 - q.b2);
            let ahead = (a2 - c.a2, b2 - c.b2);
            let norm2 = back.0 * back.0 + back.1 * back.1;
            let alpha = if norm2 > 0.0 {
                (ahead.0 * back.0 + ahead.1 * back.1) / norm2
            } else {
                0.0
            };
            if alpha.abs() <= MAX_ALPHA {
                return Some(alpha);
            }
        }
        Self::shape_spectra(&mut self.shapes, a2, b2, &mut self.next);
        None
    }

    /// In the overdamped limit (`m = 0`) the velocity is `F / eta_t` at every state.
    pub(super) fn set_overdamped_velocity(&mut self, f: &Forces) {
        if self.params.mass == 0.0 && !self.pinned {
            (self.state.vx, self.state.vy) = dynamics::overdamped_velocity(&self.params, f);
        }
    }

    /// Velocity used for advection at a stage with forces `f` and integrated velocity `v`.
    pub(super) fn stage_velocity(&self, f: &Forces, v: (f64, f64)) -> (f64, f64) {
        if self.pinned {
            (0.0, 0.0)
        } else if self.params.mass == 0.0 {
            dynamics::overdamped_velocity(&self.params, f)
        } else {
            v
        }
    }

    /// Explicit rates of `(vx, vy, a2, b2)` beyond their linear terms.
    pub(super) fn scalar_rates(&self, f: &Forces) -> [f64; 4] {
        dynamics::forcing(&self.params, f, self.pinned)
    }
}

impl Stepper for TwoModeEtd {
    fn attempt(&mut self, h: f64, max_error: f64) -> Attempt {
        let half = self.predict(h);
        let (next, corrector_velocity) = self.correct_scalars(&half);
        // The step can be refused here, before the second half of its cost.
        let error = self.step_error(&half, &next);
        if max_error.is_finite() && (error.is_nan() || error > max_error) {
            return Attempt {
                accepted: false,
                error: Some(error),
            };
        }
        self.correct_field(&half, next, corrector_velocity);
        Attempt {
            accepted: true,
            error: Some(error),
        }
    }
}

impl Scheme for TwoModeEtd {
    fn state(&self) -> DropletState {
        self.state
    }

    fn leap(
        &mut self,
        root: &[f64],
        root_field: &[Complex64],
        factor: f64,
        shift: [f64; 2],
    ) -> bool {
        if root.len() != 4
            || root_field.len() != self.w_hat.len()
            || self.pinned
            || self.params.mass == 0.0
        {
            return false;
        }
        scale_displacement(&mut self.w_hat, root_field, factor);
        let st = &mut self.state;
        scale_displacement(
            [&mut st.vx, &mut st.vy, &mut st.a2, &mut st.b2],
            root,
            factor,
        );
        st.x += shift[0];
        st.y += shift[1];
        // The shape changed: its spectra and forces are recomputed, and the predictor's
        // extrapolation starts afresh.
        self.forces0 = None;
        self.prev_valid = false;
        true
    }

    fn spectrum(&self) -> Option<&[Complex64]> {
        Some(&self.w_hat)
    }

    fn mass(&self) -> f64 {
        self.params.box_len * self.params.box_len * self.w_hat[0].re
    }

    fn field(&mut self) -> Field {
        // Lab frame: u(x) = w(x - r_c), an exact phase shift e^{-i k . r_c}.
        let n = self.grid.n;
        let mut spec = self.w_hat.clone();
        self.grid
            .shift_spectrum(&mut spec, self.state.x, self.state.y);
        let mut values = vec![0.0; n * n];
        self.fft.inverse(&mut spec, &mut values, 0, n - 1);
        Field {
            n,
            len: self.params.box_len,
            values,
        }
    }
}
