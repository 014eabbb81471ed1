//! A map's run time, part by part (`droplet bench --map DIR`): a seeded sample of the runs
//! of a finished map (or all of them) computed again by this binary as the map's sweep runs
//! them, each profiled ([`droplet_solver::contract::profile`]): how the time divides between
//! time stepping, the Newton solves, the eigenvalue problems, the landing's and the
//! orientation flow's samples, per way of ending (the map's), per refinement level and per
//! decade of simulated time (a map's slow runs are few and weigh most), against the map's
//! own time for the same runs; and each run's end against the map's (the same class, `v` and
//! `s` within [`SAME_END`]).
use crate::error::SweepError;
use crate::execution::progress::progress_bar;
use crate::map::sample::Sample;
use crate::spec::axes::Point;
use crate::store::plan::{point_set, Plan};
use crate::tables::read::{self, PointRow, RunRow};
use crate::tables::sweep_tables::{f64_col, metadata, str_col, write_parquet};
use droplet_solver::contract::profile::RunProfile;
use droplet_solver::runs::driver::simulate;
use polars::prelude::*;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};
use std::path::PathBuf;
use std::time::Instant;

/// Largest difference of `v` and of `s` between a run and the map's for the same end.
pub const SAME_END: f64 = 1e-6;

/// What to profile and where to write it.
#[derive(Debug, Clone)]
pub struct MapProfileOptions {
    /// A finished map's directory (its `runs.parquet`, `points.parquet` and the spec in
    /// their metadata).
    pub map: PathBuf,
    pub out: PathBuf,
    /// A seeded sample of this many runs (`None`: every run).
    pub sample: Option<Sample>,
    /// Worker threads (default: all cores, as a sweep).
    pub jobs: Option<usize>,
    pub progress: bool,
}

/// One run computed again, beside the map's.
#[derive(Debug, Clone, Serialize)]
pub struct ProfiledRun {
    pub point: u32,
    /// The point's coordinates in the map's plane.
    pub coords: Point,
    pub ic: String,
    pub level: u32,
    /// The map's run: its class, how it ended, `v`, `s` and time.
    pub map_class: Option<String>,
    pub map_ended_by: Option<String>,
    pub map_v: f64,
    pub map_s: f64,
    pub map_t_end: f64,
    pub map_wall_s: f64,
    /// This binary's run.
    pub class: Option<String>,
    pub ended_by: Option<String>,
    pub v: f64,
    pub s: f64,
    pub t_end: f64,
    pub steps: u64,
    pub wall_s: f64,
    /// The same class, and `v`, `s` within [`SAME_END`] of the map's.
    pub same_end: bool,
    pub profile: RunProfile,
}

/// The runs of one group (a way of ending, a level, or all): their time here and in the map,
/// and its parts.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Group {
    pub name: String,
    pub runs: usize,
    pub wall_s: f64,
    pub map_wall_s: f64,
    /// Runs that end as the map's did.
    pub same_end: usize,
    /// The parts' seconds and counts, summed.
    pub profile: RunProfile,
}

impl Group {
    fn add(&mut self, r: &ProfiledRun) {
        self.runs += 1;
        self.wall_s += r.wall_s;
        self.map_wall_s += r.map_wall_s;
        self.same_end += usize::from(r.same_end);
        self.profile.add(&r.profile);
    }

    /// The run time outside every profiled part (the driver's own bookkeeping).
    pub fn other_s(&self) -> f64 {
        (self.wall_s - self.profile.total_s()).max(0.0)
    }
}

/// A map's profile.
#[derive(Debug, Clone, Serialize)]
pub struct MapProfile {
    pub map: PathBuf,
    /// Runs in the map, and runs profiled (a sample, or all).
    pub map_runs: usize,
    pub runs: usize,
    pub seed: Option<u64>,
    pub jobs: usize,
    pub total: Group,
    /// By the map's way of ending (`steady_by_newton`, ..., or the status of an unsettled
    /// run), and by refinement level.
    pub by_ending: Vec<Group>,
    pub by_level: Vec<Group>,
    /// By the decade of the run's simulated time `t_end` here ([`duration_group`]).
    pub by_duration: Vec<Group>,
    /// The runs that end otherwise than the map's.
    pub changed: Vec<ProfiledRun>,
    /// Wall time of the whole profile.
    pub wall_s: f64,
    pub files: Vec<PathBuf>,
}

/// The runs to compute again: the map's rows (a sample, or all), with their points.
fn chosen(
    rows: Vec<RunRow>,
    points: &HashMap<u32, &PointRow>,
    sample: Option<Sample>,
) -> Result<Vec<RunRow>, SweepError> {
    if let Some(r) = rows.iter().find(|r| !points.contains_key(&r.point)) {
        return Err(SweepError::Invalid(format!(
            "run {} names point {}, which the points table lacks: the map's tables are of \
             two sweeps",
            r.key, r.point
        )));
    }
    Ok(match sample {
        None => rows,
        Some(s) => s.draw_by(rows.into_iter(), |r| {
            let mut id = r.point.to_le_bytes().to_vec();
            id.extend(r.ic.as_bytes());
            id
        }),
    })
}

/// The plan of the chosen runs' points and, per run, its index in that plan.
fn plan_of(
    spec: &crate::spec::SweepSpec,
    runs: &[RunRow],
    points: &HashMap<u32, &PointRow>,
) -> Result<(Plan, Vec<usize>), SweepError> {
    let mut order: Vec<u32> = runs.iter().map(|r| r.point).collect();
    order.sort_unstable();
    order.dedup();
    let coords = order
        .iter()
        .map(|p| [points[p].x, points[p].y, points[p].z])
        .collect();
    let levels = order.iter().map(|p| points[p].level).collect();
    let cells = vec![(f64::NAN, f64::NAN); order.len()];
    let plan = point_set(spec, coords, levels, cells);
    let n_ics = plan.ic_names.len();
    let index = runs
        .iter()
        .map(|r| {
            let ic = plan
                .ic_names
                .iter()
                .position(|n| *n == r.ic)
                .ok_or_else(|| {
                    SweepError::Invalid(format!(
                        "run {} has initial condition {}, which the map's spec does not list",
                        r.key, r.ic
                    ))
                })?;
            let at = order
                .binary_search(&r.point)
                .expect("every run's point is planned");
            Ok(at * n_ics + ic)
        })
        .collect::<Result<Vec<_>, SweepError>>()?;
    Ok((plan, index))
}

/// Computes the chosen runs of the map again, profiled, and writes
/// `OUT/map_profile.parquet` (one row per run) and `OUT/map_profile.json` (the groups).
pub fn profile_map(opts: &MapProfileOptions) -> Result<MapProfile, SweepError> {
    let started = Instant::now();
    let runs_path = opts.map.join(read::RUNS);
    for table in [read::RUNS, read::POINTS] {
        if !opts.map.join(table).is_file() {
            return Err(SweepError::Invalid(format!(
                "--map {}: no {table}; it takes the directory of a finished map (a sweep's \
                 output, or a committed result under results/)",
                opts.map.display()
            )));
        }
    }
    let spec = read::stored_spec(&runs_path)?;
    let rows = read::runs(&runs_path)?;
    let point_rows = read::points(&opts.map.join(read::POINTS))?;
    let points: HashMap<u32, &PointRow> = point_rows.iter().map(|p| (p.point, p)).collect();
    let map_runs = rows.len();
    let chosen = chosen(rows, &points, opts.sample)?;
    let (plan, index) = plan_of(&spec, &chosen, &points)?;
    crate::store::atomic::create_output_dir(&opts.out)?;
    let jobs = opts
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| SweepError::Invalid(format!("cannot start {jobs} worker threads: {e}")))?;
    let pb = progress_bar(chosen.len() as u64, 0, opts.progress, "runs");
    let ran: Vec<ProfiledRun> = pool.install(|| {
        chosen
            .par_iter()
            .zip(index.par_iter())
            .map(|(row, &i)| {
                let task = plan.task(i);
                let out = simulate(&task.params, &task.ic, &task.settings)?;
                pb.inc(1);
                let class = out.class.map(|c| c.as_str().to_string());
                let map_class = row.class.map(|c| c.as_str().to_string());
                Ok(ProfiledRun {
                    point: row.point,
                    coords: plan.points[i / plan.ic_names.len()],
                    ic: row.ic.clone(),
                    level: points[&row.point].level,
                    same_end: class == map_class
                        && (out.v - row.v).abs() <= SAME_END
                        && (out.s - row.s).abs() <= SAME_END,
                    map_class,
                    map_ended_by: row.ended_by.clone(),
                    map_v: row.v,
                    map_s: row.s,
                    map_t_end: row.t_end,
                    map_wall_s: row.wall_s,
                    class,
                    ended_by: out.ended_by.map(|e| e.as_str().to_string()),
                    v: out.v,
                    s: out.s,
                    t_end: out.t_end,
                    steps: out.steps,
                    wall_s: out.wall_s,
                    profile: out.profile,
                })
            })
            .collect::<Result<Vec<_>, SweepError>>()
    })?;
    pb.finish_and_clear();
    let mut profile = summarise(&ran);
    profile.map = opts.map.clone();
    profile.map_runs = map_runs;
    profile.seed = opts.sample.map(|s| s.seed);
    profile.jobs = jobs;
    profile.files = vec![
        opts.out.join("map_profile.parquet"),
        opts.out.join("map_profile.json"),
    ];
    profile.wall_s = started.elapsed().as_secs_f64();
    write(&ran, &profile, &spec.source)?;
    Ok(profile)
}

/// The groups of the profiled runs.
fn summarise(ran: &[ProfiledRun]) -> MapProfile {
    let mut total = Group {
        name: "all".into(),
        ..Group::default()
    };
    let mut by_ending: BTreeMap<String, Group> = BTreeMap::new();
    let mut by_level: BTreeMap<u32, Group> = BTreeMap::new();
    let mut by_duration: BTreeMap<i32, Group> = BTreeMap::new();
    for r in ran {
        total.add(r);
        let ending = r.map_ended_by.clone().unwrap_or_else(|| "unsettled".into());
        add_to(&mut by_ending, ending.clone(), ending, r);
        add_to(&mut by_level, r.level, format!("level {}", r.level), r);
        let (decade, name) = duration_group(r.t_end);
        add_to(&mut by_duration, decade, name, r);
    }
    MapProfile {
        map: PathBuf::new(),
        map_runs: 0,
        runs: ran.len(),
        seed: None,
        jobs: 0,
        total,
        by_ending: by_ending.into_values().collect(),
        by_level: by_level.into_values().collect(),
        by_duration: by_duration.into_values().collect(),
        changed: ran.iter().filter(|r| !r.same_end).cloned().collect(),
        wall_s: 0.0,
        files: Vec::new(),
    }
}

/// Adds `r` to the group of `key`, named `name` when `r` is its first run.
fn add_to<K: Ord>(groups: &mut BTreeMap<K, Group>, key: K, name: String, r: &ProfiledRun) {
    groups
        .entry(key)
        .or_insert_with(|| Group {
            name,
            ..Group::default()
        })
        .add(r);
}

/// The decade of simulated time a run of `t_end` falls in, and its group's name: `t < 10`,
/// `10 <= t < 100`, ... up to `t >= 10000` (decades 1 to 5; a run with no steps, `t_end` 0,
/// is in the first).
pub fn duration_group(t_end: f64) -> (i32, String) {
    let decade = if t_end >= 10.0 {
        (t_end.log10().floor() as i32).clamp(1, 4) + 1
    } else {
        1
    };
    let name = match decade {
        1 => "t < 10".to_string(),
        5 => "t >= 10000".to_string(),
        d => format!("{} <= t < {}", 10i64.pow(d as u32 - 1), 10i64.pow(d as u32)),
    };
    (decade, name)
}

/// The per-run table and the summary (`profile.files`), atomically.
fn write(ran: &[ProfiledRun], profile: &MapProfile, spec_text: &str) -> Result<(), SweepError> {
    let f = |g: fn(&ProfiledRun) -> f64| ran.iter().map(g).collect::<Vec<f64>>();
    let opt =
        |g: fn(&ProfiledRun) -> Option<String>| ran.iter().map(g).collect::<Vec<Option<String>>>();
    let u = |g: fn(&ProfiledRun) -> u64| ran.iter().map(g).collect::<Vec<u64>>();
    let cols = vec![
        Column::new(
            "point".into(),
            ran.iter().map(|r| r.point).collect::<Vec<u32>>(),
        ),
        f64_col("x", f(|r| r.coords[0])),
        f64_col("y", f(|r| r.coords[1])),
        f64_col("z", f(|r| r.coords[2])),
        str_col("ic", ran.iter().map(|r| r.ic.clone()).collect()),
        Column::new(
            "level".into(),
            ran.iter().map(|r| r.level).collect::<Vec<u32>>(),
        ),
        Column::new("map_class".into(), opt(|r| r.map_class.clone())),
        Column::new("map_ended_by".into(), opt(|r| r.map_ended_by.clone())),
        f64_col("map_v", f(|r| r.map_v)),
        f64_col("map_s", f(|r| r.map_s)),
        f64_col("map_t_end", f(|r| r.map_t_end)),
        f64_col("map_wall_s", f(|r| r.map_wall_s)),
        Column::new("class".into(), opt(|r| r.class.clone())),
        Column::new("ended_by".into(), opt(|r| r.ended_by.clone())),
        f64_col("v", f(|r| r.v)),
        f64_col("s", f(|r| r.s)),
        f64_col("t_end", f(|r| r.t_end)),
        Column::new("steps".into(), u(|r| r.steps)),
        Column::new(
            "same_end".into(),
            ran.iter().map(|r| r.same_end).collect::<Vec<bool>>(),
        ),
        f64_col("wall_s", f(|r| r.wall_s)),
        f64_col("stepping_s", f(|r| r.profile.stepping_s)),
        f64_col("newton_s", f(|r| r.profile.newton_s)),
        f64_col("eigen_s", f(|r| r.profile.eigen_s)),
        f64_col("landing_s", f(|r| r.profile.landing_s)),
        f64_col("flow_s", f(|r| r.profile.flow_s)),
        f64_col("leap_s", f(|r| r.profile.leap_s)),
        f64_col("diagnosis_s", f(|r| r.profile.diagnosis_s)),
        Column::new("newton_solves".into(), u(|r| r.profile.newton_solves)),
        Column::new("eigen_problems".into(), u(|r| r.profile.eigen_problems)),
        Column::new("field_solves".into(), u(|r| r.profile.field_solves)),
    ];
    let mut df = DataFrame::new(ran.len(), cols)?;
    let (table, summary) = (&profile.files[0], &profile.files[1]);
    let mut meta = metadata(Some(spec_text));
    meta.push(("map".into(), profile.map.display().to_string()));
    if let Some(seed) = profile.seed {
        meta.push(("seed".into(), seed.to_string()));
    }
    write_parquet(&mut df, table, meta)?;
    let text = serde_json::to_vec_pretty(profile).expect("plain data serialises");
    crate::store::atomic::write_atomic(summary, &text)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::duration_group;

    #[test]
    fn runs_fall_in_the_decade_of_their_simulated_time() {
        let decade = |t: f64| duration_group(t).0;
        assert_eq!(
            [0.0, 9.99, 10.0, 99.9, 100.0, 999.9, 1000.0, 9999.0, 1e4, 1e6].map(decade),
            [1, 1, 2, 2, 3, 3, 4, 4, 5, 5]
        );
        assert_eq!(duration_group(250.0).1, "100 <= t < 1000");
        assert_eq!(duration_group(5.0).1, "t < 10");
        assert_eq!(duration_group(2e5).1, "t >= 10000");
    }
}
