//! `droplet bench --map DIR --certify`: what `refine.certify_midpoints`
//! ([`crate::map::certify`]) would make of a finished refined map, from its tables: at every
//! point that lies midway between two coarser points, the certificate from the neighbours'
//! runs as the map has them, against the point's own runs (its class and root, and the
//! certificate's time against theirs). Nothing is stepped: a committed map made without the
//! option (N = 192, hours of run time) is measured in minutes. With `chained` the levels are
//! taken in order, as the sweep takes them, and a neighbour certified here lends the
//! certificate its certified ends instead of its runs'.
use crate::error::SweepError;
use crate::map::certify::{certify_ends, first_candidate, End, Refusal, SAME_ROOT};
use crate::map::refine::midway;
use crate::spec::lattice::{Certify, Lattice};
use crate::tables::read::{self, PointRow, RunRow};
use droplet_solver::contract::ending::Ending;
use droplet_solver::contract::outcome::RunStatus;
use droplet_solver::model::classify::StateClass;
use droplet_solver::model::state::speed_and_deformation;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What the certificate makes of a map.
#[derive(Debug, Clone, Default, Serialize)]
pub struct CertifyCheck {
    pub map: PathBuf,
    /// `true` (from stepped neighbours) or `chained`.
    pub mode: &'static str,
    pub points: usize,
    /// Points midway between two coarser points of one single state.
    pub candidates: usize,
    /// Of those, the points certified, and their runs.
    pub certified_points: usize,
    pub certified_runs: usize,
    /// The others, by reason ([`Refusal`]).
    pub refused: BTreeMap<String, usize>,
    /// Certified runs whose own run (the map's) ended on another class, or not steady.
    pub class_differences: usize,
    /// Certified runs whose own run ended on another root of the class (`v` or `s` more than
    /// 1e-6 apart), and by how much at most; the largest difference of the others.
    pub other_root: usize,
    pub other_root_max_dv: f64,
    pub other_root_max_ds: f64,
    pub same_root_max_dv: f64,
    pub same_root_max_ds: f64,
    /// The certificates' time (this machine) and the map's run time of the runs they replace
    /// (the machine that made the map), and of the whole map.
    pub certificates_s: f64,
    pub their_runs_s: f64,
    pub map_run_time_s: f64,
    pub wall_s: f64,
}

/// The certificate under `mode` at every midpoint of the refined map in `map` (its tables),
/// on `jobs` threads (default: one per core).
pub fn check_certificates(
    map: &Path,
    mode: Certify,
    jobs: Option<usize>,
) -> Result<CertifyCheck, SweepError> {
    if !mode.is_on() {
        return Err(SweepError::Invalid(
            "--certify: a mode that certifies (true or chained)".to_string(),
        ));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.unwrap_or(0))
        .build()
        .map_err(|e| SweepError::Invalid(format!("cannot start the worker threads: {e}")))?;
    pool.install(|| check_all(map, mode))
}

/// [`check_certificates`] on the current pool.
fn check_all(map: &Path, mode: Certify) -> Result<CertifyCheck, SweepError> {
    let started = Instant::now();
    let runs_path = map.join(read::RUNS);
    for table in [read::RUNS, read::POINTS] {
        if !map.join(table).is_file() {
            return Err(SweepError::Invalid(format!(
                "--map {}: no {table}; it takes the directory of a finished map",
                map.display()
            )));
        }
    }
    let spec = read::stored_spec(&runs_path)?;
    let Some(lattice) = &spec.refine else {
        return Err(SweepError::Invalid(format!(
            "--certify: the map in {} has no refine: section (only refined maps have midpoints)",
            map.display()
        )));
    };
    let rows = read::runs(&runs_path)?;
    let points = read::points(&map.join(read::POINTS))?;
    let names: Vec<String> = crate::store::plan::plan(&spec).ic_names;
    let mut by_point: HashMap<u32, Vec<Option<&RunRow>>> = HashMap::new();
    for r in &rows {
        let slot = by_point
            .entry(r.point)
            .or_insert_with(|| vec![None; names.len()]);
        if let Some(i) = names.iter().position(|n| *n == r.ic) {
            slot[i] = Some(r);
        }
    }
    let checked = check_levels(&midpoints_by_level(lattice, &points), &by_point, mode);
    let mut out = CertifyCheck {
        map: map.to_path_buf(),
        mode: mode.as_str(),
        points: points.len(),
        map_run_time_s: rows.iter().map(|r| r.wall_s).sum(),
        ..Default::default()
    };
    for c in checked {
        out.add(c);
    }
    out.wall_s = started.elapsed().as_secs_f64();
    Ok(out)
}

/// The map's midpoints by level (a midpoint's pairs are of lower levels), each slice of a
/// third axis on its own, as refinement has it.
fn midpoints_by_level(lattice: &Lattice, points: &[PointRow]) -> BTreeMap<u32, Vec<Midpoint>> {
    let at: HashMap<(u64, (u64, u64)), (u32, u32)> = points
        .iter()
        .map(|p| {
            let node = lattice.node_of((p.x, p.y));
            ((p.z.to_bits(), node), (p.point, p.level))
        })
        .collect();
    let mut by_level: BTreeMap<u32, Vec<Midpoint>> = BTreeMap::new();
    for p in points {
        let z = p.z.to_bits();
        let node = lattice.node_of((p.x, p.y));
        let pairs = midway(lattice, node, p.level, |m| at.get(&(z, m)).map(|&(_, l)| l));
        let pairs: Vec<[u32; 2]> = pairs
            .iter()
            .map(|pair| pair.map(|m| at[&(z, m)].0))
            .collect();
        if !pairs.is_empty() {
            by_level.entry(p.level).or_default().push((p.point, pairs));
        }
    }
    by_level
}

/// Each level's midpoints certified (in parallel) from their neighbours' ends: a
/// neighbour's certificate's when chained and certified here, else its runs' (a neighbour
/// without all its runs in the tables is no candidate).
fn check_levels(
    by_level: &BTreeMap<u32, Vec<Midpoint>>,
    by_point: &HashMap<u32, Vec<Option<&RunRow>>>,
    mode: Certify,
) -> Vec<Checked> {
    let mut lent: HashMap<u32, Vec<End>> = HashMap::new();
    let mut checked: Vec<Checked> = Vec::new();
    for level_points in by_level.values() {
        let ends = |q: u32| -> Result<Vec<End>, Refusal> {
            if let Some(e) = lent.get(&q) {
                return Ok(e.clone());
            }
            let runs = by_point.get(&q).ok_or(Refusal::NotCandidate)?;
            runs.iter()
                .map(|r| r.map(end_of))
                .collect::<Option<_>>()
                .ok_or(Refusal::NotCandidate)
        };
        let level: Vec<Checked> = level_points
            .par_iter()
            .filter_map(|(p, pairs)| {
                let own = by_point
                    .get(p)?
                    .iter()
                    .copied()
                    .collect::<Option<Vec<_>>>()?;
                let t = Instant::now();
                let result = first_candidate(pairs, |[a, b]| {
                    certify_ends(own[0].params, own[0].n, &ends(a)?, &ends(b)?, mode)
                });
                Some(Checked {
                    point: *p,
                    result,
                    seconds: t.elapsed().as_secs_f64(),
                    own: own.into_iter().cloned().collect(),
                })
            })
            .collect();
        if mode == Certify::Chained {
            for c in &level {
                if let Ok((class, ends)) = &c.result {
                    let end = |z: &Vec<f64>| End {
                        class: Some(*class),
                        certified: true,
                        z: z.clone(),
                    };
                    lent.insert(c.point, ends.iter().map(end).collect());
                }
            }
        }
        checked.extend(level);
    }
    checked
}

impl CertifyCheck {
    /// Counts one midpoint's certificate (or refusal) against its own runs.
    fn add(&mut self, c: Checked) {
        let (class, ends) = match c.result {
            Err(Refusal::NotCandidate) => return,
            Err(why) => {
                self.candidates += 1;
                *self.refused.entry(why.as_str().to_string()).or_default() += 1;
                return;
            }
            Ok(found) => found,
        };
        self.candidates += 1;
        self.certified_points += 1;
        self.certificates_s += c.seconds;
        for (z, r) in ends.iter().zip(&c.own) {
            self.certified_runs += 1;
            self.their_runs_s += r.wall_s;
            if r.status != RunStatus::Steady.as_str() || r.class != Some(class) {
                self.class_differences += 1;
                continue;
            }
            let (v, s) = speed_and_deformation(z);
            let (dv, ds) = ((v - r.v).abs(), (s - r.s).abs());
            if dv > SAME_ROOT || ds > SAME_ROOT {
                self.other_root += 1;
                self.other_root_max_dv = self.other_root_max_dv.max(dv);
                self.other_root_max_ds = self.other_root_max_ds.max(ds);
            } else {
                self.same_root_max_dv = self.same_root_max_dv.max(dv);
                self.same_root_max_ds = self.same_root_max_ds.max(ds);
            }
        }
    }
}

/// A map point (its index) and the pairs of coarser points it lies midway between.
type Midpoint = (u32, Vec<[u32; 2]>);

/// One midpoint's certificate and its own runs.
struct Checked {
    point: u32,
    result: Result<(StateClass, Vec<Vec<f64>>), Refusal>,
    seconds: f64,
    own: Vec<RunRow>,
}

/// A map run's end as the certificate reads it.
fn end_of(r: &RunRow) -> End {
    End {
        class: r.class.filter(|_| r.status == RunStatus::Steady.as_str()),
        certified: r.ended_by.as_deref() == Some(Ending::Certified.as_str()),
        z: r.state.clone(),
    }
}
