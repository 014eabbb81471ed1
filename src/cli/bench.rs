//! `droplet bench`: the work-precision benchmark ([`droplet_sweep::bench`]).
use super::{print_json, CliError};
use droplet_sweep::bench::{self, BenchPlan, BenchSummary, Profile, References};
use droplet_sweep::{precision_plot, tables};
use serde::Serialize;
use std::path::{Path, PathBuf};

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

#[derive(Serialize)]
struct Report {
    out: PathBuf,
    profile: Profile,
    rows: usize,
    summary: BenchSummary,
    reference_wall_s: f64,
    reference_reused: bool,
    wall_s: f64,
    files: Vec<PathBuf>,
}

/// `model name` of the first CPU and the core count, for the table's metadata.
fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{model}, {cores} cores")
}

fn load_or_compute(dir: &Path, plan: &BenchPlan) -> Result<(References, bool), CliError> {
    let path = dir.join("reference.json");
    if path.exists() {
        let text = std::fs::read_to_string(&path)
            .map_err(|e| CliError::usage(format!("{}: {e}", path.display())))?;
        let refs: References = serde_json::from_str(&text).map_err(|e| {
            CliError::usage(format!("{}: not a bench reference: {e}", path.display()))
        })?;
        if refs.plan != *plan {
            return Err(CliError::usage(format!(
                "{} was computed for another benchmark plan (profile or version); move it away or use another --out",
                path.display()
            )));
        }
        return Ok((refs, true));
    }
    let refs = bench::references(plan)?;
    droplet_sweep::atomic::write_atomic(
        &path,
        serde_json::to_string_pretty(&refs)
            .expect("json")
            .as_bytes(),
    )?;
    Ok((refs, false))
}

/// Every row as a Markdown table (the Parquet table's main columns), grouped by case.
fn markdown(rows: &[bench::BenchRow]) -> String {
    let mut out = String::from(
        "| case | method | dt | tol | status | class ok | err v | err s | err series | steps | rejected | wall s |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let e = |x: f64| format!("{x:.1e}");
    for r in rows {
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2} |\n",
            r.case,
            r.family,
            r.dt,
            r.tol,
            r.status,
            if r.class_ok { "yes" } else { "NO" },
            e(r.err_v),
            e(r.err_s),
            r.err_series.map_or("-".into(), e),
            r.steps,
            r.rejected,
            r.wall_s
        ));
    }
    out
}

pub fn run(a: Args) -> Result<(), CliError> {
    let started = std::time::Instant::now();
    let profile = if a.quick {
        Profile::Quick
    } else {
        Profile::Full
    };
    let plan = BenchPlan::new(profile);
    let table = a.out.join("bench.parquet");
    if a.rescore && !table.exists() {
        return Err(CliError::usage(format!(
            "--rescore: {} does not exist; run the benchmark first",
            table.display()
        )));
    }
    if table.exists() && !a.force && !a.rescore {
        return Err(CliError::usage(format!(
            "{} exists; pass --force to replace it, or use another --out",
            table.display()
        )));
    }
    std::fs::create_dir_all(&a.out)
        .map_err(|e| CliError::usage(format!("cannot create {}: {e}", a.out.display())))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.jobs.unwrap_or(0))
        .build()
        .map_err(|e| CliError::usage(format!("thread pool: {e}")))?;
    let (refs, reused, rows) = pool.install(|| -> Result<_, CliError> {
        let (refs, reused) = load_or_compute(&a.out, &plan)?;
        let rows = if a.rescore {
            let mut rows = tables::read_bench(&table)?;
            bench::rescore(&refs, &mut rows);
            rows
        } else {
            bench::run(&refs, !a.json)?
        };
        Ok((refs, reused, rows))
    })?;
    let summary = bench::summarise(&refs, &rows);
    let machine = machine();
    let mut meta = tables::metadata(None);
    if a.rescore {
        // Keep the provenance of the measurement; add the re-scoring's.
        let old = tables::read_metadata(&table)?;
        for k in ["machine", "command", "jobs", "git_commit"] {
            if let Some(v) = old.get(k) {
                meta.push((format!("measured_{k}"), v.clone()));
            }
        }
    }
    meta.push(("machine".into(), machine.clone()));
    meta.push((
        "command".into(),
        std::env::args().collect::<Vec<_>>().join(" "),
    ));
    meta.push(("jobs".into(), pool.current_num_threads().to_string()));
    meta.push(("plan".into(), serde_json::to_string(&plan).expect("json")));
    let mut df = tables::bench_frame(&rows)?;
    tables::write_parquet(&mut df, &table, meta)?;
    let md_path = a.out.join("bench.md");
    droplet_sweep::atomic::write_atomic(&md_path, markdown(&rows).as_bytes())?;
    let summary_path = a.out.join("summary.json");
    droplet_sweep::atomic::write_atomic(
        &summary_path,
        serde_json::to_string_pretty(&summary)
            .expect("json")
            .as_bytes(),
    )?;
    let title = format!(
        "Work-precision ({:?} profile; {}; commit {})",
        profile,
        machine,
        tables::GIT_COMMIT
    );
    let mut files = vec![table, md_path, summary_path, a.out.join("reference.json")];
    files.extend(precision_plot::work_precision(
        &a.out,
        "work_precision",
        &title,
        &rows,
    )?);
    let report = Report {
        out: a.out.clone(),
        profile,
        rows: rows.len(),
        summary,
        reference_wall_s: refs.wall_s,
        reference_reused: reused,
        wall_s: started.elapsed().as_secs_f64(),
        files,
    };
    if a.json {
        print_json(&report);
        return Ok(());
    }
    println!(
        "{} runs in {:.0} s (reference {}: {:.0} s)",
        report.rows,
        report.wall_s,
        if reused { "reused" } else { "computed" },
        refs.wall_s
    );
    if let Some(rate) = report.summary.paper_fd_s_per_time {
        println!("paper-fd: {rate:.2} s of wall time per simulated time unit");
    }
    for d in report.summary.vs_paper_fd.iter().filter(|d| d.is_default) {
        println!(
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
        println!("diverged: {d}");
    }
    for d in &report.summary.class_mismatches {
        println!("class differs from the reference: {d}");
    }
    for f in &report.files {
        println!("wrote {}", f.display());
    }
    Ok(())
}
