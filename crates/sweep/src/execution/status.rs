//! Progress and class counts of a sweep directory, finished or not.
use crate::error::SweepError;
use crate::map::phase_map::PhaseMap;
use crate::map::tally::tally;
use crate::store::plan::plan;
use crate::store::run_store::Store;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The state of a sweep directory.
#[derive(Debug, Clone, Serialize)]
pub struct SweepStatus {
    pub name: String,
    pub output: PathBuf,
    pub points: usize,
    pub runs_total: usize,
    pub runs_done: usize,
    /// Stored runs that cannot be used (unreadable, or content not matching the key); the
    /// next sweep on the directory moves them to `corrupt/` and recomputes them.
    pub runs_corrupt: usize,
    pub complete: bool,
    pub run_statuses: BTreeMap<String, usize>,
    pub run_classes: BTreeMap<String, usize>,
    /// Point labels over the points whose runs are all done.
    pub point_classes: BTreeMap<String, usize>,
    /// Points whose runs are all done, one of them unsettled (not on a stable state): their
    /// labels are not proven ([`crate::map::point_class::PointClass::settled`]).
    pub points_unsettled: usize,
    pub cpu_s: f64,
    /// A refined sweep's levels so far (empty for a uniform one): the levels whose points
    /// are known, the last one possibly unfinished (later levels follow from it).
    pub levels: Vec<LevelStatus>,
    /// Remaining CPU seconds of the known runs at the mean cost of the finished ones (a
    /// refined sweep's later levels are not known yet).
    pub eta_cpu_s: Option<f64>,
    /// Runs stored in the last [`PACE_WINDOW_S`] seconds (by any process: threads, shards).
    pub runs_recent: usize,
    /// Seconds over which the pace is measured: from the first of those runs to now, at
    /// least [`PACE_FLOOR_S`] (0 when none was stored in the window).
    pub pace_s: f64,
    /// Wall seconds until the known runs are done at that pace, measured from the first of
    /// those runs to now (`None` when none was stored in the window, or nothing remains).
    pub eta_s: Option<f64>,
    /// Seconds since the newest run of the window was stored (`None` when none was). Longer
    /// than `eta_s`: the estimate is already passed, the runs left are slower than the
    /// finished ones (a sweep's slow tail, next to its boundaries).
    pub since_last_s: Option<f64>,
    /// Read from the directory's tables (`points.parquet`, `runs.parquet`), which has no run
    /// store: a committed result directory.
    pub from_tables: bool,
}

/// The window over which `droplet status` measures a running sweep's pace.
pub const PACE_WINDOW_S: u64 = 600;

/// The shortest span over which a pace is measured: a sweep's first few runs of the window
/// do not make a pace.
pub const PACE_FLOOR_S: f64 = 60.0;

/// Progress of one refinement level.
#[derive(Debug, Clone, Serialize)]
pub struct LevelStatus {
    pub level: u32,
    pub points: usize,
    pub runs_total: usize,
    pub runs_done: usize,
}

/// The plan of the levels the stored runs know so far (all of them for an unrefined sweep) and
/// each refinement level's progress.
fn levels_known(
    spec: &crate::spec::SweepSpec,
    store: &Store,
) -> Result<(crate::store::plan::Plan, Vec<LevelStatus>), SweepError> {
    let mut levels = Vec::new();
    let plan = match &spec.refine {
        None => plan(spec),
        Some(lattice) => crate::map::levels::walk(spec, lattice, store, |level, plan, runs, _| {
            let done = runs
                .iter()
                .filter(|&&i| store.has(&plan.task(i).key))
                .count();
            levels.push(LevelStatus {
                level,
                points: runs.len() / plan.ic_names.len().max(1),
                runs_total: runs.len(),
                runs_done: done,
            });
            Ok(done == runs.len())
        })?,
    };
    Ok((plan, levels))
}

/// Reads the status of the sweep in `dir`: from its run store, or from its tables when it has
/// none (a committed result directory).
pub fn status(dir: &Path) -> Result<SweepStatus, SweepError> {
    if crate::tables::read::is_tables_only(dir) {
        return status_from_tables(dir);
    }
    let store = Store::open_read(dir)?;
    let spec = crate::spec::load_stored(dir)?;
    let (plan, levels) = levels_known(&spec, &store)?;
    let (records, runs_corrupt) = store.load_counting(plan.tasks().map(|t| t.key));
    let run_statuses = tally(
        records
            .values()
            .map(|r| r.outcome.status.as_str().to_string()),
    );
    let run_classes = tally(records.values().map(|r| {
        r.outcome
            .class
            .map_or("none".to_string(), |c| c.as_str().to_string())
    }));
    // A fold from +0.0 (an empty f64 sum is -0.0, printed "-0").
    let cpu_s = records.values().fold(0.0, |acc, r| acc + r.outcome.wall_s);
    // Point labels only over points whose runs are all done.
    let map = PhaseMap::new(&plan, &records);
    let point_counts = map.class_counts();
    let points_unsettled = map
        .points
        .iter()
        .filter(|p| p.complete() && !p.class.settled())
        .count();
    let eta_cpu_s = (!records.is_empty())
        .then(|| cpu_s / records.len() as f64 * (plan.len() - records.len()) as f64);
    let recent = store.stored_within(
        plan.tasks().map(|t| t.key),
        std::time::Duration::from_secs(PACE_WINDOW_S),
    );
    let remaining = plan.len() - records.len();
    // The pace over the time since the window's first stored run (a sweep resumed 3 min ago
    // has stored its runs in 3 min, not 10), at least [`PACE_FLOOR_S`].
    let pace_span_s = recent.oldest.as_secs_f64().max(PACE_FLOOR_S);
    let eta_s = (recent.runs > 0 && remaining > 0)
        .then(|| remaining as f64 * pace_span_s / recent.runs as f64);
    let runs_recent = recent.runs;
    let pace_s = if runs_recent > 0 { pace_span_s } else { 0.0 };
    let since_last_s = recent.newest.map(|d| d.as_secs_f64());
    Ok(SweepStatus {
        name: spec.name,
        output: dir.to_path_buf(),
        points: plan.points.len(),
        runs_total: plan.len(),
        runs_done: records.len(),
        runs_corrupt,
        complete: records.len() == plan.len(),
        run_statuses,
        run_classes,
        point_classes: point_counts,
        points_unsettled,
        cpu_s,
        levels,
        eta_cpu_s,
        runs_recent,
        pace_s,
        eta_s,
        since_last_s,
        from_tables: false,
    })
}

/// The status of a finished map known only by its tables.
fn status_from_tables(dir: &Path) -> Result<SweepStatus, SweepError> {
    use crate::tables::read;
    let spec = read::stored_spec(&dir.join(read::POINTS))?;
    let points = read::points(&dir.join(read::POINTS))?;
    let runs = read::runs(&dir.join(read::RUNS))?;
    let mut levels: BTreeMap<u32, LevelStatus> = BTreeMap::new();
    if spec.refine.is_some() {
        for p in &points {
            let l = levels.entry(p.level).or_insert(LevelStatus {
                level: p.level,
                points: 0,
                runs_total: 0,
                runs_done: 0,
            });
            l.points += 1;
            l.runs_total += p.n_runs as usize;
            l.runs_done += p.n_runs as usize;
        }
    }
    Ok(SweepStatus {
        name: spec.name,
        output: dir.to_path_buf(),
        points: points.len(),
        runs_total: runs.len(),
        runs_done: runs.len(),
        runs_corrupt: 0,
        complete: true,
        run_statuses: tally(runs.iter().map(|r| r.status.clone())),
        run_classes: tally(
            runs.iter()
                .map(|r| r.class.map_or("none", |c| c.as_str()).to_string()),
        ),
        point_classes: tally(points.iter().map(|p| p.label.clone())),
        points_unsettled: points.iter().filter(|p| !p.settled).count(),
        cpu_s: runs.iter().fold(0.0, |acc, r| acc + r.wall_s),
        levels: levels.into_values().collect(),
        eta_cpu_s: None,
        runs_recent: 0,
        pace_s: 0.0,
        eta_s: None,
        since_last_s: None,
        from_tables: true,
    })
}
