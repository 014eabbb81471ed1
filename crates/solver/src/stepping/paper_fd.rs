//! The paper's own scheme (Sect. 3): forward Euler, 5-point Laplacian, central differences,
//! `Theta` evaluated on the lab grid at the droplet's position (minimum image).
//! Kept as the baseline for speed and error comparisons; paper settings dx = 0.025, dt = 1e-4.
use crate::model::dynamics;
use crate::model::forces::parseval::Forces;
use crate::model::grid::Grid;
use crate::model::params::ModelParams;
use crate::model::shape::ShapeParams;
use crate::model::state::DropletState;
use crate::stepping::{Attempt, Field, Scheme, Stepper};

/// Explicit finite-difference integrator on the lab grid.
pub struct PaperFd {
    params: ModelParams,
    shape: ShapeParams,
    n: usize,
    dx: f64,
    pinned: bool,
    state: DropletState,
    u: Vec<f64>,
    u_next: Vec<f64>,
    theta: Vec<f64>,
    /// Rows and columns (wrapped indices) touched by the last `Theta` fill.
    touched: Vec<usize>,
}

impl PaperFd {
    /// A run from `state` with `u = 0` on an `n x n` lab grid.
    pub fn new(
        params: ModelParams,
        n: usize,
        state: DropletState,
        pinned: bool,
    ) -> Result<Self, crate::error::SolverError> {
        params.validate()?;
        let grid = Grid::new(n, params.box_len)?;
        let mut state = state;
        if pinned {
            state.vx = 0.0;
            state.vy = 0.0;
        }
        Ok(Self {
            params,
            shape: ShapeParams {
                radius: params.radius,
                sigma: params.sigma,
            },
            n,
            dx: grid.dx,
            pinned,
            state,
            u: vec![0.0; n * n],
            u_next: vec![0.0; n * n],
            theta: vec![0.0; n * n],
            touched: Vec::new(),
        })
    }

    /// Fills `Theta` around the droplet and sums `A`, `F`, `Ga`, `Gb` with central differences.
    fn fill_and_forces(&mut self) -> [f64; 5] {
        let n = self.n;
        let dx = self.dx;
        for &i in &self.touched {
            self.theta[i] = 0.0;
        }
        self.touched.clear();
        let st = self.state;
        let len = self.params.box_len;
        let wrap = |c: f64| c - len * (c / len).round();
        let (xc, yc) = (wrap(st.x), wrap(st.y));
        let r_out = self.shape.outer_radius(st.a2, st.b2);
        let w = (r_out / dx).ceil() as isize + 1;
        // Grid index nearest to the centre (x = (i - n/2) dx).
        let cx = (xc / dx).round() as isize + (n / 2) as isize;
        let cy = (yc / dx).round() as isize + (n / 2) as isize;
        let ni = n as isize;
        let (mut area, mut fx, mut fy, mut ga, mut gb) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let inv2dx = 0.5 / dx;
        for jy in cy - w..=cy + w {
            let iy = jy.rem_euclid(ni) as usize;
            let y = (jy - (n / 2) as isize) as f64 * dx - yc;
            for jx in cx - w..=cx + w {
                let ix = jx.rem_euclid(ni) as usize;
                let x = (jx - (n / 2) as isize) as f64 * dx - xc;
                let t = self.shape.theta(st.a2, st.b2, x, y);
                if t == 0.0 {
                    continue;
                }
                let idx = iy * n + ix;
                self.theta[idx] = t;
                self.touched.push(idx);
                area += t;
                let (ux, uy) = central_gradient(&self.u, n, (ix, iy), inv2dx);
                fx -= ux * t;
                fy -= uy * t;
                ga -= (x * ux - y * uy) * t;
                gb -= (y * ux + x * uy) * t;
            }
        }
        let da = dx * dx;
        [area * da, fx * da, fy * da, ga * da, gb * da]
    }
}

impl Stepper for PaperFd {
    /// Forward Euler has no embedded estimate: every attempt is taken.
    fn attempt(&mut self, h: f64, _max_error: f64) -> Attempt {
        self.euler_step(h);
        Attempt {
            accepted: true,
            error: None,
        }
    }
}

impl Scheme for PaperFd {
    fn state(&self) -> DropletState {
        self.state
    }

    fn mass(&self) -> f64 {
        self.u.iter().sum::<f64>() * self.dx * self.dx
    }

    fn field(&mut self) -> Field {
        Field {
            n: self.n,
            len: self.params.box_len,
            values: self.u.clone(),
        }
    }
}

/// `grad u` at cell `(ix, iy)` of the periodic `n x n` field `u` by central differences
/// (`inv2dx = 1 / (2 dx)`).
pub(crate) fn central_gradient(
    u: &[f64],
    n: usize,
    (ix, iy): (usize, usize),
    inv2dx: f64,
) -> (f64, f64) {
    let ux = (u[iy * n + (ix + 1) % n] - u[iy * n + (ix + n - 1) % n]) * inv2dx;
    let uy = (u[((iy + 1) % n) * n + ix] - u[((iy + n - 1) % n) * n + ix]) * inv2dx;
    (ux, uy)
}

/// One forward-Euler step of `h` of the field on the periodic `n x n` lab grid of spacing
/// `dx`: `u <- u + h (Lap u - u + Theta / A)`, the 5-point Laplacian, into `u` (`u_next` is
/// scratch).
pub(crate) fn euler_field_step(
    u: &mut Vec<f64>,
    u_next: &mut Vec<f64>,
    theta: &[f64],
    (n, dx): (usize, f64),
    h: f64,
    area: f64,
) {
    let inv_dx2 = 1.0 / (dx * dx);
    let inv_a = 1.0 / area;
    for iy in 0..n {
        let up = ((iy + n - 1) % n) * n;
        let dn = ((iy + 1) % n) * n;
        let row = iy * n;
        for ix in 0..n {
            let l = if ix == 0 { n - 1 } else { ix - 1 };
            let r = if ix == n - 1 { 0 } else { ix + 1 };
            let c = u[row + ix];
            let lap = (u[row + l] + u[row + r] + u[up + ix] + u[dn + ix] - 4.0 * c) * inv_dx2;
            u_next[row + ix] = c + h * (lap - c + theta[row + ix] * inv_a);
        }
    }
    std::mem::swap(u, u_next);
}

impl PaperFd {
    /// One forward-Euler step of the field and the droplet (paper Sect. 3).
    fn euler_step(&mut self, h: f64) {
        let [area, fx, fy, ga, gb] = self.fill_and_forces();
        euler_field_step(
            &mut self.u,
            &mut self.u_next,
            &self.theta,
            (self.n, self.dx),
            h,
            area,
        );
        let p = self.params;
        let st = &mut self.state;
        let f = Forces {
            fx,
            fy,
            ga,
            gb,
            area,
        };
        let rhs = dynamics::force_balance(&p, st.monitored(), &f);
        if !self.pinned {
            let (vx, vy) = (st.vx, st.vy);
            if p.mass > 0.0 {
                st.vx += h / p.mass * rhs[0];
                st.vy += h / p.mass * rhs[1];
                st.x += h * vx;
                st.y += h * vy;
            } else {
                (st.vx, st.vy) = dynamics::overdamped_velocity(&p, &f);
                st.x += h * st.vx;
                st.y += h * st.vy;
            }
        }
        st.a2 += h / p.eta2 * rhs[2];
        st.b2 += h / p.eta2 * rhs[3];
    }
}
