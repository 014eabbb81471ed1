//! The paper's own scheme (Sect. 3, [`crate::stepping::paper_fd`]) for its general model with
//! shape modes `2..K`: forward Euler on the lab grid, the 5-point Laplacian, central
//! differences for `grad u`, and `Theta` of the shape with every mode
//! ([`crate::model::modes::Modes`]) at the droplet's position (minimum image).
//!
//! Per step of `h`, with everything at the step's start:
//! `u <- u + h (Lap u - u + Theta / A)`, `r_c <- r_c + h v`,
//! `v <- v + (h / m) (-eta_t v + F)`, `a_k <- a_k + (h / eta2) (G_k^(a) - kappa_k a_k)` and the
//! same for `b_k` (`kappa_k = (k^2 / 4) kappa2`, `eta_k = eta2` unless a friction law is
//! set in the model's parameters, [`crate::model::friction`]), with the forces
//! `F = -Int grad u Theta dA` (eq. 35) and `G_k = -Int w_k . grad u Theta dA` (the smoothed
//! eqs. dakdt_dl, dbkdt_dl; `w_k` of [`crate::model::modes::w_fields`]). With `K = 2` this is
//! [`crate::stepping::paper_fd::TwoModeFd`] (tested to round-off).
use crate::error::SolverError;
use crate::model::friction::eta_k;
use crate::model::grid::Grid;
use crate::model::modes::{w_fields, Modes};
use crate::model::params::ModelParams;
use crate::model::shape::ShapeParams;
use crate::model::state::DropletState;
use crate::stepping::paper_fd::finite_differences::central_gradient;
use crate::stepping::{Attempt, Field, Scheme, Stepper};

/// Explicit finite differences for the `K`-mode droplet on the lab grid. One step is
/// [`PaperFd::rates`] (`Theta` and the forces at the present state, and the rates)
/// then [`PaperFd::advance`] (a [`Stepper`] step measures the rate unless the run just did);
/// the buffers are made once.
pub struct PaperFd {
    params: ModelParams,
    shape: ShapeParams,
    n: usize,
    dx: f64,
    /// `(vx, vy, a_2..a_K, b_2..b_K)`.
    pub z: Vec<f64>,
    /// The centre.
    pub x: f64,
    pub y: f64,
    u: Vec<f64>,
    u_next: Vec<f64>,
    theta: Vec<f64>,
    /// Cells where the last [`Self::rate`] wrote `Theta`.
    touched: Vec<usize>,
    /// Per unknown: the inertia (`m`, `eta2`) and the linear decay coefficient (`eta_t`,
    /// `kappa_k`) of its force balance.
    inertia: Vec<f64>,
    stiffness: Vec<f64>,
    /// The force balances `-eta_t v + F`, `G_k - kappa_k a_k` at `z`, and `A`, from the last
    /// [`Self::rate`].
    balance: Vec<f64>,
    area: f64,
    /// Whether [`Self::balance`] is the present state's.
    fresh: bool,
}

impl PaperFd {
    /// The `K`-mode droplet (`K = z0.len() / 2`) at `z0`, centred at the origin, with `u = 0`
    /// on an `n x n` lab grid.
    pub fn new(params: &ModelParams, n: usize, z0: &[f64]) -> Result<Self, SolverError> {
        params.validate()?;
        let k_max = z0.len() / 2;
        crate::stepping::require_inertia(params)?;
        let grid = Grid::new(n, params.box_len)?;
        let mut inertia = vec![params.mass; 2];
        let mut stiffness = vec![params.eta_t; 2];
        for k in (2..=k_max).chain(2..=k_max) {
            inertia.push(eta_k(params.eta2, k, params.eta_k_exponent));
            stiffness.push((k * k) as f64 / 4.0 * params.kappa2);
        }
        Ok(Self {
            params: *params,
            shape: params.shape(),
            n,
            dx: grid.dx,
            z: z0.to_vec(),
            x: 0.0,
            y: 0.0,
            u: vec![0.0; n * n],
            u_next: vec![0.0; n * n],
            theta: vec![0.0; n * n],
            touched: Vec::new(),
            inertia,
            stiffness,
            balance: vec![0.0; z0.len()],
            area: 0.0,
            fresh: false,
        })
    }

    /// Replaces the field by `values` (lab grid, `values[iy * n + ix]` at
    /// `x = (ix - n/2) dx`, as [`crate::stepping::Field`]); false, changing nothing, when the
    /// length is not `n^2`.
    pub fn set_field(&mut self, values: &[f64]) -> bool {
        let fits = values.len() == self.u.len();
        if fits {
            self.u.copy_from_slice(values);
        }
        fits
    }

    /// `Integral u dA`.
    pub fn mass(&self) -> f64 {
        self.u.iter().sum::<f64>() * self.dx * self.dx
    }

    /// Fills `Theta` around the droplet and sums `A` and the forces with central differences
    /// into [`Self::balance`] (the forces only; [`Self::rate`] subtracts the linear parts).
    fn fill_and_forces(&mut self) {
        let (n, dx) = (self.n, self.dx);
        for &i in &self.touched {
            self.theta[i] = 0.0;
        }
        self.touched.clear();
        let k_max = self.z.len() / 2;
        let modes = Modes::of_state(&self.z);
        let len = self.params.box_len;
        let wrap = |c: f64| c - len * (c / len).round();
        let (xc, yc) = (wrap(self.x), wrap(self.y));
        let w = (modes.outer_radius(&self.shape) / dx).ceil() as isize + 1;
        // Grid index nearest to the centre (x = (i - n/2) dx).
        let cx = (xc / dx).round() as isize + (n / 2) as isize;
        let cy = (yc / dx).round() as isize + (n / 2) as isize;
        let (ni, half) = (n as isize, (n / 2) as isize);
        let inv2dx = 0.5 / dx;
        let mut area = 0.0;
        self.balance.iter_mut().for_each(|b| *b = 0.0);
        for jy in cy - w..=cy + w {
            let iy = jy.rem_euclid(ni) as usize;
            let y = (jy - half) as f64 * dx - yc;
            for jx in cx - w..=cx + w {
                let ix = jx.rem_euclid(ni) as usize;
                let x = (jx - half) as f64 * dx - xc;
                let t = modes.theta(&self.shape, x, y);
                if t == 0.0 {
                    continue;
                }
                let idx = iy * n + ix;
                self.theta[idx] = t;
                self.touched.push(idx);
                area += t;
                let (ux, uy) = central_gradient(&self.u, n, (ix, iy), inv2dx);
                self.balance[0] -= ux * t;
                self.balance[1] -= uy * t;
                for k in 2..=k_max {
                    let (wa, wb) = w_fields(k, self.shape.radius, x, y);
                    self.balance[k] -= (wa[0] * ux + wa[1] * uy) * t;
                    self.balance[k_max - 1 + k] -= (wb[0] * ux + wb[1] * uy) * t;
                }
            }
        }
        let da = dx * dx;
        self.area = area * da;
        self.balance.iter_mut().for_each(|b| *b *= da);
    }

    /// `Theta` and the force balances at the present state, kept for [`Self::advance`], and
    /// the rates `dz/dt` = `balance / inertia`.
    pub fn rates(&mut self) -> Vec<f64> {
        self.fill_and_forces();
        self.fresh = true;
        let mut rates = Vec::with_capacity(self.balance.len());
        for (i, b) in self.balance.iter_mut().enumerate() {
            *b -= self.stiffness[i] * self.z[i];
            rates.push(*b / self.inertia[i]);
        }
        rates
    }

    /// One forward-Euler step of `h` from the state of the last [`Self::rates`].
    pub fn advance(&mut self, h: f64) {
        crate::stepping::paper_fd::finite_differences::euler_field_step(
            &mut self.u,
            &mut self.u_next,
            &self.theta,
            (self.n, self.dx),
            h,
            self.area,
        );
        self.x += h * self.z[0];
        self.y += h * self.z[1];
        for ((z, b), m) in self.z.iter_mut().zip(&self.balance).zip(&self.inertia) {
            *z += h / m * b;
        }
        self.fresh = false;
    }
}

impl Stepper for PaperFd {
    /// Forward Euler has no error estimate: every step is taken.
    fn attempt(&mut self, h: f64, _max_error: f64) -> Attempt {
        if !self.fresh {
            self.rates();
        }
        self.advance(h);
        Attempt {
            accepted: true,
            error: None,
        }
    }
}

impl Scheme for PaperFd {
    fn state(&self) -> DropletState {
        DropletState::of_unknowns(&self.z, self.x, self.y).0
    }

    fn unknowns(&self) -> Vec<f64> {
        self.z.clone()
    }

    fn mass(&self) -> f64 {
        PaperFd::mass(self)
    }

    fn field(&mut self) -> Field {
        Field {
            n: self.n,
            len: self.params.box_len,
            values: self.u.clone(),
        }
    }

    fn rates(&mut self) -> Option<Vec<f64>> {
        Some(PaperFd::rates(self))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stepping::paper_fd::TwoModeFd;

    #[test]
    fn two_modes_step_as_the_papers_scheme() {
        // K = 2 from a moving, deformed droplet: 400 steps at N = 64 follow TwoModeFd to
        // round-off (Theta of the mode sum against the paper's plane shape: 1e-14).
        let p = ModelParams::at(0.085, 0.112);
        let (n, h) = (64, 2e-3);
        let st = DropletState {
            x: 0.0,
            y: 0.0,
            vx: 0.3,
            vy: -0.1,
            a2: -0.08,
            b2: 0.03,
        };
        let mut paper = TwoModeFd::new(p, n, st, false).unwrap();
        let mut fd = PaperFd::new(&p, n, &[0.3, -0.1, -0.08, 0.03]).unwrap();
        for _ in 0..400 {
            paper.step(h);
            fd.rates();
            fd.advance(h);
        }
        let s = paper.state();
        let want = [s.vx, s.vy, s.a2, s.b2, s.x, s.y];
        let got = [fd.z[0], fd.z[1], fd.z[2], fd.z[3], fd.x, fd.y];
        for (w, g) in want.iter().zip(&got) {
            assert!((w - g).abs() < 1e-12, "{want:?} vs {got:?}");
        }
        assert!((paper.mass() - fd.mass()).abs() < 1e-12);
        assert!(s.vx.abs() > 0.05, "the droplet still moves: {s:?}");
    }

    /// The largest force balance of the paper's scheme at the `K = 3` MD state of the spectral
    /// steady solver, its field included, against the largest force there.
    fn balance_at_spectral_md(n: usize) -> (f64, f64, f64) {
        use crate::roots::{balances::lab_field, steady_solver::SteadySolver};
        let p = ModelParams::at(0.085, 0.112);
        let mut solver = SteadySolver::new(p, n).unwrap();
        let md = crate::roots::named_state::md_state(&mut solver, 3).unwrap();
        let z = crate::roots::steady_solver::on_x_axis(md.v, &md.a);
        let field = lab_field(&mut solver, &z, 0.0, 0.0);
        let mut fd = PaperFd::new(&p, n, &z).unwrap();
        assert!(fd.set_field(&field.values));
        fd.rates();
        let worst = fd.balance.iter().fold(0.0f64, |m, b| m.max(b.abs()));
        (worst, p.eta_t * md.v, md.a[1])
    }

    #[test]
    fn its_forces_balance_at_the_spectral_steady_state_to_second_order() {
        // Independent of the spectral solver's forces: the paper's central differences and
        // the general w_k on the spectral MD state of modes 2..3 (a3 != 0) and its field.
        // The state is a root of the spectral balances; here every balance is O(dx^2) and
        // falls about 4x when dx halves.
        let (coarse, force, a3) = balance_at_spectral_md(96);
        let (fine, ..) = balance_at_spectral_md(192);
        assert!(a3.abs() > 1e-2, "a3 = {a3}");
        assert!(fine < 1e-3 * force, "{fine} vs the drag {force}");
        let order = (coarse / fine).log2();
        assert!(
            (1.7..2.3).contains(&order),
            "{coarse} -> {fine}: order {order}"
        );
    }

    #[test]
    fn the_field_mass_tends_to_one_and_a_four_fold_shape_at_rest_stays_put() {
        // A 4-fold shape (a4) at rest, centred on a grid point: the shape has the grid's
        // symmetries (mirrors in both axes and in the diagonal), so no net force and no force
        // on any other mode: it neither moves nor takes another shape. Integral u dA relaxes
        // to 1 as forward Euler's 1 - (1 - h)^steps (the source has unit mass, the decay
        // rate 1, and the Laplacian sums to 0).
        let p = ModelParams::at(0.085, 0.112);
        let (n, h, steps) = (64, 2e-3, 2000);
        let mut z = vec![0.0; 8];
        z[4] = 0.05;
        let mut fd = PaperFd::new(&p, n, &z).unwrap();
        for _ in 0..steps {
            fd.rates();
            fd.advance(h);
        }
        let want = 1.0 - (1.0 - h).powi(steps);
        assert!((fd.mass() - want).abs() < 1e-9, "{} vs {want}", fd.mass());
        for (i, zi) in fd.z.iter().enumerate().filter(|(i, _)| *i != 4) {
            assert!(zi.abs() < 1e-12, "unknown {i}: {:?}", fd.z);
        }
        assert!(fd.z[4] > 0.0 && fd.z[4] < 0.05, "a4 relaxes: {:?}", fd.z);
    }
}
