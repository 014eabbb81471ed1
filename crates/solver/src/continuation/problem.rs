//! One family of steady states on a mirror line of the box, as the zero set of the force
//! balance over `(unknowns, parameter)`, for the model with shape modes `2..K`: the map from
//! the continuation's scaled vector `y = (unknowns..., q)` (with `q` the varied parameter
//! mapped onto `[0, 1]` over the line) to the state `z = (vx, vy, a_2..a_K, b_2..b_K)` and the
//! balance's residual. The shape amplitudes are those in the line's own frame (the state is
//! mirror-symmetric about the line); a family holds only the modes its symmetry allows
//! ([`Family::free_modes`]), so that no symmetry-breaking branch point lies on its own curve:
//!
//! - IC: the modes the square box drives on a disk, multiples of 4 (none for `K < 4`: then
//!   `z = 0` is a root for every parameter).
//! - ID: the even modes (a resting droplet is point-symmetric), `v = 0`: their shape balances.
//! - MD moving along its minor axis (`a2 < 0`) or its major axis (`a2 > 0`): `v` and every
//!   mode, speed along the line: the balance along the motion and every shape balance.
//!
//! The balances are [`Balances`]: for `K = 2` the 2-mode fast path, whose unknowns are
//! `(c)` for ID and `(v, c)` for MD with `c` the mode-2 amplitude on the line.
use crate::model::mirror::MirrorLine;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::numerics::newton::{self, NewtonOptions};
use crate::roots::balances::Balances;
use crate::roots::steady_solver::TwoModeSolver;
use crate::roots::verdict::Verdict;
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

    /// The shape modes of `2..=k_max` the family's states hold on a mirror line, in the
    /// line's frame (the others vanish by symmetry): every one for MD; the even ones for ID
    /// (point-symmetric); the multiples of 4 for IC (the square box's quarter turns).
    pub fn free_modes(&self, k_max: usize) -> Vec<usize> {
        (2..=k_max)
            .filter(|k| match self {
                Self::IC => k % 4 == 0,
                Self::ID => k % 2 == 0,
                Self::MdMinor | Self::MdMajor => true,
            })
            .collect()
    }

    /// Whether the family's states move (their first unknown is the speed).
    pub fn moving(&self) -> bool {
        matches!(self, Self::MdMinor | Self::MdMajor)
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
    pub balances: Balances,
    pub family: Family,
    pub mirror: MirrorLine,
    pub parameter: ModelParam,
    /// Start of the line (`q = 0`).
    pub from: f64,
    /// `to - from` (`q = 1` at `to`).
    pub span: f64,
    /// [`Family::free_modes`] of the balances' `K`.
    free: Vec<usize>,
}

impl Problem {
    /// `family` on `mirror` with `balances` (their parameters the line's start, the varied
    /// one overwritten), `parameter` from `from` to `to`.
    pub fn new(
        balances: Balances,
        family: Family,
        mirror: MirrorLine,
        parameter: ModelParam,
        from: f64,
        to: f64,
    ) -> Self {
        Self {
            free: family.free_modes(balances.modes()),
            balances,
            family,
            mirror,
            parameter,
            from,
            span: to - from,
        }
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
        self.parameter.with(self.balances.params(), self.value(q))
    }

    /// Moves the balances to `q`; false where the parameters are invalid there (a geometric
    /// parameter beyond its range), where the residual is NaN and the corrector fails.
    fn set(&mut self, q: f64) -> bool {
        self.balances
            .set_param(self.parameter, self.value(q))
            .is_ok()
    }

    /// Speed along the line and the shape `a_2..a_K` in its frame at `y`.
    fn speed_and_modes(&self, y: &[f64]) -> (f64, Vec<f64>) {
        let unknowns = &y[..y.len() - 1];
        let (v, amplitudes) = if self.family.moving() {
            (unknowns[0], &unknowns[1..])
        } else {
            (0.0, unknowns)
        };
        let mut a = vec![0.0; self.balances.modes() - 1];
        for (k, x) in self.free.iter().zip(amplitudes) {
            a[k - 2] = *x;
        }
        (v, a)
    }

    /// Speed along the axis and the mode-2 amplitude on it at `y`.
    pub fn speed_and_shape(&self, y: &[f64]) -> (f64, f64) {
        let (v, a) = self.speed_and_modes(y);
        (v, a[0])
    }

    /// `z = (vx, vy, a_2..a_K, b_2..b_K)` at `y`.
    pub fn state(&self, y: &[f64]) -> Vec<f64> {
        let (v, a) = self.speed_and_modes(y);
        self.balances.on_mirror(self.mirror, v, &a)
    }

    /// `y` from the speed `v` and the shape `a = a_2..a_K` (the family's free modes of it)
    /// at the parameter value `value`.
    fn y_of(&self, v: f64, a: &[f64], value: f64) -> Vec<f64> {
        let speed = self.family.moving().then_some(v);
        speed
            .into_iter()
            .chain(self.free.iter().map(|k| a[k - 2]))
            .chain([self.q_of(value)])
            .collect()
    }

    /// The force balance at `y` (as many equations as unknowns).
    pub fn residual(&mut self, y: &[f64]) -> Vec<f64> {
        if !self.set(*y.last().expect("q")) {
            return vec![f64::NAN; y.len() - 1];
        }
        if self.free.is_empty() && !self.family.moving() {
            return Vec::new();
        }
        let (v, a) = self.speed_and_modes(y);
        let r = self.balances.residual_on(self.mirror, v, &a);
        let shape = self.free.iter().map(|k| r[k - 1]);
        if self.family.moving() {
            std::iter::once(r[0]).chain(shape).collect()
        } else {
            shape.collect()
        }
    }

    /// Where the branch through `near` (a root with small `v`, or small `a2` for ID) meets the
    /// family it bifurcates from, as a root of the bifurcation equations themselves: the
    /// balance along the motion is odd in `v` (odd in `a2` for ID's mode-2 balance, by the
    /// box's quarter-turn and mirror symmetries), so at the meeting point its derivative at
    /// `v = 0` vanishes together with the other equations. Newton on the other unknowns and
    /// `q`: exact where the arclength corrector is not (the two branches cross there).
    pub fn meeting(&mut self, near: &[f64]) -> Option<Vec<f64>> {
        const H: f64 = 1e-5;
        if self.family == Family::IC {
            return None;
        }
        let rest = near.len() - 1;
        // The general balances' sums in real space carry round-off of ~1e-15, which the
        // central difference of step `H` makes ~1e-10 in the slope; the 2-mode sums by
        // Parseval reach 1e-13.
        let tol = match self.balances {
            Balances::Two(_) => 1e-13,
            Balances::General(_) => 1e-10,
        };
        let opts = NewtonOptions {
            tol,
            max_iter: 30,
            fd_step: 1e-7,
            max_step: vec![0.05; rest.max(2)],
            one_sided: false,
            backtrack: false,
        };
        let sol = newton::solve(
            |x| {
                let mut at = |first: f64| {
                    let y: Vec<f64> = std::iter::once(first).chain(x.iter().copied()).collect();
                    self.residual(&y)
                };
                let (plus, minus) = (at(H), at(-H));
                let slope = (plus[0] - minus[0]) / (2.0 * H);
                if rest == 1 {
                    return vec![slope];
                }
                let at0 = at(0.0);
                std::iter::once(slope)
                    .chain(at0[1..].iter().copied())
                    .collect()
            },
            &near[1..],
            &opts,
        )
        .ok()?;
        Some(std::iter::once(0.0).chain(sol.x).collect())
    }

    /// The stability verdict at `y` (a root).
    pub fn verdict(&mut self, y: &[f64]) -> Verdict {
        self.set(*y.last().expect("q"));
        let z = self.state(y);
        self.balances.verdict(&z)
    }

    /// A root of the family at the parameter value `value`, by Newton from the reduced model's
    /// states and a few fixed seeds (with more modes from the 2-mode root, one mode added at a
    /// time); `None` if the family has no state there (that Newton finds).
    pub fn root_at(&mut self, value: f64) -> Option<Vec<f64>> {
        let q = self.q_of(value);
        if !self.set(q) {
            return None;
        }
        let (family, mirror) = (self.family, self.mirror);
        let guess = match &mut self.balances {
            Balances::Two(solver) => {
                let (v, c) = two_mode_root(solver, family, mirror)?;
                return Some(self.y_of(v, &[c], value));
            }
            Balances::General(solver) => {
                let k_max = solver.params().modes;
                let mut two = TwoModeSolver::new(*solver.params(), solver.n()).ok()?;
                solver.set_axis(mirror.angle());
                match family {
                    Family::IC => self.y_of(0.0, &vec![0.0; k_max - 1], value),
                    Family::ID => {
                        let (_, c) = two_mode_root(&mut two, family, mirror)?;
                        let a = crate::roots::named_state::id_state(solver, k_max, c)?;
                        self.y_of(0.0, &a, value)
                    }
                    Family::MdMinor | Family::MdMajor => {
                        let (v, c) = two_mode_root(&mut two, family, mirror)?;
                        let st =
                            crate::roots::named_state::md_state_from(solver, k_max, v, c).ok()?;
                        self.y_of(st.v, &st.a, value)
                    }
                }
            }
        };
        // Newton on the family's own balances at `q` from the guess.
        let n = guess.len() - 1;
        let opts = NewtonOptions {
            tol: 1e-12,
            max_iter: 40,
            fd_step: 1e-7,
            max_step: vec![0.2; n.max(1)],
            one_sided: false,
            backtrack: false,
        };
        let x = if n == 0 {
            Vec::new()
        } else {
            newton::solve(
                |x| {
                    let y: Vec<f64> = x.iter().copied().chain([q]).collect();
                    self.residual(&y)
                },
                &guess[..n],
                &opts,
            )
            .ok()?
            .x
        };
        let y: Vec<f64> = x.into_iter().chain([q]).collect();
        let (v, c) = self.speed_and_shape(&y);
        let sign = if family == Family::MdMajor { 1.0 } else { -1.0 };
        let found = match family {
            Family::IC => c.abs() < 1e-4,
            Family::ID => c.abs() > 1e-4 && c.abs() < 0.9,
            Family::MdMinor | Family::MdMajor => v > 1e-4 && c * sign > 0.0 && c.abs() < 0.9,
        };
        found.then_some(y)
    }
}

/// The 2-mode state of `family` on `mirror` at the solver's parameters, `(v, c)` with `c` the
/// mode-2 amplitude on the line: Newton from the reduced model's states and a few fixed seeds.
fn two_mode_root(
    solver: &mut TwoModeSolver,
    family: Family,
    mirror: MirrorLine,
) -> Option<(f64, f64)> {
    let p = *solver.params();
    let coef = crate::reduced::coefficients::Coefficients::new(
        p.radius,
        crate::contract::settings::H0_PAPER,
    );
    match family {
        Family::IC => Some((0.0, 0.0)),
        Family::ID => {
            let seed = crate::roots::named_state::id_seed(&coef, &p);
            let st = solver.newton_on(mirror, 0.0, seed, 1e-12).ok()?;
            (st.a2.abs() > 1e-4 && st.a2.abs() < 0.9).then_some((0.0, st.a2))
        }
        Family::MdMinor | Family::MdMajor => {
            let sign = if family == Family::MdMinor { -1.0 } else { 1.0 };
            let mut seeds = crate::roots::named_state::md_seeds(&coef, &p, sign);
            seeds.extend([0.6, 0.3, 0.9].map(|v| (v, sign * 0.27 * v / 0.6)));
            seeds.into_iter().find_map(|(v0, c0)| {
                let st = solver.newton_on(mirror, v0, c0, 1e-12).ok()?;
                (st.v > 1e-4 && st.a2 * sign > 0.0 && st.a2.abs() < 0.9).then_some((st.v, st.a2))
            })
        }
    }
}
