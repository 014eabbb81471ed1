//! The paper's scheme ([`crate::stepping::paper_fd`]) for the 2-mode droplet, with the mode-2
//! shape's own sampler of `Theta`.
use crate::model::dynamics;
use crate::model::forces::parseval::Forces;
use crate::model::grid::Grid;
use crate::model::params::ModelParams;
use crate::model::shape::ShapeParams;
use crate::model::state::DropletState;
use crate::stepping::paper_fd::finite_differences::{central_gradient, euler_field_step};
use crate::stepping::{Attempt, Field, Scheme, Stepper};

/// Explicit finite-difference integrator on the lab grid.
pub struct TwoModeFd {
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

impl TwoModeFd {
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
            shape: params.shape(),
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

impl Stepper for TwoModeFd {
    /// Forward Euler has no embedded estimate: every attempt is taken.
    fn attempt(&mut self, h: f64, _max_error: f64) -> Attempt {
        self.euler_step(h);
        Attempt {
            accepted: true,
            error: None,
        }
    }
}

impl Scheme for TwoModeFd {
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

impl TwoModeFd {
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
