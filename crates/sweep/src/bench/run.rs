//! A whole benchmark run ([`crate::bench`]) from start to files: the references (computed
//! once, then reused), the timed rows in a thread pool (or re-scored), and the outputs.
use crate::bench::plan::{BenchPlan, Profile};
use crate::bench::references::{references, References};
use crate::bench::scoring::{rescore, run, summarise, BenchSummary};
use crate::bench::{precision_plot, table};
use crate::error::SweepError;
use crate::tables::sweep_tables;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// What to run.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    pub out: PathBuf,
    pub quick: bool,
    /// Worker threads (`None`: all cores).
    pub jobs: Option<usize>,
    /// Replace an existing table.
    pub force: bool,
    /// Re-score the stored rows instead of running them.
    pub rescore: bool,
    /// Show a progress bar.
    pub progress: bool,
}

/// What a benchmark run did.
#[derive(Debug, Clone, Serialize)]
pub struct BenchReport {
    pub out: PathBuf,
    pub profile: Profile,
    pub rows: usize,
    pub summary: BenchSummary,
    pub reference_wall_s: f64,
    pub reference_reused: bool,
    pub wall_s: f64,
    pub files: Vec<PathBuf>,
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

fn load_or_compute(dir: &Path, plan: &BenchPlan) -> Result<(References, bool), SweepError> {
    let path = dir.join("reference.json");
    if path.exists() {
        let text = std::fs::read_to_string(&path)
            .map_err(|e| SweepError::Invalid(format!("{}: {e}", path.display())))?;
        let refs: References = serde_json::from_str(&text).map_err(|e| {
            SweepError::Invalid(format!("{}: not a bench reference: {e}", path.display()))
        })?;
        if !refs.plan.same_references(plan) {
            return Err(SweepError::Invalid(format!(
                "{} was computed for another benchmark plan (profile, cases or reference settings); move it away or use another --out",
                path.display()
            )));
        }
        // Only the methods changed: the references stand; record the plan they now serve.
        let mut refs = refs;
        if refs.plan != *plan {
            refs.plan = plan.clone();
            store_references(&path, &refs)?;
        }
        return Ok((refs, true));
    }
    let refs = references(plan)?;
    store_references(&path, &refs)?;
    Ok((refs, false))
}

fn store_references(path: &Path, refs: &References) -> Result<(), SweepError> {
    crate::store::atomic::write_atomic(
        path,
        serde_json::to_string_pretty(refs).expect("json").as_bytes(),
    )
    .map(drop)
}

/// Every row as a Markdown table (the Parquet table's main columns), grouped by case.
fn markdown(rows: &[crate::bench::scoring::BenchRow]) -> String {
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

/// The benchmark table's metadata: the machine, the command, the threads and the plan; on a
/// re-scoring, also those of the measurement it re-scores.
fn table_metadata(
    a: &BenchOptions,
    table: &Path,
    plan: &BenchPlan,
    machine: &str,
    jobs: usize,
) -> Result<Vec<(String, String)>, SweepError> {
    let mut meta = sweep_tables::metadata(None);
    if a.rescore {
        // Keep the provenance of the measurement; add the re-scoring's.
        let old = sweep_tables::read_metadata(table)?;
        for k in ["machine", "command", "jobs", "git_commit"] {
            if let Some(v) = old.get(k) {
                meta.push((format!("measured_{k}"), v.clone()));
            }
        }
    }
    meta.push(("machine".into(), machine.to_string()));
    meta.push((
        "command".into(),
        std::env::args().collect::<Vec<_>>().join(" "),
    ));
    meta.push(("jobs".into(), jobs.to_string()));
    meta.push(("plan".into(), serde_json::to_string(plan).expect("json")));
    Ok(meta)
}

/// Runs (or with `rescore`, re-scores) the benchmark into `opts.out`: references loaded or
/// computed once, the rows in a pool of `opts.jobs` threads, then `bench.parquet`, `bench.md`,
/// `summary.json` and the work-precision picture.
pub fn run_benchmark(a: &BenchOptions) -> Result<BenchReport, SweepError> {
    let started = std::time::Instant::now();
    let profile = if a.quick {
        Profile::Quick
    } else {
        Profile::Full
    };
    let plan = BenchPlan::new(profile);
    let table = a.out.join("bench.parquet");
    if a.rescore && !table.exists() {
        return Err(SweepError::Invalid(format!(
            "--rescore: {} does not exist; run the benchmark first",
            table.display()
        )));
    }
    if table.exists() && !a.force && !a.rescore {
        return Err(SweepError::Invalid(format!(
            "{} exists; pass --force to replace it, or use another --out",
            table.display()
        )));
    }
    crate::store::atomic::create_output_dir(&a.out)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.jobs.unwrap_or(0))
        .build()
        .map_err(|e| SweepError::Invalid(format!("thread pool: {e}")))?;
    let (refs, reused, rows) = pool.install(|| -> Result<_, SweepError> {
        let (refs, reused) = load_or_compute(&a.out, &plan)?;
        let rows = if a.rescore {
            let mut rows = table::read_bench(&table)?;
            rescore(&refs, &mut rows);
            rows
        } else {
            run(&refs, a.progress)?
        };
        Ok((refs, reused, rows))
    })?;
    let summary = summarise(&refs, &rows);
    let machine = machine();
    let meta = table_metadata(a, &table, &plan, &machine, pool.current_num_threads())?;
    let mut df = table::bench_frame(&rows)?;
    sweep_tables::write_parquet(&mut df, &table, meta)?;
    let md_path = a.out.join("bench.md");
    crate::store::atomic::write_atomic(&md_path, markdown(&rows).as_bytes())?;
    let summary_path = a.out.join("summary.json");
    crate::store::atomic::write_atomic(
        &summary_path,
        serde_json::to_string_pretty(&summary)
            .expect("json")
            .as_bytes(),
    )?;
    let title = format!(
        "Work-precision ({:?} profile; {}; commit {})",
        profile,
        machine,
        sweep_tables::GIT_COMMIT
    );
    let mut files = vec![table, md_path, summary_path, a.out.join("reference.json")];
    files.extend(precision_plot::work_precision(
        &a.out,
        "work_precision",
        &title,
        &rows,
    )?);
    let report = BenchReport {
        out: a.out.clone(),
        profile,
        rows: rows.len(),
        summary,
        reference_wall_s: refs.wall_s,
        reference_reused: reused,
        wall_s: started.elapsed().as_secs_f64(),
        files,
    };
    Ok(report)
}
