//! Runs a sweep: the pending tasks of a plan in a rayon pool, each persisted as it finishes,
//! with progress (runs done / total, ETA, classes so far), then the final tables and picture.
use crate::error::SweepError;
use crate::execution::progress::{clock, progress_bar};
use crate::map::phase_map::PhaseMap;
use crate::map::tally::tally;
use crate::spec::lattice::Lattice;
use crate::spec::SweepSpec;
use crate::store::plan::{plan, Plan, Task};
use crate::store::run_store::{CorruptRun, RunRecord, Store, Stored};
use crate::store::shard::{indices_of, Shard};
use crate::tables::sweep_tables;
use droplet_solver::contract::ending::Ending;
use droplet_solver::contract::profile::RunProfile;
use droplet_solver::runs::driver::simulate;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

/// How to run a sweep.
#[derive(Debug, Clone, Default)]
pub struct SweepOptions {
    /// Worker threads (default: all cores).
    pub jobs: Option<usize>,
    /// Show a progress bar (only drawn on a terminal).
    pub progress: bool,
    /// Run only this slice of the runs, and write no final tables (`droplet merge` does).
    pub shard: Option<Shard>,
    /// With `shard`, for a spec with `refine:`: the level whose slice this process runs (the
    /// levels below it must be finished; see [`run_refined`]).
    pub level: Option<u32>,
    /// Draw the pictures with the tables (unsharded sweeps only).
    pub plot: bool,
    /// Refuse specs with more runs than this (`None`: [`crate::store::plan::DEFAULT_MAX_RUNS`]).
    pub max_runs: Option<u64>,
}

/// What a finished sweep did.
#[derive(Debug, Clone, Serialize)]
pub struct SweepSummary {
    pub name: String,
    pub output: PathBuf,
    pub points: usize,
    /// Runs of this invocation (all, or this shard's).
    pub runs: usize,
    /// `I/N` when sharded.
    pub shard: Option<String>,
    /// The level a shard of a refined sweep ran.
    pub level: Option<u32>,
    /// Runs computed by this invocation.
    pub computed: usize,
    /// Runs found in the store (resumed or shared with another sweep).
    pub reused: usize,
    /// Runs of this invocation certified without stepping (`refine.certify_midpoints`,
    /// [`crate::map::certify`]; their `ended_by` is `certified_midway`), among `computed`.
    pub certified: usize,
    /// The points between two coarser ones of one state that were left to their runs, by
    /// reason ([`crate::map::certify::Refusal`]; empty unless `refine.certify_midpoints`).
    pub certify_refused: BTreeMap<String, usize>,
    /// Stored runs that could not be used (unreadable, or content not matching the key):
    /// moved to `DIR/corrupt/` and recomputed.
    pub corrupt: Vec<CorruptRun>,
    /// Stored runs of an earlier release upgraded in place when the store was opened
    /// (sealed, or re-keyed: `Store::upgraded`), not recomputed.
    pub upgraded: usize,
    pub wall_s: f64,
    pub jobs: usize,
    pub point_classes: BTreeMap<String, usize>,
    pub run_statuses: BTreeMap<String, usize>,
    /// Fixed-step runs whose step looked too large (`RunOutcome::dt_warning`).
    pub dt_warnings: usize,
    /// The run time of the runs computed by this invocation (the sum of their `wall_s`) and
    /// where it went ([`droplet_solver::contract::profile`]).
    pub run_time_s: f64,
    pub profile: RunProfile,
    pub tables: Vec<PathBuf>,
}

/// Runs one task to a record.
pub fn run_task(task: &Task) -> Result<RunRecord, SweepError> {
    let outcome = simulate(&task.params, &task.ic, &task.settings)?;
    Ok(RunRecord {
        key: task.key.clone(),
        params: task.params,
        ic: task.ic.clone(),
        settings: task.settings,
        solver_version: droplet_solver::solver_version(task.settings.model, task.params.modes)
            .to_string(),
        outcome,
    })
}

/// What running one set of a plan's runs did.
#[derive(Default)]
struct Ran {
    computed: usize,
    reused: usize,
    certified: usize,
    /// Points left to their runs by `refine.certify_midpoints`, by reason.
    refused: BTreeMap<String, usize>,
    corrupt: Vec<CorruptRun>,
    /// The computed runs' time and its parts.
    run_time_s: f64,
    profile: RunProfile,
}

impl Ran {
    fn add(&mut self, o: Ran) {
        self.computed += o.computed;
        self.reused += o.reused;
        self.certified += o.certified;
        for (why, n) in o.refused {
            *self.refused.entry(why).or_default() += n;
        }
        self.corrupt.extend(o.corrupt);
        self.run_time_s += o.run_time_s;
        self.profile.add(&o.profile);
    }
}

/// The counts and pace of one set of runs in progress: the progress bar's message.
#[derive(Default)]
struct Pace {
    labels: BTreeMap<String, usize>,
    done: usize,
    run_time_s: f64,
    profile: RunProfile,
}

impl Pace {
    /// Class counts, then the mean run time of this set's runs so far and the time left at
    /// that pace on `jobs` threads for the `left` runs to go.
    fn message(&self, left: usize, jobs: usize) -> String {
        let counts = self
            .labels
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect::<Vec<_>>()
            .join(", ");
        let mean = self.run_time_s / self.done.max(1) as f64;
        format!(
            "{counts}; {mean:.2} s/run, {} left at this pace",
            clock(mean * left as f64 / jobs.max(1) as f64)
        )
    }
}

/// Runs the runs `mine` of `plan` that are not validly stored (a corrupt one is moved aside
/// and recomputed; a certified one, unless `certified_count`, is replaced by its run), each
/// saved as it finishes, with a progress bar labelled `what`.
fn run_pending(
    store: &Store,
    plan: &Plan,
    mine: &[usize],
    pool: &rayon::ThreadPool,
    progress: bool,
    what: &str,
    certified_count: bool,
) -> Result<Ran, SweepError> {
    let mut pending: Vec<usize> = Vec::new();
    let mut corrupt = Vec::new();
    for &i in mine {
        let key = plan.task(i).key;
        match store.check(&key) {
            Stored::Valid(r)
                if !certified_count && r.outcome.ended_by == Some(Ending::Certified) =>
            {
                pending.push(i)
            }
            Stored::Valid(_) => {}
            Stored::Missing => pending.push(i),
            Stored::Corrupt(reason) => {
                corrupt.push(store.quarantine(&key, &reason)?);
                pending.push(i);
            }
        }
    }
    let reused = mine.len() - pending.len();
    let pb = progress_bar(mine.len() as u64, reused as u64, progress, what);
    let pace: Mutex<Pace> = Mutex::new(Pace::default());
    let jobs = pool.current_num_threads();
    pool.install(|| {
        pending
            .par_iter()
            .try_for_each(|&i| -> Result<(), SweepError> {
                let record = run_task(&plan.task(i))?;
                store.save(&record)?;
                let out = &record.outcome;
                let label = match out.class {
                    Some(c)
                        if out.status == droplet_solver::contract::outcome::RunStatus::Steady =>
                    {
                        c.as_str().to_string()
                    }
                    _ => out.status.as_str().to_string(),
                };
                let mut p = pace.lock().expect("no panics while held");
                *p.labels.entry(label).or_default() += 1;
                p.done += 1;
                p.run_time_s += out.wall_s;
                p.profile.add(&out.profile);
                let msg = p.message(pending.len() - p.done, jobs);
                drop(p);
                pb.set_message(msg);
                pb.inc(1);
                Ok(())
            })
    })?;
    pb.finish_and_clear();
    let pace = pace.into_inner().expect("no panics while held");
    Ok(Ran {
        computed: pending.len(),
        reused,
        certified: 0,
        refused: BTreeMap::new(),
        corrupt,
        run_time_s: pace.run_time_s,
        profile: pace.profile,
    })
}

/// Runs a refined sweep level by level ([`crate::map::levels`]). Unsharded: every level.
/// Sharded (`Some((shard, level))`): only the shard's slice of `level`, after checking that
/// every level below it is finished (its points follow from them), so a Slurm array per level,
/// each depending on the one before, runs the sweep; a level refinement never reaches has
/// no runs. Returns the plan so far and, sharded, the runs of the slice.
fn run_refined(
    spec: &SweepSpec,
    lattice: &Lattice,
    store: &Store,
    pool: &rayon::ThreadPool,
    progress: bool,
    shard: Option<(Shard, u32)>,
) -> Result<(Plan, Vec<usize>, Ran), SweepError> {
    let mut total = Ran::default();
    let mut mine = Vec::new();
    let plan = crate::map::levels::walk(spec, lattice, store, |level, plan, runs, between| {
        let runs = match shard {
            None => runs.to_vec(),
            Some((_, target)) if level < target => {
                let missing = runs
                    .iter()
                    .filter(|&&i| !store.has(&plan.task(i).key))
                    .count();
                if missing > 0 {
                    return Err(SweepError::LevelNotReady {
                        level: target,
                        earlier: level,
                        missing,
                        output: store.dir().to_path_buf(),
                    });
                }
                return Ok(true);
            }
            Some((sh, _)) => indices_of(plan, runs, sh),
        };
        let mode = lattice.refine.certify_midpoints;
        let certify = mode.is_on();
        let mut to_run = runs.clone();
        if certify {
            let c = crate::execution::certify::certify_pending(
                store, plan, &runs, between, mode, pool,
            )?;
            to_run.retain(|i| !c.runs.contains(i));
            total.add(Ran {
                computed: c.runs.len(),
                certified: c.runs.len(),
                run_time_s: c.run_time_s,
                refused: c.refused,
                ..Ran::default()
            });
        }
        let ran = run_pending(
            store,
            plan,
            &to_run,
            pool,
            progress,
            &format!("level {level} runs"),
            certify,
        )?;
        total.add(ran);
        mine.extend(runs);
        Ok(shard.is_none())
    })?;
    if shard.is_none() {
        mine = (0..plan.len()).collect();
    }
    Ok((plan, mine, total))
}

/// A pool of `jobs` worker threads (default: one per core) and its size.
fn worker_pool(jobs: Option<usize>) -> Result<(rayon::ThreadPool, usize), SweepError> {
    let jobs = jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| SweepError::Invalid(format!("cannot start {jobs} worker threads: {e}")))?;
    Ok((pool, jobs))
}

/// The shard and refinement level this invocation runs (`--shard I/N --level L` on a spec
/// with `refine:`), or none; the combinations that make no sense are refused.
fn shard_level(spec: &SweepSpec, opts: &SweepOptions) -> Result<Option<(Shard, u32)>, SweepError> {
    match (&spec.refine, opts.shard, opts.level) {
        (Some(l), _, Some(level)) if level > l.refine.levels => {
            Err(SweepError::Invalid(format!(
                "invalid --level {level}: the spec's refine: has levels 0..={}",
                l.refine.levels
            )))
        }
        (Some(_), Some(sh), Some(level)) => Ok(Some((sh, level))),
        (Some(l), Some(_), None) => {
            Err(SweepError::Invalid(format!(
                "a spec with refine: is sharded one level at a time (each level's points follow from the one before): add --level L, L in 0..={} (`droplet slurm` submits one array per level)",
                l.refine.levels
            )))
        }
        (None, _, Some(_)) => {
            Err(SweepError::Invalid(
                "--level is for specs with refine: (this one has a uniform grid)".into(),
            ))
        }
        (_, None, Some(_)) => {
            Err(SweepError::Invalid(
                "--level goes with --shard (an unsharded sweep runs every level)".into(),
            ))
        }
        _ => Ok(None),
    }
}

/// The runs of an unrefined sweep (this shard's, with `--shard`), the pending ones computed:
/// its plan, the indices of this invocation's runs, and what running them did.
fn run_grid(
    spec: &SweepSpec,
    store: &Store,
    pool: &rayon::ThreadPool,
    opts: &SweepOptions,
) -> Result<(Plan, Vec<usize>, Ran), SweepError> {
    let plan = plan(spec);
    // This invocation's runs; runs are made on demand (memory per run: 8 bytes).
    let mine: Vec<usize> = match opts.shard {
        None => (0..plan.len()).collect(),
        Some(sh) => indices_of(&plan, &(0..plan.len()).collect::<Vec<_>>(), sh),
    };
    let ran = run_pending(store, &plan, &mine, pool, opts.progress, "runs", false)?;
    Ok((plan, mine, ran))
}

/// Runs every pending task of `spec` into `out` and writes the tables.
pub fn run_sweep(
    spec: &SweepSpec,
    out: &Path,
    opts: &SweepOptions,
) -> Result<SweepSummary, SweepError> {
    let started = Instant::now();
    crate::store::plan::check_size(
        spec,
        opts.max_runs
            .unwrap_or(crate::store::plan::DEFAULT_MAX_RUNS),
    )?;
    let shard_level = shard_level(spec, opts)?;
    let store = match opts.shard {
        None => Store::open_locked(out)?,
        Some(sh) => Store::open_shard(out, &sh.lock_name())?,
    };
    store.write_file("spec.yaml", spec.source.as_bytes())?;
    let (pool, jobs) = worker_pool(opts.jobs)?;
    let (plan, mine, ran) = match &spec.refine {
        Some(lattice) => run_refined(spec, lattice, &store, &pool, opts.progress, shard_level)?,
        None => run_grid(spec, &store, &pool, opts)?,
    };
    let records = store.load_many(plan.tasks().map(|t| t.key));
    if opts.shard.is_none() && records.len() != plan.len() {
        // Only another process touching runs/ meanwhile can cause this: never write tables
        // with rows missing.
        return Err(SweepError::Incomplete(Box::new(
            store.report_missing(&plan),
        )));
    }
    // Classified once, for the points table, the picture and the summary.
    let map = PhaseMap::new(&plan, &records);
    let mut tables = Vec::new();
    if opts.shard.is_none() {
        tables = sweep_tables::write_tables(&store, spec, &plan, &records, &map)?;
        if opts.plot {
            tables.extend(crate::pictures::sweep_pictures::plot_records(
                out, spec, &plan, &records, &map,
            )?);
        }
    }
    let point_classes = tally(map.points.iter().map(|p| p.class.label.clone()));
    let run_statuses = tally(
        records
            .values()
            .map(|r| r.outcome.status.as_str().to_string()),
    );
    let dt_warnings = records
        .values()
        .filter(|r| r.outcome.dt_warning(&r.settings).is_some())
        .count();
    Ok(SweepSummary {
        name: spec.name.clone(),
        output: out.to_path_buf(),
        points: plan.points.len(),
        runs: mine.len(),
        shard: opts.shard.map(|s| format!("{}/{}", s.index, s.count)),
        level: shard_level.map(|(_, l)| l),
        computed: ran.computed,
        reused: ran.reused,
        certified: ran.certified,
        certify_refused: ran.refused,
        corrupt: ran.corrupt,
        upgraded: store.upgraded(),
        wall_s: started.elapsed().as_secs_f64(),
        jobs,
        point_classes,
        run_statuses,
        dt_warnings,
        run_time_s: ran.run_time_s,
        profile: ran.profile,
        tables,
    })
}
