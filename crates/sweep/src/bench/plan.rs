//! The plan of the work-precision benchmark: representative runs with the paper's FD scheme, the spectral
//! scheme at several `N` and `dt`, and the adaptive spectral scheme at several tolerances,
//! each timed and compared with a fine reference that is computed once and stored beside the
//! results (`reference.json`).
//!
//! Cases: the three Fig. 1 points (IC, ID, MD, from IC (i), run to the steady test), one point
//! in the IC/MD bistable band of Fig. 2(b) (class agreement is what counts there), and the
//! transient `t <= 20` through the MD instability (the time series is compared).
//! References: steady MD / ID states by Newton on the exact co-moving steady equations
//! ([`droplet_solver::roots::steady_solver::TwoModeSolver`]) at `n_newton`, seeded from a fine time integration that
//! also gives the reference class; IC states are exactly `v = s = 0`; the transient by the
//! spectral scheme at `n_ref` with a small fixed step.
use crate::bench::family::Family;
use droplet_solver::contract::ending::SteadyMethod;
use droplet_solver::{contract::settings::SolverSettings, stepping::SchemeKind};
use serde::{Deserialize, Serialize};

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

/// The methods of a profile: the paper's scheme, fixed spectral steps (N x dt), adaptive
/// steps (N x dt_max x tol) and the Newton finish (N x tol at the default step cap), each
/// from `base` (fixed steps, the paper's test).
fn methods(quick: bool, base: &SolverSettings) -> Vec<Method> {
    let base = *base;
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
    methods
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
        let methods = methods(quick, &base);
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

#[cfg(test)]
mod tests {
    use super::*;

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
