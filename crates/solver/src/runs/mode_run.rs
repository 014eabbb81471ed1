//! Time stepping of the `K`-mode model (the paper's general equations with modes `2..K`,
//! [`crate::roots::mode_solver`]) in the droplet's frame, until its state is steady: the first
//! scheme of the `K`-mode model, exponential Euler (first order in time).
//!
//! Per step of length `h` the field moves exactly under its diffusion and decay
//! `c = -(1 + k^2)` with the advection and the source frozen at the step's start, as the
//! production scheme's predictor does ([`crate::stepping::comoving_etd`]):
//! `u_hat <- e^(c h) u_hat + (e^(c h) - 1) / c (i k.v u_hat + s_hat)` (`s = Theta / A`),
//! and the mechanics under their exact linear decay with the current forces frozen:
//! `m v_t = -eta_t v + F`, `eta_k a_k,t = G_k^(a) - kappa_k a_k` (`eta_k = eta2`), the same
//! for `b_k`. Its fixed points are exactly the steady states of [`ModeSolver`] (the field's
//! is `s_hat / (1 + k^2 - i k.v)`), so a run that settles lands on the root Newton finds, to
//! the accuracy of its settling. The run starts from `u = 0` (the paper's initial field) and
//! is steady when every rate `|dz/dt|` is below `tol`.
use crate::error::SolverError;
use crate::model::modes::Modes;
use crate::model::params::ModelParams;
use crate::roots::mode_solver::ModeSolver;
use crate::stepping::etd::SeparableExp;
use rustfft::num_complex::Complex64;

/// How a `K`-mode run steps and when it stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeRunSettings {
    /// Time step.
    pub dt: f64,
    /// Largest time.
    pub t_max: f64,
    /// Steady when every rate `|dz/dt|` is below this.
    pub tol: f64,
}

/// How a `K`-mode run ended.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeRun {
    /// `(vx, vy, a_2..a_K, b_2..b_K)` at the end.
    pub z: Vec<f64>,
    pub t_end: f64,
    pub steps: u64,
    /// Whether every rate fell below the tolerance before `t_max`.
    pub steady: bool,
    /// The largest rate `|dz/dt|` at the end.
    pub rate: f64,
}

/// Per unknown `(vx, vy, a_2..a_K, b_2..b_K)`: the linear decay rate (`eta_t / m`,
/// `kappa_k / eta_k`), the inertia (`m`, `eta_k`), and the exponential-Euler weights of a step
/// `h`: `e^(-r h)` on the value and `(1 - e^(-r h)) / (r m)` on the frozen force.
type LinearParts = (Vec<f64>, Vec<f64>, Vec<(f64, f64)>);

fn linear_parts(solver: &ModeSolver, k_max: usize, h: f64) -> LinearParts {
    let p = solver.params();
    let mut rate_of = vec![p.eta_t / p.mass; 2];
    let mut inertia = vec![p.mass; 2];
    // a_2..a_K, then b_2..b_K.
    for k in (2..=k_max).chain(2..=k_max) {
        rate_of.push(solver.kappa(k) / solver.eta(k));
        inertia.push(solver.eta(k));
    }
    let decay = rate_of
        .iter()
        .zip(&inertia)
        .map(|(r, m)| {
            let e = (-r * h).exp();
            (e, (1.0 - e) / (r * m))
        })
        .collect();
    (rate_of, inertia, decay)
}

/// The `K`-mode model's state in time, stepped by exponential Euler: one step is
/// [`ModeStepper::rate`] (the forces at the present state, and the largest rate `|dz/dt|`)
/// then [`ModeStepper::advance`]. Plans and buffers are made once; a step allocates nothing
/// but the forces' vector.
pub struct ModeStepper {
    solver: ModeSolver,
    /// `(vx, vy, a_2..a_K, b_2..b_K)`.
    pub z: Vec<f64>,
    /// The field's spectrum.
    u: Vec<Complex64>,
    /// `e^(c h) - 1` factored by wavenumber (`c = -(1 + kx^2 + ky^2)`), and `1 / c` per mode.
    exp: SeparableExp,
    inv_c: Vec<f64>,
    /// `1 / (A N^2)`: the last [`Self::rate`]'s raw transform of `Theta` to the source.
    src_scale: f64,
    h: f64,
    rate_of: Vec<f64>,
    inertia: Vec<f64>,
    decay: Vec<(f64, f64)>,
    /// The forces at `z`, from the last [`Self::rate`].
    forces: Vec<f64>,
    pub t: f64,
    pub steps: u64,
    /// The centre, moved by the velocity at the start of each step.
    pub x: f64,
    pub y: f64,
}

impl ModeStepper {
    /// The `K`-mode model (`K = z0.len() / 2`) at `z0` with the field 0, steps of `h`.
    pub fn new(params: &ModelParams, n: usize, z0: &[f64], h: f64) -> Result<Self, SolverError> {
        let k_max = z0.len() / 2;
        crate::contract::limits::check_mode_stepper(params, n, k_max)?;
        let solver = ModeSolver::new(*params, n)?;
        let (rate_of, inertia, decay) = linear_parts(&solver, k_max, h);
        let grid = solver.grid();
        let mut exp = SeparableExp::default();
        exp.update(h, &grid.kx, &grid.ky);
        let inv_c = grid.inverse_rates();
        Ok(Self {
            solver,
            z: z0.to_vec(),
            u: Vec::new(),
            exp,
            inv_c,
            src_scale: 0.0,
            h,
            rate_of,
            inertia,
            decay,
            forces: Vec::new(),
            t: 0.0,
            steps: 0,
            x: 0.0,
            y: 0.0,
        })
    }

    /// Sets the friction law of the modes `k >= 3` ([`crate::model::mode_friction`]; the
    /// default is `eta_k = eta2`).
    pub fn set_eta_k_exponent(&mut self, exponent: f64) {
        self.solver.set_eta_k_exponent(exponent);
        (self.rate_of, self.inertia, self.decay) =
            linear_parts(&self.solver, self.z.len() / 2, self.h);
    }

    /// The forces at the present state, kept for [`Self::advance`], and the largest rate
    /// `|dz/dt|` = `|force / inertia - rate z|` they give.
    pub fn rate(&mut self) -> f64 {
        let k_max = self.z.len() / 2;
        let m = Modes::of_state(&self.z);
        let (area, lo, hi) = self.solver.theta_spectrum(&m);
        self.src_scale = self.solver.source_scale(area);
        if self.u.is_empty() {
            self.u = vec![Complex64::default(); self.solver.source_spectrum().len()];
        }
        self.solver.gradient(&self.u, lo, hi);
        self.forces = self.solver.sums(k_max, lo, hi, area).to_vec();
        self.forces
            .iter()
            .zip(&self.z)
            .zip(self.rate_of.iter().zip(&self.inertia))
            .map(|((f, z), (r, m))| (f / m - r * z).abs())
            .fold(0.0f64, f64::max)
    }

    /// The steady solver the run steps with (its buffers are refilled by the next
    /// [`Self::rate`]).
    pub fn solver_mut(&mut self) -> &mut ModeSolver {
        &mut self.solver
    }

    /// One step of `h` with the forces, the advection and the source of the last
    /// [`Self::rate`] frozen: the field's diffusion and decay exact, the mechanics under their
    /// exact linear decay. The propagator's coefficients come from [`SeparableExp`] (made
    /// once for the fixed step): no exponential or division per mode, and the source's scale
    /// `1 / (A N^2)` is applied in the same pass.
    pub fn advance(&mut self) {
        let h = self.h;
        let (vx, vy) = (self.z[0], self.z[1]);
        self.x += h * vx;
        self.y += h * vy;
        let grid = self.solver.grid();
        let n = grid.n;
        let inv_h = 1.0 / h;
        let scale = self.src_scale;
        let source = self.solver.source_spectrum();
        for (jx, (kxd, ax)) in grid.kx_d.iter().zip(&self.exp.ax).enumerate() {
            let row = jx * n..(jx + 1) * n;
            let modes = grid
                .ky_d
                .iter()
                .zip(&self.exp.ay)
                .zip(&self.inv_c[row.clone()]);
            for ((u, s), ((kyd, ay), ic)) in
                self.u[row.clone()].iter_mut().zip(&source[row]).zip(modes)
            {
                let cf = SeparableExp::coef(*ax, *ay, *ic, h, inv_h);
                let kv = kxd * vx + kyd * vy;
                // i k.v u + s.
                let nl = Complex64::new(-kv * u.im + scale * s.re, kv * u.re + scale * s.im);
                *u = *u * cf.e + nl * cf.p1;
            }
        }
        for ((z, f), (e, w)) in self.z.iter_mut().zip(&self.forces).zip(&self.decay) {
            *z = e * *z + w * f;
        }
        self.t += h;
        self.steps += 1;
    }
}

/// Runs the `K`-mode model (`K = z0.len() / 2`) from `z0` with the field 0.
pub fn run_modes(
    params: &ModelParams,
    n: usize,
    z0: &[f64],
    settings: &ModeRunSettings,
) -> Result<ModeRun, SolverError> {
    let mut run = ModeStepper::new(params, n, z0, settings.dt)?;
    crate::error::require(
        settings.dt > 0.0 && settings.t_max / settings.dt <= crate::contract::settings::MAX_STEPS,
        "dt",
        settings.dt,
        "a finite number > 0 giving at most MAX_STEPS steps up to t_max",
    )?;
    loop {
        let rate = run.rate();
        let t = run.t;
        if (rate < settings.tol && t > 0.0) || t >= settings.t_max || !rate.is_finite() {
            return Ok(ModeRun {
                z: run.z,
                t_end: t,
                steps: run.steps,
                steady: rate < settings.tol,
                rate,
            });
        }
        run.advance();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuation::mode_branch::md_state;

    #[test]
    fn a_run_settles_on_the_state_newton_finds_with_its_mode_3() {
        // Fig. 1c with modes 2..3 from a droplet pushed along x: the run ends steady on the MD
        // state of the steady solver, a3 included, to 1e-6. (N = 96: there the box's rotation
        // mode of the x-axis state decays, at rate 0.037; at N = 64 the run turns away from
        // the axis.)
        let p = ModelParams::at(0.085, 0.112);
        let n = 96;
        let run = run_modes(
            &p,
            n,
            &[0.5, 0.0, -0.1, 0.0, 0.0, 0.0],
            &ModeRunSettings {
                dt: 0.05,
                t_max: 3000.0,
                tol: 1e-9,
            },
        )
        .unwrap();
        assert!(run.steady, "{run:?}");
        let mut solver = ModeSolver::new(p, n).unwrap();
        let st = md_state(&mut solver, 3).unwrap();
        assert!((run.z[0] - st.v).abs() < 1e-6, "{run:?} {st:?}");
        assert!((run.z[2] - st.a[0]).abs() < 1e-6, "{run:?} {st:?}");
        assert!(
            (run.z[3] - st.a[1]).abs() < 1e-6 && st.a[1].abs() > 1e-2,
            "{run:?} {st:?}"
        );
        assert!(run.z[1].abs() < 1e-9 && run.z[4].abs() < 1e-9, "{run:?}");
    }
}
