//! Time stepping of the model with shape modes `2..K` (the paper's general equations) in the
//! droplet's frame: ETD2RK ([`crate::stepping::comoving_etd`]) for the general shape, with
//! its embedded error estimate, so that the one clock ([`crate::runs::clock`]) takes fixed or
//! adaptive steps with it ([`Stepper`]).
//!
//! With `w` the co-moving field and `z = (vx, vy, a_2..a_K, b_2..b_K)`:
//! `w_t = c w + N(w, z)`, `c = -(1 + k^2)`, `N = i k.v w + s_hat(z)` (`s = Theta / A`), and
//! `z_j,t = -r_j z_j + f_j(w, z) / m_j` with the forces `f = (F, G_k^(a), G_k^(b))`, the
//! decay rates `r = (eta_t / m, kappa_k / eta_k)` and the inertia `m_j = (m, eta_k)`. One step
//! of `h`: the ETD1 predictor `a = e w + h phi1 N(w, z)`, `z_a` likewise with the forces at
//! the step's start; the forces and `Theta` at `(a, z_a)`; the corrector
//! `w' = a + h phi2 (N(a, z_a) - N(w, z))`, `z'` likewise. The corrector minus the predictor
//! of `z` is the error estimate; a step refused there leaves the run unchanged. Every ETD-RK
//! step keeps the ODE's fixed points, so the fixed points of the scheme are exactly the
//! steady states of [`crate::roots::steady_solver::SteadySolver`] (the field's is `s_hat / (1 + k^2 - i k.v)`), whatever
//! the step.
//!
//! The predictor's droplet (`Theta` and its transform) and the field's gradient on it are
//! extrapolated from the last two accepted states ([`super::predictor`]): the scheme stays
//! second order and its fixed points are unchanged. The 2-mode fast path extrapolates its
//! droplet by the same rule and sums its predictor's own field (which costs it no transform),
//! so at `K = 2` the two part by `O(h^2)` (numerics `modes-16`; the general step's error half
//! the fast path's, tested).
//!
//! Cost per step: `Theta` sampled and transformed once and the field's gradient transformed
//! back once, both at the new state (three row-pruned transforms; the gradient's two share
//! one pass over the spectrum, [`PrunedFft2::inverse_gradient`]), and one pass over the
//! field's spectrum for both of its stages (the forces at the predictor need not its field;
//! two passes when they do, after a start); the 2-mode scheme saves the inverse transforms by
//! the droplet's point symmetry and the forces' Parseval sums, which the odd modes break.
use super::predictor::History;
use crate::error::SolverError;
use crate::model::forces::quadrature::{ForceQuadrature, PassBuffers};
use crate::model::grid::Grid;
use crate::model::modes::Modes;
use crate::model::params::ModelParams;
use crate::model::state::{largest_magnitude, DropletState};
use crate::numerics::fft2::PrunedFft2;
use crate::stepping::etd::{EtdCoef, SeparableExp};
use crate::stepping::{scale_displacement, Attempt, Field, Scheme, Stepper};
use rustfft::num_complex::Complex64;

/// The forces at the run's present state (kept while a refused step leaves it unchanged).
struct AtStart {
    forces: Vec<f64>,
    area: f64,
}

/// The predictor's source `Theta_hat` as `base + alpha (base - back)` of two transforms, with
/// `alpha = 0` (and `back = base`) for a transform of its own.
#[derive(Clone, Copy)]
struct Source<'a> {
    base: &'a [Complex64],
    back: &'a [Complex64],
    alpha: f64,
}

impl<'a> Source<'a> {
    /// A transform of its own.
    fn own(spec: &'a [Complex64]) -> Self {
        Self {
            base: spec,
            back: spec,
            alpha: 0.0,
        }
    }
}

/// The field's spectra of one run and what a pass over them needs.
struct Spectra {
    /// The field's normalised spectrum and the predictor's.
    u: Vec<Complex64>,
    a_hat: Vec<Complex64>,
    /// `e^(c h) - 1` factored by wavenumber, and `1 / c` per mode.
    exp: SeparableExp,
    inv_c: Vec<f64>,
}

/// The `K`-mode model's state in time, stepped by ETD2RK ([`Stepper::attempt`]). Plans and
/// buffers are made once; a step allocates only the forces' vectors.
pub struct ComovingEtd {
    /// The model (its friction law sets the modes' rates; the state's length, `K`).
    params: ModelParams,
    quad: ForceQuadrature,
    /// `(vx, vy, a_2..a_K, b_2..b_K)`.
    pub z: Vec<f64>,
    field: Spectra,
    /// Per unknown: the linear decay rate `r_j` and the inertia `m_j`.
    rate_of: Vec<f64>,
    inertia: Vec<f64>,
    start: Option<AtStart>,
    /// The last two accepted states' droplets and gradients, for the predictor's
    /// ([`super::predictor`]).
    history: History,
    /// The last accepted step (between the state `start` is taken at and the one before).
    h_accepted: f64,
    /// Time stepped (the run's clock keeps the run's own).
    pub t: f64,
    /// The centre.
    pub x: f64,
    pub y: f64,
}

impl ComovingEtd {
    /// The `K`-mode model (`K = z0.len() / 2`) at `z0` with the field 0.
    pub fn new(params: &ModelParams, n: usize, z0: &[f64]) -> Result<Self, SolverError> {
        params.validate()?;
        crate::stepping::require_inertia(params)?;
        let grid = Grid::new(n, params.box_len)?;
        let len = grid.spectral_len();
        let inv_c = grid.inverse_rates();
        let shape = params.shape();
        let zero = Complex64::default();
        let history = History::new(&grid);
        let mut run = Self {
            params: *params,
            quad: ForceQuadrature::new(grid, shape),
            z: z0.to_vec(),
            field: Spectra {
                u: vec![zero; len],
                a_hat: vec![zero; len],
                exp: SeparableExp::default(),
                inv_c,
            },
            rate_of: Vec::new(),
            inertia: Vec::new(),
            start: None,
            history,
            h_accepted: 0.0,
            t: 0.0,
            x: 0.0,
            y: 0.0,
        };
        run.linear_parts();
        Ok(run)
    }

    /// The decay rates and the inertia of `(vx, vy, a_2..a_K, b_2..b_K)`.
    fn linear_parts(&mut self) {
        let k_max = self.z.len() / 2;
        let p = self.params;
        self.rate_of = vec![p.eta_t / p.mass; 2];
        self.inertia = vec![p.mass; 2];
        for k in (2..=k_max).chain(2..=k_max) {
            let eta = crate::model::friction::eta_k(p.eta2, k, p.eta_k_exponent);
            self.rate_of
                .push(crate::model::modes::kappa_k(p.kappa2, k) / eta);
            self.inertia.push(eta);
        }
    }

    /// The forces of the field whose gradient the quadrature holds on the droplet it holds
    /// (rows `lo..=hi`), `(Fx, Fy, G^(a)_2.., G^(b)_2..)`.
    fn forces(&mut self, lo: usize, hi: usize, area: f64) -> Vec<f64> {
        let k_max = self.z.len() / 2;
        self.quad.sums(k_max, lo, hi, area).to_vec()
    }

    /// The forces at the present state; the first call after a step samples and transforms
    /// its droplet, and records it with its field's gradient in the history.
    fn ensure_start(&mut self) {
        if self.start.is_some() {
            return;
        }
        let (area, lo, hi) = self.quad.theta_spectrum(&Modes::of_state(&self.z));
        self.quad.gradient(&self.field.u, lo, hi);
        let forces = self.forces(lo, hi, area);
        self.history
            .record(&mut self.quad, &self.z[2..], self.h_accepted);
        self.start = Some(AtStart { forces, area });
    }

    /// The rates `dz/dt = f / m - r z` at the present state.
    pub fn rates(&mut self) -> Vec<f64> {
        self.ensure_start();
        let f = &self.start.as_ref().expect("forces at the start").forces;
        f.iter()
            .zip(&self.z)
            .zip(self.rate_of.iter().zip(&self.inertia))
            .map(|((f, z), (r, m))| f / m - r * z)
            .collect()
    }
}

/// One droplet's part of a pass over the field's spectrum: its raw `Theta_hat` `source`, the
/// factor to the normalised source ([`ForceQuadrature::source_scale`]) and its velocity.
type Droplet<'a> = (Source<'a>, f64, (f64, f64));

/// `N(w, z) = i k.v w + s` of one mode `u` (`kv = k.v`; `s` the normalised source) and the
/// ETD1 predictor `a = e w + h phi1 N` with the mode's coefficients `cf`: `(N, a)`.
#[inline(always)]
fn predicted(u: Complex64, cf: &EtdCoef, kv: f64, s: Complex64) -> (Complex64, Complex64) {
    let n = Complex64::new(-kv * u.im + s.re, kv * u.re + s.im);
    (n, u * cf.e + n * cf.p1)
}

impl Spectra {
    /// The ETD1 predictor `a = e w + h phi1 N(w, z)` of a step of `h` into `a_hat`, the droplet
    /// at the step's start `start`: for a step whose forces at the predictor need the
    /// predictor's field ([`Self::advance`] then makes the step).
    fn predict(&mut self, grid: &Grid, h: f64, start: Droplet) {
        let (Source { base, back, alpha }, scale, (vx, vy)) = start;
        self.exp.update(h, &grid.kx, &grid.ky);
        let (n, inv_h) = (grid.n, 1.0 / h);
        for (jx, (kxd, ax)) in grid.kx_d.iter().zip(&self.exp.ax).enumerate() {
            let row = jx * n..(jx + 1) * n;
            let modes = grid
                .ky_d
                .iter()
                .zip(&self.exp.ay)
                .zip(&self.inv_c[row.clone()]);
            let sources = base[row.clone()].iter().zip(&back[row.clone()]);
            let fields = self.u[row.clone()].iter().zip(&mut self.a_hat[row]);
            for (((u, a), (sb, sq)), ((kyd, ay), ic)) in fields.zip(sources).zip(modes) {
                let cf = SeparableExp::coef(*ax, *ay, *ic, h, inv_h);
                let s = (*sb + (*sb - *sq) * alpha) * scale;
                (_, *a) = predicted(*u, &cf, kxd * vx + kyd * vy, s);
            }
        }
    }

    /// A step of `h` of the field in one pass over its spectrum: per mode the predictor `a`
    /// and `N(w, z)` of the droplet at the start `start` (held, not stored: the same numbers
    /// as [`Self::predict`]), then the corrector `w = a + h phi2 (N(a, z_a) - N(w, z))` with the
    /// predictor's droplet `predictor`.
    fn advance(&mut self, grid: &Grid, h: f64, start: Droplet, predictor: Droplet) {
        let (start, scale0, (v0x, v0y)) = start;
        let (Source { base, back, alpha }, scale, (vx, vy)) = predictor;
        self.exp.update(h, &grid.kx, &grid.ky);
        let (n, inv_h) = (grid.n, 1.0 / h);
        for (jx, (kxd, ax)) in grid.kx_d.iter().zip(&self.exp.ax).enumerate() {
            let row = jx * n..(jx + 1) * n;
            let modes = grid
                .ky_d
                .iter()
                .zip(&self.exp.ay)
                .zip(&self.inv_c[row.clone()]);
            let starts = start.base[row.clone()].iter().zip(&start.back[row.clone()]);
            let sources = base[row.clone()].iter().zip(&back[row.clone()]);
            for (((u, (s0b, s0q)), (sb, sq)), ((kyd, ay), ic)) in
                self.u[row].iter_mut().zip(starts).zip(sources).zip(modes)
            {
                let cf = SeparableExp::coef(*ax, *ay, *ic, h, inv_h);
                let s0 = (*s0b + (*s0b - *s0q) * start.alpha) * scale0;
                let (n0, a) = predicted(*u, &cf, kxd * v0x + kyd * v0y, s0);
                let s = (*sb + (*sb - *sq) * alpha) * scale;
                let (na, _) = predicted(a, &cf, kxd * vx + kyd * vy, s);
                *u = a + (na - n0) * cf.p2;
            }
        }
    }
}

impl Scheme for ComovingEtd {
    fn state(&self) -> DropletState {
        DropletState::of_unknowns(&self.z, self.x, self.y).0
    }

    fn unknowns(&self) -> Vec<f64> {
        self.z.clone()
    }

    fn rates(&mut self) -> Option<Vec<f64>> {
        Some(ComovingEtd::rates(self))
    }

    fn spectrum(&self) -> Option<&[Complex64]> {
        Some(&self.field.u)
    }

    fn mass(&self) -> f64 {
        let len = self.params.box_len;
        len * len * self.field.u[0].re
    }

    fn leap(
        &mut self,
        root: &[f64],
        root_field: &[Complex64],
        factor: f64,
        shift: [f64; 2],
    ) -> bool {
        if root.len() != self.z.len() || root_field.len() != self.field.u.len() {
            return false;
        }
        scale_displacement(&mut self.field.u, root_field, factor);
        scale_displacement(&mut self.z, root, factor);
        self.x += shift[0];
        self.y += shift[1];
        // The shape changed: its droplet and forces are sampled afresh, and the predictor's
        // extrapolation starts again.
        self.start = None;
        self.history.forget();
        true
    }

    fn field(&mut self) -> Field {
        // Lab frame: u(x) = w(x - r_c), an exact phase shift e^{-i k . r_c}.
        let grid = self.quad.grid();
        let n = grid.n;
        let mut spec = self.field.u.clone();
        grid.shift_spectrum(&mut spec, self.x, self.y);
        let mut values = vec![0.0; n * n];
        PrunedFft2::new(n).inverse(&mut spec, &mut values, 0, n - 1);
        Field {
            n,
            len: self.params.box_len,
            values,
        }
    }
}

impl Stepper for ComovingEtd {
    fn attempt(&mut self, h: f64, max_error: f64) -> Attempt {
        self.ensure_start();
        // The mechanics' predictor and its droplet; the start's forces, put back if the
        // step is refused.
        let coefs: Vec<EtdCoef> = self.rate_of.iter().map(|r| EtdCoef::new(-r, h)).collect();
        let start = self.start.take().expect("forces at the start");
        let f0 = &start.forces;
        let z_a: Vec<f64> = (0..self.z.len())
            .map(|j| coefs[j].predict(self.z[j], f0[j] / self.inertia[j]))
            .collect();
        let (alpha, area_a, lo, hi) = self.history.shape(&mut self.quad, &z_a);
        let beta = self.history.gradient_factor(h, (lo, hi));
        let start_scale = self.quad.source_scale(start.area);
        let velocity = (self.z[0], self.z[1]);
        // The gradient at the predictor: extrapolated (the field's step is then one pass over
        // its spectrum, once the step is accepted), or the predictor's own field's,
        // transformed back after a pass of its own.
        match beta {
            Some(beta) => self
                .history
                .extrapolate_gradient(&mut self.quad, beta, (lo, hi)),
            None => {
                let start_source = Source::own(self.history.start_spectrum());
                let start = (start_source, start_scale, velocity);
                self.field.predict(self.quad.grid(), h, start);
                self.quad.gradient(&self.field.a_hat, lo, hi);
            }
        }
        let f_a = self.forces(lo, hi, area_a);
        let next: Vec<f64> = (0..self.z.len())
            .map(|j| {
                let m = self.inertia[j];
                coefs[j].correct(z_a[j], f0[j] / m, f_a[j] / m)
            })
            .collect();
        // The largest |corrector - predictor|, NaN if any is.
        let error = largest_magnitude(next.iter().zip(&z_a).map(|(c, p)| c - p));
        if max_error.is_finite() && (error.is_nan() || error > max_error) {
            self.start = Some(start);
            return Attempt {
                accepted: false,
                error: Some(error),
            };
        }
        let (v0, v_a) = (velocity, (z_a[0], z_a[1]));
        // The field's corrector with the predictor's source.
        let scale = self.quad.source_scale(area_a);
        let (base, back) = self.history.spectra();
        let PassBuffers { grid, source } = self.quad.pass_buffers();
        let source = match alpha {
            Some(alpha) => Source { base, back, alpha },
            None => Source::own(source),
        };
        let start = (Source::own(base), start_scale, v0);
        self.field.advance(grid, h, start, (source, scale, v_a));
        self.h_accepted = h;
        // The centre by the trapezoidal rule (ETD2RK with rate 0).
        self.x += 0.5 * h * (v0.0 + v_a.0);
        self.y += 0.5 * h * (v0.1 + v_a.1);
        self.z = next;
        self.t += h;
        Attempt {
            accepted: true,
            error: Some(error),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::initial::InitialCondition;
    use crate::roots::named_state::md_state;
    use crate::stepping::{comoving_etd::TwoModeEtd, Scheme, Stepper};

    /// `(vx, vy, a_2..a_K, b_2..b_K)` after `steps` fixed steps of `h` from IC i with modes
    /// `3..K` at 0, and the centre.
    fn stepped(p: &ModelParams, n: usize, k: usize, h: f64, steps: usize) -> (Vec<f64>, f64) {
        let z0 = InitialCondition::parse("i").unwrap().unknowns(k);
        let mut run = ComovingEtd::new(p, n, &z0).unwrap();
        for _ in 0..steps {
            run.step(h);
        }
        (run.z, run.x)
    }

    /// `(vx, vy, a2, b2, x)` after `steps` steps of `h` from IC i at `K = 2`: the general step
    /// and the 2-mode fast path.
    fn both_at_two_modes(p: &ModelParams, h: f64, steps: usize) -> ([f64; 5], [f64; 5]) {
        let (z, x) = stepped(p, 64, 2, h, steps);
        let st0 = InitialCondition::parse("i").unwrap().state();
        let mut fast = TwoModeEtd::new(*p, 64, st0, false).unwrap();
        for _ in 0..steps {
            fast.step(h);
        }
        let st = fast.state();
        (
            [z[0], z[1], z[2], z[3], x],
            [st.vx, st.vy, st.a2, st.b2, st.x],
        )
    }

    #[test]
    fn with_two_modes_it_converges_with_the_two_mode_scheme() {
        // The general step at K = 2 and the 2-mode fast path (point symmetry, Parseval forces)
        // from IC i to t = 2 at N = 64: the same discretisation and the same ETD2RK but for
        // the predictor's field gradient, which the general step extrapolates from the last
        // two states ([`super::super::predictor`]) where the fast path sums its predictor's own
        // field; both second order, so they part by O(h^2): a quarter as the step halves.
        let p = ModelParams::at(0.085, 0.112);
        let gap = |h: f64| {
            let (general, fast) = both_at_two_modes(&p, h, (2.0 / h).round() as usize);
            assert!(fast[0] > 0.4, "{fast:?}");
            general
                .iter()
                .zip(&fast)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        };
        // Measured 5.1e-4, 1.3e-4, 4.2e-5 (the general step's error from h = 0.001 half the
        // fast path's at each step).
        let (g1, g2, g3) = (gap(0.04), gap(0.02), gap(0.01));
        for ratio in [g1 / g2, g2 / g3] {
            assert!(ratio > 3.0 && ratio < 5.0, "{g1:e} {g2:e} {g3:e}");
        }
    }

    #[test]
    fn a_steady_state_is_a_fixed_point_whatever_the_step() {
        // The 3-mode MD root and its steady field at N = 96: steps of any length from it (the
        // predictor's droplet and gradient extrapolated from the second on) leave it there.
        let p = ModelParams::at(0.085, 0.112).with_modes(3);
        let n = 96;
        let mut solver = crate::roots::steady_solver::SteadySolver::new(p, n).unwrap();
        let st = md_state(&mut solver, 3).unwrap();
        let root = vec![st.v, 0.0, st.a[0], st.a[1], 0.0, 0.0];
        solver.forces(root[0], root[1], &Modes::of_state(&root));
        let field = solver.field_spectrum().to_vec();
        for h in [0.02, 0.1, 0.3] {
            let mut run = ComovingEtd::new(&p, n, &root).unwrap();
            // A leap by the factor 0 puts the run on the root, field and all.
            assert!(run.leap(&root, &field, 0.0, [0.0; 2]));
            for _ in 0..20 {
                run.step(h);
            }
            let drift = run
                .z
                .iter()
                .zip(&root)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(drift < 1e-10, "h = {h}: {drift:e}");
        }
    }

    #[test]
    fn the_field_step_is_etd2rk_written_out_mode_by_mode() {
        // A field and two sources with every coefficient set, N = 32: the one pass of a step
        // and the predictor's pass against ETD2RK written out per mode.
        let grid = Grid::new(32, 7.0).unwrap();
        let len = grid.spectral_len();
        let field = |c: f64| -> Vec<Complex64> {
            (0..len)
                .map(|i| Complex64::new((i as f64 * c).sin(), (i as f64 * 0.3).cos()))
                .collect()
        };
        let (u, cur, prev) = (field(0.11), field(0.37), field(0.53));
        let mut spectra = Spectra {
            u: u.clone(),
            a_hat: vec![Complex64::default(); len],
            exp: SeparableExp::default(),
            inv_c: grid.inverse_rates(),
        };
        let (h, alpha, (scale0, scale)) = (0.07, 0.8, (0.6, 0.5));
        let (v0, va) = ((0.31, -0.02), (0.29, -0.015));
        let predictor = Source {
            base: &cur,
            back: &prev,
            alpha,
        };
        spectra.predict(&grid, h, (Source::own(&cur), scale0, v0));
        let a_hat = spectra.a_hat.clone();
        spectra.advance(
            &grid,
            h,
            (Source::own(&cur), scale0, v0),
            (predictor, scale, va),
        );
        let n = grid.n;
        let mut exp = SeparableExp::default();
        exp.update(h, &grid.kx, &grid.ky);
        let inv_c = grid.inverse_rates();
        for jx in 0..=n / 2 {
            for jy in 0..n {
                let i = jx * n + jy;
                let cf = SeparableExp::coef(exp.ax[jx], exp.ay[jy], inv_c[i], h, 1.0 / h);
                let k = (grid.kx_d[jx], grid.ky_d[jy]);
                // N = i k.v w + s.
                let big_n = |w: Complex64, v: (f64, f64), s: Complex64| {
                    Complex64::new(0.0, k.0 * v.0 + k.1 * v.1) * w + s
                };
                let s0 = cur[i] * scale0;
                let sa = (cur[i] + (cur[i] - prev[i]) * alpha) * scale;
                let n0 = big_n(u[i], v0, s0);
                let a = u[i] * cf.e + n0 * cf.p1;
                let next = a + (big_n(a, va, sa) - n0) * cf.p2;
                assert!((a_hat[i] - a).norm() <= 1e-15 * a.norm().max(1.0), "{i}");
                assert!(
                    (spectra.u[i] - next).norm() <= 1e-15 * next.norm().max(1.0),
                    "{i}"
                );
            }
        }
        assert!(spectra.u.iter().zip(&u).any(|(a, b)| (a - b).norm() > 1e-3));
    }

    #[test]
    fn its_steps_are_second_order_in_time() {
        // Modes 2..3 from IC i to t = 2 at N = 64 with steps 0.01, 0.005, 0.0025 against
        // 0.000625: the error quarters as the step halves (measured ratios 3.4 and 3.8; at
        // larger steps the field's start from 0 is not yet resolved: 2.9 from 0.04 to 0.02).
        let p = ModelParams::at(0.085, 0.112);
        let reference = stepped(&p, 64, 3, 0.000625, 3200).0;
        let error = |h: f64| {
            let z = stepped(&p, 64, 3, h, (2.0 / h).round() as usize).0;
            z.iter()
                .zip(&reference)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        };
        let (e1, e2, e3) = (error(0.01), error(0.005), error(0.0025));
        for ratio in [e1 / e2, e2 / e3] {
            assert!(ratio > 3.2 && ratio < 4.5, "{e1:e} {e2:e} {e3:e}");
        }
    }

    #[test]
    fn a_refused_step_changes_nothing() {
        let p = ModelParams::at(0.085, 0.112);
        let z0 = InitialCondition::parse("i").unwrap().unknowns(3);
        let mut run = ComovingEtd::new(&p, 64, &z0).unwrap();
        run.step(0.02);
        let (z, x, t) = (run.z.clone(), run.x, run.t);
        let a = run.attempt(0.5, 1e-12);
        assert!(!a.accepted && a.error.unwrap() > 1e-12);
        assert_eq!((run.z.clone(), run.x, run.t), (z.clone(), x, t));
        // The step after the refusal is the step that would have been taken.
        let mut twin = ComovingEtd::new(&p, 64, &z0).unwrap();
        twin.step(0.02);
        run.step(0.02);
        twin.step(0.02);
        assert_eq!(run.z, twin.z);
    }

    #[test]
    fn a_run_settles_on_the_state_newton_finds_with_its_mode_3() {
        // Fig. 1c with modes 2..3 from a droplet pushed along x, by pure time stepping (the
        // paper's test, every rate below 1e-9, fixed steps): the run ends steady on the MD
        // state of the steady solver, a3 included, to 1e-6. (N = 96: there the box's rotation
        // mode of the x-axis state decays, at rate 0.037; at N = 64 the run turns away from
        // the axis.)
        let p = ModelParams::at(0.085, 0.112).with_modes(3);
        let n = 96;
        let settings = crate::contract::settings::SolverSettings {
            n,
            dt: 0.05,
            tol: 0.0,
            t_max: 3000.0,
            steady: crate::contract::ending::SteadyMethod::Test,
            steady_tol: 1e-9,
            ..Default::default()
        };
        let ic = InitialCondition::parse("custom:0.5,0,-0.1,0,0,0").unwrap();
        let run = crate::runs::driver::simulate(&p, &ic, &settings).unwrap();
        assert_eq!(
            run.status,
            crate::contract::outcome::RunStatus::Steady,
            "{run:?}"
        );
        let mut solver = crate::roots::steady_solver::SteadySolver::new(p, n).unwrap();
        let st = md_state(&mut solver, 3).unwrap();
        let z = run.unknowns();
        assert!((z[0] - st.v).abs() < 1e-6, "{run:?} {st:?}");
        assert!((z[2] - st.a[0]).abs() < 1e-6, "{run:?} {st:?}");
        assert!(
            (z[3] - st.a[1]).abs() < 1e-6 && st.a[1].abs() > 1e-2,
            "{run:?} {st:?}"
        );
        assert!(z[1].abs() < 1e-9 && z[4].abs() < 1e-9, "{run:?}");
    }
}
