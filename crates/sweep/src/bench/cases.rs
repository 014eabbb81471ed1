//! Work-precision benchmark: representative runs with the paper's FD scheme, the spectral
//! scheme at several `N` and `dt`, and the adaptive spectral scheme at several tolerances,
//! each timed and compared with a fine reference that is computed once and stored beside the
//! results (`reference.json`).
//!
//! Cases: the three Fig. 1 points (IC, ID, MD, from IC (i), run to the steady test), one point
//! in the IC/MD bistable band of Fig. 2(b) (class agreement is what counts there), and the
//! transient `t <= 20` through the MD instability (the time series is compared).
//! References: steady MD / ID states by Newton on the exact co-moving steady equations
//! ([`droplet_solver::roots::steady_solver::SteadySolver`]) at `n_newton`, seeded from a fine time integration that
//! also gives the reference class; IC states are exactly `v = s = 0`; the transient by the
//! spectral scheme at `n_ref` with a small fixed step.
use crate::bench::family::Family;
use crate::error::SweepError;
use crate::execution::progress::progress_bar;
use droplet_solver::contract::ending::SteadyMethod;
use droplet_solver::roots::steady_solver::MirrorAxis;
use droplet_solver::{
    contract::outcome::RunOutcome, contract::outcome::RunStatus,
    contract::settings::SolverSettings, model::classify::StateClass,
    model::initial::InitialCondition, model::params::ModelParams,
    roots::steady_solver::SteadySolver, runs::driver::simulate, stepping::SchemeKind,
};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// One benchmark case.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Case {
    pub name: String,
    pub eta_t: f64,
    pub kappa2: f64,
    pub ic: String,
    /// `Some(t)`: a transient window compared as a time series; `None`: run to the steady test.
    pub window: Option<f64>,
}

/// One way of computing a case.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Method {
    /// Curve of the picture.
    pub family: Family,
    pub settings: SolverSettings,
}

/// How large a benchmark to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Profile {
    /// The committed benchmark (tens of minutes on 2 cores).
    Full,
    /// A seconds-long miniature with the same structure, for tests.
    Quick,
}

/// The fixed set of cases, methods and reference settings of a profile.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct BenchPlan {
    pub profile: Profile,
    pub cases: Vec<Case>,
    pub methods: Vec<Method>,
    /// Time integration giving the reference class and the Newton seed.
    pub reference_run: SolverSettings,
    /// Newton resolution of the reference steady states (quick: the reference run's own, so
    /// that the state the run found exists; a coarser run's ID state need not exist at a finer
    /// N near the threshold).
    pub n_newton: usize,
    /// Reference time series: resolution and step.
    pub transient_reference: SolverSettings,
    /// Sampling interval of the time series.
    pub every: f64,
}

fn case(name: &str, eta_t: f64, kappa2: f64, window: Option<f64>) -> Case {
    Case {
        name: name.into(),
        eta_t,
        kappa2,
        ic: "i".into(),
        window,
    }
}

impl BenchPlan {
    pub fn new(profile: Profile) -> Self {
        let quick = profile == Profile::Quick;
        let cases = vec![
            case("IC", 0.085, 0.120, None),
            case("ID", 0.085, 0.116, None),
            case("MD", 0.085, 0.112, None),
            case("IC/MD band", 0.0775, 0.130, None),
            case(
                "transient",
                0.085,
                0.112,
                Some(if quick { 5.0 } else { 20.0 }),
            ),
        ];
        let t_max = if quick { 400.0 } else { 2000.0 };
        // Fixed steps unless a method says otherwise, whatever the current defaults are (the
        // plan is stored with the references and must not change when the defaults do).
        let base = SolverSettings {
            t_max,
            tol: 0.0,
            dt_max: 1.0,
            steady: SteadyMethod::Test,
            ..SolverSettings::default()
        };
        // Fixed steps: N x dt; adaptive: N x dt_max x tol.
        let (ns, dts): (&[usize], &[f64]) = if quick {
            (&[32, 48], &[0.05, 0.1])
        } else {
            (&[96, 128, 192, 256], &[0.005, 0.01, 0.02, 0.05, 0.1])
        };
        let (adaptive_ns, dt_maxes): (&[usize], &[f64]) = if quick {
            (&[48], &[0.25])
        } else {
            (&[128, 192, 256], &[0.1, 0.25, 1.0])
        };
        let tols: &[f64] = if quick {
            &[1e-4, 1e-3]
        } else {
            &[1e-5, 1e-4, 1e-3]
        };
        let fd = SolverSettings {
            dt_max: base.dt_max,
            ..SolverSettings::paper_fd()
        };
        let mut methods = vec![Method {
            family: Family::PaperFd,
            settings: if quick {
                SolverSettings {
                    n: 48,
                    dt: 1e-3,
                    ..fd
                }
            } else {
                fd
            },
        }];
        for &n in ns {
            for &dt in dts {
                methods.push(Method {
                    family: Family::Spectral { n },
                    settings: SolverSettings { n, dt, ..base },
                });
            }
        }
        for &n in adaptive_ns {
            for &dt_max in dt_maxes {
                for &tol in tols {
                    methods.push(Method {
                        family: Family::Adaptive { n, dt_max },
                        settings: SolverSettings {
                            n,
                            tol,
                            dt_max,
                            ..base
                        },
                    });
                }
            }
        }
        // Adaptive steps finished by Newton (the default for sweeps), at the default step cap.
        let dt_max = droplet_solver::contract::settings::DEFAULT_DT_MAX;
        for &n in adaptive_ns {
            for &tol in tols {
                methods.push(Method {
                    family: Family::Newton { n, dt_max },
                    settings: SolverSettings {
                        n,
                        tol,
                        dt_max,
                        steady: SteadyMethod::Newton,
                        ..base
                    },
                });
            }
        }
        Self {
            profile,
            cases,
            methods,
            reference_run: SolverSettings {
                n: if quick { 64 } else { 256 },
                ..base
            },
            n_newton: if quick { 64 } else { 384 },
            transient_reference: SolverSettings {
                n: if quick { 64 } else { 256 },
                dt: if quick { 0.005 } else { 0.001 },
                ..base
            },
            every: 0.1,
        }
    }

    /// Which (case, method) pairs run. The paper's FD scheme runs the transient only (a
    /// steady run is ~1e7 of its steps; its per-run time is extrapolated from the transient's
    /// rate, see [`BenchSummary`]). Fixed steps below 0.02 run the transient only: a steady
    /// state is a fixed point of the scheme for every `dt`, so they would change only the time.
    /// The Newton finish runs the steady cases only: a transient window never stops early, so
    /// it would repeat the adaptive run of the same settings.
    pub fn jobs(&self) -> Vec<(usize, usize)> {
        let mut jobs = Vec::new();
        for (ci, c) in self.cases.iter().enumerate() {
            for (mi, m) in self.methods.iter().enumerate() {
                let s = &m.settings;
                let steady = c.window.is_none();
                let fd = s.scheme == SchemeKind::PaperFd;
                if steady && (fd || (!s.adaptive() && s.dt < 0.02)) {
                    continue;
                }
                if !steady && !s.steady.is_test() {
                    continue;
                }
                jobs.push((ci, mi));
            }
        }
        jobs
    }

    /// Whether `other`'s references serve this plan: the same cases and reference settings
    /// (the methods may differ; the references do not depend on them).
    pub fn same_references(&self, other: &BenchPlan) -> bool {
        self.profile == other.profile
            && self.cases == other.cases
            && self.reference_run == other.reference_run
            && self.n_newton == other.n_newton
            && self.transient_reference == other.transient_reference
            && self.every == other.every
    }
}

/// The reference of one case.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Reference {
    pub case: String,
    pub class: String,
    pub v: f64,
    pub s: f64,
    /// Time the reference run met the steady test (steady cases).
    pub t_steady: Option<f64>,
    /// `(t, v, s)` every `plan.every` (transient case).
    pub series: Vec<[f64; 3]>,
    /// How the values were obtained.
    pub how: String,
}

/// The stored references of a plan.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct References {
    pub plan: BenchPlan,
    pub cases: Vec<Reference>,
    pub wall_s: f64,
}

/// One measured (case, method) run.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct BenchRow {
    pub case: String,
    pub family: Family,
    pub scheme: String,
    pub n: usize,
    pub dt: f64,
    pub tol: f64,
    pub dt_max: f64,
    /// How the run decided it was steady: `test` or `newton`.
    pub steady: String,
    pub status: String,
    pub class: Option<String>,
    pub class_ok: bool,
    pub v: f64,
    pub s: f64,
    pub err_v: f64,
    pub err_s: f64,
    /// Max over the samples of `max(|v - v_ref|, |s - s_ref|)` (transient case).
    pub err_series: Option<f64>,
    pub t_end: f64,
    pub steps: u64,
    pub rejected: u64,
    pub max_step_error: Option<f64>,
    pub wall_s: f64,
}

impl BenchRow {
    /// The error drawn in the picture: series error for the transient, else max(err_v, err_s).
    pub fn error(&self) -> f64 {
        self.err_series.unwrap_or(self.err_v.max(self.err_s))
    }
}

fn params(c: &Case) -> ModelParams {
    ModelParams::at(c.eta_t, c.kappa2)
}

fn ic(c: &Case) -> Result<InitialCondition, SweepError> {
    Ok(InitialCondition::parse(&c.ic)?)
}

/// Runs `settings` on `c`, recording the series in a transient case.
fn run_case(c: &Case, settings: &SolverSettings, every: f64) -> Result<RunOutcome, SweepError> {
    let mut s = *settings;
    let p = params(c);
    let ic = ic(c)?;
    match c.window {
        Some(t) => {
            s.t_max = t;
            s.steady_tol = f64::MIN_POSITIVE; // never steady: the whole window
            Ok(droplet_solver::runs::driver::Run::new(&p, &ic, &s)?
                .record_every(Some(every))
                .execute())
        }
        None => Ok(simulate(&p, &ic, &s)?),
    }
}

fn series_of(out: &RunOutcome) -> Vec<[f64; 3]> {
    out.series.iter().map(|r| [r.t, r.v, r.s]).collect()
}

/// Computes the references of `plan` (minutes for the full profile), in parallel.
pub fn references(plan: &BenchPlan) -> Result<References, SweepError> {
    let started = Instant::now();
    let cases = plan
        .cases
        .par_iter()
        .map(|c| reference(plan, c))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(References {
        plan: plan.clone(),
        cases,
        wall_s: started.elapsed().as_secs_f64(),
    })
}

fn reference(plan: &BenchPlan, c: &Case) -> Result<Reference, SweepError> {
    if c.window.is_some() {
        let s = plan.transient_reference;
        let out = run_case(c, &s, plan.every)?;
        return Ok(Reference {
            case: c.name.clone(),
            class: out.class.map_or("-", |k| k.as_str()).into(),
            v: out.v,
            s: out.s,
            t_steady: None,
            series: series_of(&out),
            how: format!("spectral N = {}, fixed dt = {}", s.n, s.dt),
        });
    }
    let out = run_case(c, &plan.reference_run, plan.every)?;
    if out.status == RunStatus::Diverged
        || (out.status != RunStatus::Steady && plan.profile == Profile::Full)
    {
        return Err(SweepError::Invalid(format!(
            "bench reference for {} did not reach the steady test ({})",
            c.name,
            out.status.as_str()
        )));
    }
    let class = out.class.expect("runs that did not diverge have a class");
    let run_how = format!(
        "class from spectral N = {}, dt = {} ({} at t = {:.1})",
        plan.reference_run.n,
        plan.reference_run.dt,
        out.status.as_str(),
        out.t_end
    );
    let (v, s, how) = match class {
        StateClass::IC => (
            0.0,
            0.0,
            format!("{run_how}; resting disk v = s = 0 exactly"),
        ),
        StateClass::MD | StateClass::ID => {
            let mut newton = SteadySolver::new(params(c), plan.n_newton)?;
            let st = &out.state;
            // The box's mirror line nearest to the run's final orientation: its motion (MD)
            // or its long axis (ID). The periodic images make x and diagonal states differ.
            let diagonal = if class == StateClass::MD {
                let ang = st.vy.atan2(st.vx).rem_euclid(std::f64::consts::FRAC_PI_2);
                (ang - std::f64::consts::FRAC_PI_4).abs() < std::f64::consts::FRAC_PI_8
            } else {
                st.b2.abs() > st.a2.abs()
            };
            let axis = if diagonal {
                MirrorAxis::Diagonal
            } else {
                MirrorAxis::X
            };
            // Moving droplets are elongated across the motion (amplitude < 0 on the axis).
            let (v0, c0) = if class == StateClass::MD {
                (out.v, -out.s)
            } else {
                (0.0, out.s)
            };
            let sol = newton.newton_on(axis, v0, c0, 1e-12)?;
            (
                sol.v.abs(),
                sol.a2.abs(),
                format!(
                    "{run_how}; Newton on the exact steady equations on the {axis:?} mirror axis at N = {} (residual {:.1e})",
                    plan.n_newton, sol.residual
                ),
            )
        }
        StateClass::MC => (out.v, out.s, format!("{run_how}; its final state")),
    };
    Ok(Reference {
        case: c.name.clone(),
        class: class.as_str().into(),
        v,
        s,
        t_steady: out.t_steady,
        series: Vec::new(),
        how,
    })
}

/// Max over common sample times of `max(|v - v_ref|, |s - s_ref|)`.
fn series_error(series: &[[f64; 3]], reference: &[[f64; 3]], every: f64) -> f64 {
    let index = |t: f64| (t / every).round() as i64;
    let mut err: f64 = 0.0;
    let mut matched = 0;
    for r in series {
        if let Some(q) = reference.iter().find(|q| index(q[0]) == index(r[0])) {
            if (q[0] - r[0]).abs() < 1e-6 * every {
                err = err.max((r[1] - q[1]).abs()).max((r[2] - q[2]).abs());
                matched += 1;
            }
        }
    }
    if matched == 0 || matched < reference.len() {
        f64::NAN
    } else {
        err
    }
}

/// Runs every job of `refs.plan` (`jobs` threads), slowest first, with a progress bar.
pub fn run(refs: &References, progress: bool) -> Result<Vec<BenchRow>, SweepError> {
    let plan = &refs.plan;
    let mut jobs = plan.jobs();
    // Cost estimate: steps x N^2 (adaptive runs: a few thousand steps).
    let cost = |&(ci, mi): &(usize, usize)| {
        let s = &plan.methods[mi].settings;
        let t = plan.cases[ci].window.unwrap_or(1000.0);
        let steps = if s.adaptive() {
            t / s.dt_max.min(0.5) + 500.0
        } else {
            t / s.dt
        };
        steps * (s.n * s.n) as f64
    };
    jobs.sort_by(|a, b| cost(b).total_cmp(&cost(a)));
    let bar = progress_bar(jobs.len() as u64, 0, progress, "bench runs");
    let rows = jobs
        .par_iter()
        .map(|&(ci, mi)| {
            let (c, m) = (&plan.cases[ci], &plan.methods[mi]);
            let r = &refs.cases[ci];
            let out = run_case(c, &m.settings, plan.every)?;
            bar.inc(1);
            bar.set_message(format!("{} {}", c.name, m.family));
            let s = &m.settings;
            let mut row = BenchRow {
                case: c.name.clone(),
                family: m.family,
                scheme: s.scheme.as_str().into(),
                n: s.n,
                dt: s.dt,
                tol: s.tol,
                dt_max: s.dt_max,
                steady: s.steady.as_str().into(),
                status: out.status.as_str().into(),
                class: out.class.map(|k| k.as_str().to_string()),
                class_ok: false,
                v: out.v,
                s: out.s,
                err_v: f64::NAN,
                err_s: f64::NAN,
                err_series: c
                    .window
                    .map(|_| series_error(&series_of(&out), &r.series, plan.every)),
                t_end: out.t_end,
                steps: out.steps,
                rejected: out.rejected,
                max_step_error: out.max_step_error,
                wall_s: out.wall_s,
            };
            score(&mut row, r);
            Ok(row)
        })
        .collect::<Result<Vec<_>, SweepError>>()?;
    bar.finish_and_clear();
    let mut rows = rows;
    rows.sort_by(|a, b| {
        (a.case.as_str(), a.family.to_string(), a.dt, a.tol)
            .partial_cmp(&(b.case.as_str(), b.family.to_string(), b.dt, b.tol))
            .expect("finite settings")
    });
    Ok(rows)
}

/// A row's final-state errors and class agreement against its case's reference.
fn score(row: &mut BenchRow, reference: &Reference) {
    row.err_v = (row.v - reference.v).abs();
    row.err_s = (row.s - reference.s).abs();
    row.class_ok = row.class.as_deref() == Some(reference.class.as_str());
}

/// Recomputes the errors and class agreement of measured `rows` against `refs` (after a
/// better reference), without re-running them. Series errors are kept (the series are not
/// stored).
pub fn rescore(refs: &References, rows: &mut [BenchRow]) {
    for r in rows.iter_mut() {
        if let Some(c) = refs.cases.iter().find(|c| c.case == r.case) {
            score(r, c);
        }
    }
}

/// The headline numbers: the default settings against the paper's scheme.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct BenchSummary {
    /// The paper's FD scheme: measured wall seconds per simulated time unit (transient run).
    pub paper_fd_s_per_time: Option<f64>,
    /// Per steady case and N = 192 method: errors and the ratio to the paper's scheme's
    /// extrapolated run time (its measured rate x the reference's time to steady).
    pub vs_paper_fd: Vec<VsPaperFd>,
    /// Runs that diverged: `case / family / dt / tol`.
    pub diverged: Vec<String>,
    /// Runs whose class differs from the reference's.
    pub class_mismatches: Vec<String>,
}

/// One N = 192 method on one steady case.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct VsPaperFd {
    pub case: String,
    pub family: Family,
    pub dt: f64,
    pub tol: f64,
    /// These are [`SolverSettings::default`]'s numerics.
    pub is_default: bool,
    pub err_v: f64,
    pub err_s: f64,
    pub class_ok: bool,
    pub wall_s: f64,
    pub paper_fd_est_s: Option<f64>,
    pub speedup: Option<f64>,
}

fn describe(r: &BenchRow) -> String {
    format!("{} / {} / dt {} / tol {}", r.case, r.family, r.dt, r.tol)
}

/// Summarises `rows`.
pub fn summarise(refs: &References, rows: &[BenchRow]) -> BenchSummary {
    let d = SolverSettings::default();
    let fd_rate = rows
        .iter()
        .find(|r| {
            r.scheme == "paper-fd" && r.status != RunStatus::Diverged.as_str() && r.t_end > 0.0
        })
        .map(|r| r.wall_s / r.t_end);
    let vs_paper_fd = rows
        .iter()
        .filter(|r| r.err_series.is_none() && r.scheme == "spectral" && r.n == d.n)
        .map(|r| {
            let t_ref = refs
                .cases
                .iter()
                .find(|c| c.case == r.case)
                .and_then(|c| c.t_steady);
            let est = fd_rate.zip(t_ref).map(|(rate, t)| rate * t);
            VsPaperFd {
                case: r.case.clone(),
                family: r.family,
                dt: r.dt,
                tol: r.tol,
                is_default: r.dt == d.dt
                    && r.tol == d.tol
                    && (d.tol == 0.0 || r.dt_max == d.dt_max)
                    && r.steady == d.steady.as_str(),
                err_v: r.err_v,
                err_s: r.err_s,
                class_ok: r.class_ok,
                wall_s: r.wall_s,
                paper_fd_est_s: est,
                speedup: est.map(|e| e / r.wall_s),
            }
        })
        .collect();
    BenchSummary {
        paper_fd_s_per_time: fd_rate,
        vs_paper_fd,
        diverged: rows
            .iter()
            .filter(|r| r.status == RunStatus::Diverged.as_str())
            .map(describe)
            .collect(),
        class_mismatches: rows
            .iter()
            .filter(|r| r.status != RunStatus::Diverged.as_str() && !r.class_ok)
            .map(describe)
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_error_compares_matching_sample_times() {
        let r = vec![[0.0, 1.0, 0.1], [0.1, 1.0, 0.2], [0.2, 1.0, 0.3]];
        let s = vec![[0.0, 1.0, 0.1], [0.1, 1.5, 0.2], [0.2, 1.0, 0.25]];
        assert!((series_error(&s, &r, 0.1) - 0.5).abs() < 1e-15);
        // Missing samples are an error, not a silent match on fewer points.
        assert!(series_error(&s[..1], &r, 0.1).is_nan());
    }

    #[test]
    fn plans_skip_only_what_is_documented() {
        let p = BenchPlan::new(Profile::Full);
        let jobs = p.jobs();
        // The paper's scheme runs the transient only.
        let fd: Vec<_> = jobs
            .iter()
            .filter(|(_, m)| p.methods[*m].family == Family::PaperFd)
            .collect();
        assert_eq!(fd.len(), 1);
        assert!(p.cases[fd[0].0].window.is_some());
        // Every method runs the transient but the Newton finish, which runs every steady case.
        let transient = p.cases.iter().position(|c| c.window.is_some()).unwrap();
        let newton: Vec<usize> = (0..p.methods.len())
            .filter(|&m| p.methods[m].settings.steady == SteadyMethod::Newton)
            .collect();
        assert!(!newton.is_empty());
        assert_eq!(
            jobs.iter().filter(|(c, _)| *c == transient).count(),
            p.methods.len() - newton.len()
        );
        for m in newton {
            assert_eq!(
                jobs.iter().filter(|(_, j)| *j == m).count(),
                p.cases.len() - 1
            );
        }
    }
}
