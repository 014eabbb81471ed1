//! `droplet bench`: the work-precision benchmark ([`droplet_sweep::bench`]).
use super::{print_json, CliError};
use droplet_sweep::bench::run::{run_benchmark, BenchOptions};
use std::path::PathBuf;

/// Time representative runs against their references: speed and the error it costs.
///
/// Time representative runs (the Fig. 1 IC, ID and MD points, a point in the IC/MD bistable
/// band, and the transient t <= 20 through the MD instability) with the paper's FD scheme,
/// the spectral scheme at N = 96..256 and dt = 0.005..0.1, and the adaptive scheme at several
/// tolerances, and measure each run's error against a fine reference (Newton on the exact
/// steady equations at N = 384 for steady states; spectral N = 256, dt = 0.001 for the time
/// series). The reference is computed once and kept in OUT/reference.json; later runs reuse it.
/// Writes OUT/bench.parquet (one row per run, diverged runs included), OUT/summary.json and
/// the log-log picture OUT/work_precision.png/.svg. The full profile takes about half an hour
/// on 2 cores; use --quick for a seconds-long miniature.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  droplet bench --quick --out /tmp/bench     # miniature, seconds\n  droplet bench --out results/bench --jobs 2  # the committed benchmark"
)]
pub struct Args {
    /// Output directory.
    #[arg(long, default_value = "out/bench")]
    out: PathBuf,
    /// The miniature profile (N = 32..64, short windows) for tests and a first look.
    #[arg(long)]
    quick: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
    /// Replace an existing OUT/bench.parquet.
    #[arg(long)]
    force: bool,
    /// Re-score the runs of OUT/bench.parquet against OUT/reference.json (recomputed when
    /// absent) without re-running them; rewrites the table, summary and picture.
    #[arg(long, conflicts_with = "force")]
    rescore: bool,
    /// Print one JSON object (keys: out, profile, rows, summary, reference_wall_s, wall_s, files).
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let report = run_benchmark(&BenchOptions {
        out: a.out.clone(),
        quick: a.quick,
        jobs: a.jobs,
        force: a.force,
        rescore: a.rescore,
        progress: !a.json,
    })?;
    let reused = report.reference_reused;
    let refs_wall = report.reference_wall_s;
    if a.json {
        print_json(&report);
        return Ok(());
    }
    outln!(
        "{} runs in {:.0} s (reference {}: {:.0} s)",
        report.rows,
        report.wall_s,
        if reused { "reused" } else { "computed" },
        refs_wall
    );
    if let Some(rate) = report.summary.paper_fd_s_per_time {
        outln!("paper-fd: {rate:.2} s of wall time per simulated time unit");
    }
    for d in report.summary.vs_paper_fd.iter().filter(|d| d.is_default) {
        outln!(
            "default on {:<11} err v {:.1e}  err s {:.1e}  class {}  {:.2} s{}",
            d.case,
            d.err_v,
            d.err_s,
            if d.class_ok { "ok" } else { "WRONG" },
            d.wall_s,
            d.speedup
                .map(|x| format!("  ({x:.0}x faster than paper-fd, extrapolated)"))
                .unwrap_or_default()
        );
    }
    for d in &report.summary.diverged {
        outln!("diverged: {d}");
    }
    for d in &report.summary.class_mismatches {
        outln!("class differs from the reference: {d}");
    }
    for f in &report.files {
        outln!("wrote {}", f.display());
    }
    Ok(())
}
