//! `droplet sweep`: every (point, initial condition) run of a YAML spec, resumable.
use super::{print_json, CliError};
use droplet_sweep::store::shard::Shard;
use droplet_sweep::{execution::execute::run_sweep, execution::execute::SweepOptions, spec};
use std::path::PathBuf;

/// Run a sweep from a YAML spec: every point from every initial condition, resumable.
///
/// Run a sweep from a YAML spec over one to three of its parameters (the paper's (eta_t,
/// kappa2), or any of eta_t, kappa2, eta2, mass, radius, sigma, box_len, n, tol, dt_max,
/// t_max): every point from every initial condition, in parallel. Finished runs are stored at once under OUT/runs/, so re-running the
/// same command after an interruption continues where it stopped; then writes
/// OUT/runs.parquet, OUT/points.parquet and OUT/phase_map.png (+ .svg).
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  droplet sweep sweeps/smoke.yaml                 # CI smoke sweep, ~8 s on 2 cores\n  droplet sweep sweeps/fig2a.yaml                 # the paper's Fig. 2(a) grid, 377 points (check the rate: droplet status)\n  droplet sweep sweeps/fig2a-map.yaml             # refined where the class changes (docs/sweeps.md)\n  droplet sweep sweeps/smoke.yaml --out /tmp/s    # same spec, another directory\n  droplet sweep sweeps/mass-eta_t.yaml            # the inertia against eta_t (any parameter on an axis)\n\nSpec keys: name, output, model (pde | ode), params {eta_t, kappa2, eta2, radius, sigma, box_len,\nmass (those not swept), modes (K: shape modes 2..K, default 2), eta_k_exponent}, grid {1-3 axes: any of those or n, tol, dt_max, t_max; each\n{start, stop, step} or a list; a third axis gives one map per value}, initial_conditions, solver {scheme,\nn, dt, tol, dt_max, t_max, steady_tol, steady_window, steady, landing, run_on, h0, ...},\nrefine {levels, min_step, split_bistable, certify_midpoints}. See sweeps/*.yaml and docs/sweeps.md.\n\nSharded: each shard runs `--shard I/N` into the same OUT, then `droplet merge OUT`; a spec with\nrefine: is sharded level by level (`--shard I/N --level L`, L = 0, 1, ... in order).\n\nA stored run that cannot be used (truncated, not a record, or not matching its key) is moved to\nOUT/corrupt/ with a warning and recomputed. Exit codes: 0 done, 1 failure while working, 2 bad\ninput (spec, arguments, output directory, a sweep already running there)."
)]
pub struct Args {
    /// The YAML spec.
    spec: PathBuf,
    /// Output directory (overrides the spec's `output`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
    /// Do not draw the phase map at the end.
    #[arg(long)]
    no_plot: bool,
    /// Run only slice I of N (0 <= I < N), balanced by expected cost, into the same DIR as the
    /// other shards; no tables are written (run `droplet merge DIR` after all shards).
    /// Defaults from SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT when both are set.
    #[arg(long, value_name = "I/N")]
    shard: Option<String>,
    /// With --shard, for a spec with `refine:`: run level L's slice (0 = the spec's grid). The
    /// levels below L must be finished, since L's points follow from their classes; run the
    /// levels in order (one Slurm array each: `droplet slurm` does that), then `droplet merge`.
    #[arg(long, value_name = "L")]
    level: Option<u32>,
    /// Refuse specs with more runs than this (points x initial conditions), checked before
    /// anything is written. Raise it deliberately for very large sweeps.
    #[arg(long, value_name = "RUNS", default_value_t = droplet_sweep::store::plan::DEFAULT_MAX_RUNS)]
    max_runs: u64,
    /// Print a JSON summary instead of text (keys: name, output, points, runs, shard, level,
    /// computed, reused, certified (runs certified without stepping, refine.certify_midpoints;
    /// among computed), certify_refused (points left to their runs, by reason), corrupt,
    /// upgraded, wall_s, jobs, point_classes, run_statuses, dt_warnings, run_time_s and profile (the computed runs' time and its parts:
    /// stepping_s, newton_s, eigen_s, landing_s, flow_s, leap_s, diagnosis_s, newton_solves,
    /// eigen_problems, field_solves, fields), tables).
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let spec = spec::load(&a.spec)?;
    if a.jobs == Some(0) {
        return Err(CliError::usage("invalid --jobs 0: at least 1"));
    }
    let out = a.out.clone().unwrap_or_else(|| spec.output.clone());
    let shard = match &a.shard {
        Some(text) => Some(Shard::parse(text).map_err(CliError::usage)?),
        None => Shard::from_slurm_env()
            .transpose()
            .map_err(|e| CliError::usage(format!("from SLURM_ARRAY_TASK_ID/COUNT: {e}")))?,
    };
    let opts = SweepOptions {
        jobs: a.jobs,
        progress: !a.json,
        shard,
        level: a.level,
        plot: !a.no_plot,
        max_runs: Some(a.max_runs),
    };
    let summary = run_sweep(&spec, &out, &opts)?;
    if summary.upgraded > 0 {
        errln!(
            "note: {} stored runs of an earlier release were upgraded in place, not recomputed \
             (sealed with the digest of their outcome, or re-keyed: their keys held settings \
             the runs do not read, such as a PDE run's h0)",
            summary.upgraded
        );
    }
    for c in &summary.corrupt {
        errln!(
            "warning: stored run {} could not be used ({}); moved to {} and recomputed",
            c.key,
            c.reason,
            c.moved_to.display()
        );
    }
    if a.json {
        print_json(&summary);
    } else {
        print_text(&summary);
    }
    Ok(())
}

/// The sweep's summary as text: counts, point classes, certified runs, run time, warnings and
/// the files written.
fn print_text(summary: &droplet_sweep::execution::execute::SweepSummary) {
    outln!(
        "{}: {} points, {} runs ({} computed, {} reused, {} corrupt recomputed) in {:.1} s on {} threads",
        summary.name,
        summary.points,
        summary.runs,
        summary.computed,
        summary.reused,
        summary.corrupt.len(),
        summary.wall_s,
        summary.jobs
    );
    let classes: Vec<String> = summary
        .point_classes
        .iter()
        .map(|(k, v)| format!("{k}: {v}"))
        .collect();
    outln!("point classes: {}", classes.join(", "));
    if summary.certified > 0 || !summary.certify_refused.is_empty() {
        let refused: Vec<String> = summary
            .certify_refused
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect();
        outln!(
            "{} of the computed runs certified without stepping (refine.certify_midpoints; ended_by certified_midway in runs.parquet); points left to their runs: {}",
            summary.certified,
            if refused.is_empty() { "none".to_string() } else { refused.join(", ") }
        );
    }
    if summary.computed > 0 {
        outln!("{}", run_time_line(summary));
    }
    if summary.dt_warnings > 0 {
        errln!(
            "warning: {} fixed-step runs took steps too large to trust (column max_step_error > {:e} in runs.parquet); lower dt or use adaptive stepping (solver.tol)",
            summary.dt_warnings,
            droplet_solver::contract::outcome::STEP_ERROR_LIMIT
        );
    }
    for p in &summary.tables {
        outln!("wrote {}", p.display());
    }
}

/// The computed runs' time and its parts in one line (docs/performance.md).
fn run_time_line(s: &droplet_sweep::execution::execute::SweepSummary) -> String {
    let p = &s.profile;
    let t = s.run_time_s.max(1e-300);
    let pct = |x: f64| 100.0 * x / t;
    let other = (s.run_time_s - p.total_s()).max(0.0) + p.leap_s + p.diagnosis_s;
    format!(
        "run time {:.1} s over {} runs: stepping {:.0} %, Newton {:.0} %, eigenvalues {:.0} %, \
         landing {:.0} %, orientation flow {:.0} %, other {:.0} %; {} steady field solves",
        s.run_time_s,
        s.computed,
        pct(p.stepping_s),
        pct(p.newton_s),
        pct(p.eigen_s),
        pct(p.landing_s),
        pct(p.flow_s),
        pct(other),
        p.field_solves
    )
}
