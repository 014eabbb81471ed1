//! The MD branch of the `K`-mode model followed along a whole line, every state with its
//! stability (`droplet continue --modes K`): pseudo-arclength continuation of
//! `(v, a_2..a_K, q)` on the x axis as in [`crate::continuation::mode_branch`], on past its
//! folds, and the `2K x 2K` eigenproblem ([`crate::roots::linearisation`]) at every
//! state, the rotation mode set aside.
//!
//! Two independent views of the same fold, checked against each other in the tests: the
//! tangent's `q` component changes sign there (the continuation), and one real eigenvalue
//! crosses zero there (the stability).
use crate::continuation::arclength::{start, ArclengthOptions, Stepper};
use crate::continuation::mode_branch::{fold_point, ModeLine};
use crate::error::SolverError;
use crate::roots::linearisation::Linearization;
use crate::roots::named_state::md_state;
use crate::roots::steady_solver::SteadySolver;
use crate::roots::verdict::Verdict;

/// One state of the branch.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeBranchPoint {
    /// The varied parameter's value.
    pub at: f64,
    pub eta_t: f64,
    pub kappa2: f64,
    /// Speed along +x.
    pub v: f64,
    /// `a_k` for `k = 2..=K` (`b_k = 0` on the x axis).
    pub a: Vec<f64>,
    /// Its stability, the rotation mode set aside.
    pub verdict: Verdict,
    /// A fold of the branch (a saddle-node in the varied parameter).
    pub fold: bool,
}

impl ModeBranchPoint {
    /// The `2K` unknowns `(vx, vy, a_2..a_K, b_2..b_K)` of the state.
    pub fn z(&self) -> Vec<f64> {
        crate::roots::steady_solver::on_x_axis(self.v, &self.a)
    }
}

/// Why the branch ends where it does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ModeBranchEnd {
    /// The varied parameter left the line.
    LineEnd,
    /// The speed fell to 1e-3: the branch meets a resting state (its drift pitchfork).
    AtRest,
    /// No continuation step converged.
    Stalled,
    /// `max_points` states.
    MaxPoints,
}

/// The branch: its states in order along it (folds included, flagged) and why it ends.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeBranch {
    pub k_max: usize,
    /// The friction law's exponent the verdicts were computed with
    /// ([`crate::model::friction`]).
    pub eta_k_exponent: f64,
    pub points: Vec<ModeBranchPoint>,
    pub end: ModeBranchEnd,
}

impl ModeBranch {
    /// The folds, in order along the branch.
    pub fn folds(&self) -> impl Iterator<Item = &ModeBranchPoint> {
        self.points.iter().filter(|p| p.fold)
    }
}

/// Speed below which the branch is taken to have met a resting state.
const AT_REST: f64 = 1e-3;

/// The states `(v, a_2..a_K, q)` walked along `line` (with their fold flags) and the
/// stability of each.
fn with_stability(
    solver: &mut SteadySolver,
    line: &ModeLine,
    walked: Vec<(Vec<f64>, bool)>,
) -> Vec<ModeBranchPoint> {
    let span = line.to - line.from;
    walked
        .into_iter()
        .map(|(y, fold)| {
            let k = y.len() - 1;
            let at = line.from + y[k] * span;
            let p = line.parameter.with(&line.base, at);
            solver.set_control(p.eta_t, p.kappa2);
            let mut point = ModeBranchPoint {
                at,
                eta_t: p.eta_t,
                kappa2: p.kappa2,
                v: y[0],
                a: y[1..k].to_vec(),
                verdict: Verdict {
                    eigenvalues: Vec::new(),
                    rotation: None,
                    unstable: 0,
                    max_re: -1.0,
                },
                fold,
            };
            point.verdict = Linearization::at(solver, &point.z()).verdict();
            point
        })
        .collect()
}

/// Follows the MD branch from [`md_state`] at `line.from` towards `line.to`, through its folds,
/// until it leaves the line, meets rest, stalls or has `max_points` states; then the
/// stability of every state.
pub fn follow_md(
    line: &ModeLine,
    max_points: usize,
    opts: &ArclengthOptions,
) -> Result<ModeBranch, SolverError> {
    let mut solver = SteadySolver::new(line.base, line.n)?;
    solver.set_eta_k_exponent(line.eta_k_exponent);
    let st = md_state(&mut solver, line.k_max)?;
    let span = line.to - line.from;
    let (base, parameter) = (line.base, line.parameter);
    let y0: Vec<f64> = std::iter::once(st.v)
        .chain(st.a.iter().copied())
        .chain([0.0])
        .collect();
    // (y, is a fold) along the branch.
    let mut walked: Vec<(Vec<f64>, bool)> = vec![(y0.clone(), false)];
    let end = {
        let mut f = |y: &[f64]| {
            let q = *y.last().expect("q");
            let p = parameter.with(&base, line.from + q * span);
            solver.set_control(p.eta_t, p.kappa2);
            solver.residual_x(&y[..y.len() - 1])
        };
        let mut prev = vec![0.0; y0.len()];
        *prev.last_mut().expect("q") = 1.0;
        match start(&mut f, &y0, &prev, opts) {
            None => ModeBranchEnd::Stalled,
            Some(mut p) => {
                let q_of = |t: &[f64]| *t.last().expect("q");
                let mut stepper = Stepper::new(opts.clone());
                loop {
                    if walked.len() >= max_points {
                        break ModeBranchEnd::MaxPoints;
                    }
                    let Some(step) = stepper.advance(&mut f, &p) else {
                        break ModeBranchEnd::Stalled;
                    };
                    let y = &step.point.y;
                    if !(0.0..=1.0).contains(&q_of(y)) {
                        break ModeBranchEnd::LineEnd;
                    }
                    if y[0] < AT_REST {
                        break ModeBranchEnd::AtRest;
                    }
                    if q_of(&step.point.tangent) * q_of(&p.tangent) < 0.0 {
                        walked.push((fold_point(&mut f, &p, &step, opts).y, true));
                    }
                    walked.push((y.clone(), false));
                    p = step.point;
                }
            }
        }
    };
    let points = with_stability(&mut solver, line, walked);
    Ok(ModeBranch {
        k_max: line.k_max,
        eta_k_exponent: line.eta_k_exponent,
        points,
        end,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuation::mode_branch::md_fold;
    use crate::model::param::ModelParam;
    use crate::model::params::ModelParams;

    fn band_line(k_max: usize) -> ModeLine {
        ModeLine {
            base: ModelParams::at(0.077, 0.13),
            n: 64,
            k_max,
            parameter: ModelParam::EtaT,
            from: 0.077,
            to: 0.1,
            eta_k_exponent: 0.0,
        }
    }

    #[test]
    fn the_fold_is_where_the_branch_loses_its_stability() {
        // kappa2 = 0.13 with modes 2..3 at N = 64: the upper MD branch is stable up to its fold,
        // the lower one (towards rest) unstable; the fold is md_fold's, and the real eigenvalue
        // that decides stability passes through zero there (9.5e-11 at N = 96).
        let line = band_line(3);
        let opts = ArclengthOptions {
            ds_max: 0.03,
            ..ArclengthOptions::default()
        };
        let branch = follow_md(&line, 30, &opts).unwrap();
        let folds: Vec<_> = branch.folds().collect();
        assert_eq!(folds.len(), 1, "{:?}", branch.end);
        assert!(branch.points.iter().position(|p| p.fold).unwrap() < 25);
        let fold = folds[0];
        let alone = md_fold(&line).unwrap().expect("a fold");
        assert!(
            (fold.at - alone.at).abs() < 1e-9,
            "{} {}",
            fold.at,
            alone.at
        );
        let i = branch.points.iter().position(|p| p.fold).unwrap();
        assert!(branch.points[..i].iter().all(|p| p.verdict.stable()));
        assert!(branch.points[i + 1..].iter().all(|p| !p.verdict.stable()));
        // Through the fold one real eigenvalue changes sign: near zero at the fold.
        let near_zero = fold
            .verdict
            .eigenvalues
            .iter()
            .filter(|l| l[1].abs() < 1e-9 && Some(l[0]) != fold.verdict.rotation)
            .map(|l| l[0].abs())
            .fold(f64::INFINITY, f64::min);
        assert!(near_zero < 1e-4, "{:?}", fold.verdict);
        // The lower branch runs towards rest, slower than the fold.
        assert!(branch.points.last().unwrap().v < fold.v);
        // It turns back past the line's start (the lower branch reaches rest at 0.0765).
        assert_eq!(branch.end, ModeBranchEnd::LineEnd);
    }
}
