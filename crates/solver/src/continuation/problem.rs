//! One family of steady states on a mirror line of the box, as the zero set of the force
//! balance over `(unknowns, parameter)`: the map from the continuation's scaled vector
//! `y = (unknowns..., q)` (with `q` the varied parameter mapped onto `[0, 1]` over the line)
//! to the state `z = (vx, vy, a2, b2)` and the balance's residual.
//!
//! - IC: no unknowns (`z = 0` is a root for every parameter).
//! - ID: the shape amplitude `c` on the axis, `v = 0` (one equation: the shape balance).
//! - MD moving along its minor axis (`c < 0`) or its major axis (`c > 0`): `(v, c)`, speed
//!   along the axis (two equations).
use crate::error::SolverError;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::roots::linearisation::TwoModeLinearization;
use crate::roots::steady_solver::{MirrorAxis, TwoModeSolver};
use crate::roots::verdict::{assess, Verdict};
use serde::Serialize;

/// A family of steady states.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Family {
    IC,
    ID,
    /// Moving along its minor axis (the paper's MD).
    MdMinor,
    /// Moving along its major axis.
    MdMajor,
}

impl Family {
    /// The reduced model's branch of the same family.
    pub fn reduced(&self) -> crate::reduced::bifurcation::Branch {
        use crate::reduced::bifurcation::Branch;
        match self {
            Self::IC => Branch::IC,
            Self::ID => Branch::ID,
            Self::MdMinor => Branch::MdMinor,
            Self::MdMajor => Branch::MdMajor,
        }
    }

    /// The name used in tables and pictures (the reduced model's branch name).
    pub fn as_str(&self) -> &'static str {
        self.reduced().as_str()
    }

    /// Unknowns besides the parameter.
    pub fn unknowns(&self) -> usize {
        match self {
            Self::IC => 0,
            Self::ID => 1,
            Self::MdMinor | Self::MdMajor => 2,
        }
    }

    pub fn moving(&self) -> bool {
        self.unknowns() == 2
    }
}

impl std::str::FromStr for Family {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "ic" => Ok(Self::IC),
            "id" => Ok(Self::ID),
            "md" | "md-minor" => Ok(Self::MdMinor),
            "md-major" => Ok(Self::MdMajor),
            other => Err(format!(
                "unknown branch `{other}`: ic, id, md (= md-minor, moving along its minor axis) or md-major"
            )),
        }
    }
}

/// The zero set of one family along a parameter line.
pub struct Problem {
    pub solver: TwoModeSolver,
    pub family: Family,
    pub mirror: MirrorAxis,
    pub parameter: ModelParam,
    /// Start of the line (`q = 0`).
    pub from: f64,
    /// `to - from` (`q = 1` at `to`).
    pub span: f64,
}

impl Problem {
    pub fn new(
        base: &ModelParams,
        n: usize,
        family: Family,
        mirror: MirrorAxis,
        parameter: ModelParam,
        from: f64,
        to: f64,
    ) -> Result<Self, SolverError> {
        Ok(Self {
            solver: TwoModeSolver::new(*base, n)?,
            family,
            mirror,
            parameter,
            from,
            span: to - from,
        })
    }

    /// The parameter's value at `q`.
    pub fn value(&self, q: f64) -> f64 {
        self.from + q * self.span
    }

    /// `q` of a parameter value.
    pub fn q_of(&self, value: f64) -> f64 {
        (value - self.from) / self.span
    }

    /// The parameters at `q`.
    pub fn params_at(&self, q: f64) -> ModelParams {
        self.parameter.with(self.solver.params(), self.value(q))
    }

    /// Moves the solver to `q`; false where the parameters are invalid there (a geometric
    /// parameter beyond its range), where the residual is NaN and the corrector fails.
    fn set(&mut self, q: f64) -> bool {
        self.solver.set_param(self.parameter, self.value(q)).is_ok()
    }

    /// Speed along the axis and shape amplitude on it at `y`.
    pub fn speed_and_shape(&self, y: &[f64]) -> (f64, f64) {
        match self.family {
            Family::IC => (0.0, 0.0),
            Family::ID => (0.0, y[0]),
            Family::MdMinor | Family::MdMajor => (y[0], y[1]),
        }
    }

    /// `z = (vx, vy, a2, b2)` at `y`.
    pub fn state(&self, y: &[f64]) -> [f64; 4] {
        let (v, c) = self.speed_and_shape(y);
        match self.mirror {
            MirrorAxis::X => [v, 0.0, c, 0.0],
            MirrorAxis::Diagonal => {
                let d = v * std::f64::consts::FRAC_1_SQRT_2;
                [d, d, 0.0, c]
            }
        }
    }

    /// `y` from `(v, c)` at the parameter value `value`.
    pub fn y_of(&self, v: f64, c: f64, value: f64) -> Vec<f64> {
        let q = self.q_of(value);
        match self.family {
            Family::IC => vec![q],
            Family::ID => vec![c, q],
            Family::MdMinor | Family::MdMajor => vec![v, c, q],
        }
    }

    /// The force balance at `y` (as many equations as unknowns).
    pub fn residual(&mut self, y: &[f64]) -> Vec<f64> {
        if !self.set(*y.last().expect("q")) {
            return vec![f64::NAN; y.len() - 1];
        }
        let (v, c) = self.speed_and_shape(y);
        match self.family {
            Family::IC => Vec::new(),
            Family::ID => vec![self.solver.residual_on(self.mirror, 0.0, c)[1]],
            Family::MdMinor | Family::MdMajor => {
                self.solver.residual_on(self.mirror, v, c).to_vec()
            }
        }
    }

    /// Where the branch through `near` (a root with small `v`, or small `c` for ID) meets the
    /// family it bifurcates from, as a root of the bifurcation equations themselves: the
    /// balance along the motion is odd in `v` (odd in `c` for ID's shape balance, by the box's
    /// quarter-turn and mirror symmetries), so at the meeting point its derivative at `v = 0`
    /// vanishes together with the other equation. Newton on `(c, q)` (on `q` for ID): exact
    /// where the arclength corrector is not (the two branches cross there).
    pub fn meeting(&mut self, near: &[f64]) -> Option<Vec<f64>> {
        const H: f64 = 1e-5;
        let opts = crate::numerics::newton::NewtonOptions {
            tol: 1e-13,
            max_iter: 30,
            fd_step: 1e-7,
            max_step: vec![0.05; 2],
        };
        match self.family {
            Family::IC => None,
            Family::ID => {
                let sol = crate::numerics::newton::solve(
                    |x| {
                        let r = |p: &mut Self, c: f64| p.residual(&[c, x[0]])[0];
                        vec![(r(self, H) - r(self, -H)) / (2.0 * H)]
                    },
                    &[near[1]],
                    &opts,
                )
                .ok()?;
                Some(vec![0.0, sol.x[0]])
            }
            Family::MdMinor | Family::MdMajor => {
                let sol = crate::numerics::newton::solve(
                    |x| {
                        let plus = self.residual(&[H, x[0], x[1]]);
                        let minus = self.residual(&[-H, x[0], x[1]]);
                        let at0 = self.residual(&[0.0, x[0], x[1]]);
                        vec![(plus[0] - minus[0]) / (2.0 * H), at0[1]]
                    },
                    &[near[1], near[2]],
                    &opts,
                )
                .ok()?;
                Some(vec![0.0, sol.x[0], sol.x[1]])
            }
        }
    }

    /// The stability verdict at `y` (a root).
    pub fn verdict(&mut self, y: &[f64]) -> Verdict {
        self.set(*y.last().expect("q"));
        let z = self.state(y);
        assess(&TwoModeLinearization::at(&mut self.solver, z), &z)
    }

    /// A root of the family at the parameter value `value`, by Newton from the reduced model's
    /// states and a few fixed seeds; `None` if the family has no state there (that Newton
    /// finds).
    pub fn root_at(&mut self, value: f64) -> Option<Vec<f64>> {
        if !self.set(self.q_of(value)) {
            return None;
        }
        let p = *self.solver.params();
        let coef = crate::reduced::coefficients::Coefficients::new(
            p.radius,
            crate::contract::settings::H0_PAPER,
        );
        match self.family {
            Family::IC => Some(self.y_of(0.0, 0.0, value)),
            Family::ID => {
                let seed = crate::roots::named_state::id_seed(&coef, &p);
                let st = self.solver.newton_on(self.mirror, 0.0, seed, 1e-12).ok()?;
                (st.a2.abs() > 1e-4 && st.a2.abs() < 0.9).then(|| self.y_of(0.0, st.a2, value))
            }
            Family::MdMinor | Family::MdMajor => {
                let sign = if self.family == Family::MdMinor {
                    -1.0
                } else {
                    1.0
                };
                let mut seeds = crate::roots::named_state::md_seeds(&coef, &p, sign);
                seeds.extend([0.6, 0.3, 0.9].map(|v| (v, sign * 0.27 * v / 0.6)));
                seeds.into_iter().find_map(|(v0, c0)| {
                    let st = self.solver.newton_on(self.mirror, v0, c0, 1e-12).ok()?;
                    (st.v > 1e-4 && st.a2 * sign > 0.0 && st.a2.abs() < 0.9)
                        .then(|| self.y_of(st.v, st.a2, value))
                })
            }
        }
    }
}
