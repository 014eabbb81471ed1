//! The timed rows of the benchmark and their scores against the references: one row per
//! (case, method) run, its errors and class agreement, and the summary (the default settings
//! against the paper's scheme).
use crate::bench::family::Family;
use crate::bench::references::{run_case, series_error, series_of};
use crate::bench::references::{Reference, References};
use crate::error::SweepError;
use crate::execution::progress::progress_bar;
use droplet_solver::{contract::outcome::RunStatus, contract::settings::SolverSettings};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

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
