//! `droplet audit`: every point's label checked against the full model's stable states at
//! that point, independently of how the runs ended.
//!
//! A point's label names the classes its runs ended on ([`crate::map::point_class`]); each class must be
//! a stable steady state of the PDE model there (docs/model.md, "Steady states as roots"). For every point:
//! - the resting disk's eigenvalues are computed at the point (the exact, pointwise form of
//!   the onsets of motion and of deformation): a run labelled IC contradicts when one grows;
//! - every other run's final `(vx, vy, a2, b2)` is taken as a starting guess for Newton on
//!   all four steady equations (its own solver and tolerances, not the run's finish): the
//!   run contradicts when Newton finds no root there, when the root has another class (e.g.
//!   a moving root with `s <= 0.01` under an MD label: the MC side of the `s = 0.01` curve),
//!   or when the root has a growing eigenvalue besides the near-neutral rotation mode;
//! - a run that did not end on a stable state (`unsettled`) is listed too: its point's label
//!   is not proven.
//!
//! - the points table's label must be the one its runs give ([`crate::map::point_class`]'s rule), so a
//!   label edited by hand, or written by an older rule (a class from a run that had not
//!   settled), is caught too.
//!
//! A map of the general model (`params.modes: K`) is checked the same way with its own
//! equations: the disk's `2K x 2K` eigenvalues, Newton on all `2K` balances from each run's
//! final `(vx, vy, a2..aK, b2..bK)` ([`point_model`]).
//!
//! It reads the tables a sweep leaves (`runs.parquet`, `points.parquet`), so committed maps
//! are audited as they are. Roots met twice at one point (runs from several initial
//! conditions on one state) are checked once. Points run in parallel, one steady solver
//! per worker.
//!
//! May use: `spec`, `store`, `map`, `tables`. Used by: the CLI.

mod completeness;
mod point_model;

use crate::error::SweepError;
use crate::tables::read::{self as tables, RunRow as Row};
use droplet_solver::roots::balances::Balances;
use droplet_solver::{
    contract::outcome::RunStatus, model::classify::StateClass, model::params::ModelParams,
};
use point_model::{Growth, Root};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// What is wrong with one run's part in its point's label.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// The run did not end on a stable state: the label is not proven.
    Unsettled,
    /// Labelled IC where the resting disk has a growing mode.
    UnstableDisk,
    /// Newton finds no steady state at the run's final state.
    NoRoot,
    /// The root at the run's final state has another class than the run.
    OtherClass,
    /// The root has a growing eigenvalue (the rotation mode aside).
    UnstableRoot,
    /// The points table's label is not the one its runs give.
    LabelMismatch,
    /// A run of one of the spec's initial conditions is not in the runs table.
    MissingRun,
    /// A run is in the runs table more than once.
    DuplicateRun,
    /// A run of an initial condition the spec does not have, or of a point the points
    /// table does not list.
    UnknownRun,
}

impl Kind {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Unsettled => "unsettled",
            Self::UnstableDisk => "unstable_disk",
            Self::NoRoot => "no_root",
            Self::OtherClass => "other_class",
            Self::UnstableRoot => "unstable_root",
            Self::LabelMismatch => "label_mismatch",
            Self::MissingRun => "missing_run",
            Self::DuplicateRun => "duplicate_run",
            Self::UnknownRun => "unknown_run",
        }
    }
}

/// One contradiction: the run that caused it and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Contradiction {
    /// The point's index in the tables.
    pub point: u32,
    pub eta_t: f64,
    pub kappa2: f64,
    /// The point's label.
    pub label: String,
    pub ic: String,
    /// The run's class (`None`: unsettled).
    pub class: Option<String>,
    pub kind: Kind,
    pub detail: String,
    /// The run's key in the store.
    pub key: String,
}

/// The audit of one sweep directory.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Audit {
    pub points: usize,
    pub runs: usize,
    /// Points whose label has no contradiction (with a sample: none among the checks made).
    pub points_clean: usize,
    /// With a sample: the points whose stable states were checked (`None`: every point).
    pub sampled: Option<usize>,
    /// Distinct steady states whose eigenvalues were computed (resting disks included).
    pub states_checked: usize,
    pub contradictions: Vec<Contradiction>,
}

impl Audit {
    /// Contradictions of each kind, in [`Kind`] order.
    pub fn by_kind(&self) -> Vec<(Kind, usize)> {
        let mut counts = std::collections::BTreeMap::new();
        for c in &self.contradictions {
            *counts.entry(c.kind).or_insert(0) += 1;
        }
        counts.into_iter().collect()
    }
}

/// A root found from a run's final state (`None`: Newton did not converge).
type Checked = Option<Root>;

/// Audits the runs of one point (spec order of initial conditions) under `label`.
fn audit_point(
    model: &mut Balances,
    runs: &[&Row],
    label: &str,
    states: &mut usize,
) -> Vec<Contradiction> {
    let mut out = Vec::new();
    let mut point = PointStates {
        model,
        disk: None,
        roots: Vec::new(),
        states,
    };
    for r in runs {
        let steady = r.status == RunStatus::Steady.as_str();
        let problem = match (r.status.as_str(), r.class) {
            ("diverged", _) => None,
            (_, Some(StateClass::IC)) if steady => point.check_disk(),
            (_, Some(class)) if steady => point.check_root(&r.state, class),
            _ => Some((Kind::Unsettled, unsettled_detail(r))),
        };
        if let Some((kind, detail)) = problem {
            out.push(Contradiction {
                point: r.point,
                eta_t: r.params.eta_t,
                kappa2: r.params.kappa2,
                label: label.to_string(),
                ic: r.ic.clone(),
                class: r.class.map(|c| c.as_str().to_string()),
                kind,
                detail,
                key: r.key.clone(),
            });
        }
    }
    out
}

/// The steady states met at one point, each computed once: the resting disk's growth and the
/// roots near the runs' final states (counted in `states`).
struct PointStates<'a> {
    model: &'a mut Balances,
    disk: Option<Growth>,
    roots: Vec<(Vec<f64>, Checked)>,
    states: &'a mut usize,
}

impl PointStates<'_> {
    /// An IC run: the resting disk must be stable here.
    fn check_disk(&mut self) -> Option<(Kind, String)> {
        let (model, states) = (&mut *self.model, &mut *self.states);
        let g = *self.disk.get_or_insert_with(|| {
            *states += 1;
            point_model::disk(model)
        });
        (!g.stable()).then(|| {
            (
                Kind::UnstableDisk,
                format!("the resting disk is unstable here: {g}"),
            )
        })
    }

    /// A run of `class` ending at `z`: Newton from `z` must find a stable root of that class.
    fn check_root(&mut self, z: &[f64], class: StateClass) -> Option<(Kind, String)> {
        let near = |start: &[f64]| {
            start.len() == z.len() && start.iter().zip(z).all(|(a, b)| (a - b).abs() < 1e-9)
        };
        let found = match self.roots.iter().find(|(start, _)| near(start)) {
            Some((_, f)) => *f,
            None => {
                let f = point_model::root_near(self.model, z);
                *self.states += usize::from(f.is_some());
                self.roots.push((z.to_vec(), f));
                f
            }
        };
        match found {
            None => Some((
                Kind::NoRoot,
                format!("Newton finds no steady state from the run's final state {z:?}"),
            )),
            Some(root) if StateClass::of(root.v, root.s) != class => Some((
                Kind::OtherClass,
                format!(
                    "the steady state there is {} (v = {:.6}, s = {:.6})",
                    StateClass::of(root.v, root.s),
                    root.v,
                    root.s
                ),
            )),
            Some(root) if !root.growth.stable() => Some((
                Kind::UnstableRoot,
                format!("the {class} state is unstable here: {}", root.growth),
            )),
            Some(_) => None,
        }
    }
}

/// Why a run that did not settle says its point's label is not proven.
fn unsettled_detail(r: &Row) -> String {
    format!(
        "{} at t = {:.1}: {}{}",
        r.status,
        r.t_end,
        r.unsettled
            .as_deref()
            .unwrap_or("did not end on a stable state"),
        r.heading
            .as_ref()
            .map_or(String::new(), |h| format!(", heading to {h}"))
    )
}

/// The runs by point; only maps of the PDE model with the spectral scheme (their steady
/// equations and eigenvalues are what the audit computes).
fn by_point(rows: Vec<Row>) -> Result<BTreeMap<u32, Vec<Row>>, SweepError> {
    let mut out: BTreeMap<u32, Vec<Row>> = BTreeMap::new();
    for r in rows {
        if r.model != "pde" || r.scheme != "spectral" {
            return Err(SweepError::Invalid(format!(
                "audit checks maps of the PDE model with the spectral scheme (its steady \
                 equations and eigenvalues); this one has model {} and scheme {}",
                r.model, r.scheme
            )));
        }
        out.entry(r.point).or_default().push(r);
    }
    Ok(out)
}

pub use crate::map::sample::Sample;

/// Refuses a map whose runs hold more than one model's shape modes `(K, friction exponent)`,
/// naming the map.
fn one_model(dir: &Path, runs: &BTreeMap<u32, Vec<Row>>) -> Result<(), SweepError> {
    let modes = runs
        .values()
        .flatten()
        .map(|r| r.params.modes)
        .max()
        .unwrap_or(2);
    let law = runs
        .values()
        .flatten()
        .next()
        .map_or(0.0, |r| r.params.eta_k_exponent);
    if let Some(r) = runs
        .values()
        .flatten()
        .find(|r| r.params.modes != modes || r.params.eta_k_exponent != law)
    {
        return Err(SweepError::Invalid(format!(
            "{}: runs with {} and {modes} shape modes (friction exponents {} and {law}) in one \
             map; audit checks one model",
            dir.display(),
            r.params.modes,
            r.params.eta_k_exponent
        )));
    }
    Ok(())
}

/// Every point's states checked against its label, the points spread over the workers: the
/// contradictions and the number of states checked per point.
fn check_points(groups: &[(&String, Vec<&Row>)]) -> Vec<(Vec<Contradiction>, usize)> {
    groups
        .par_iter()
        .map_init(
            || None::<Balances>,
            |slot, (label, rows)| {
                let Some(first) = rows.first() else {
                    return (Vec::new(), 0);
                };
                let (p, n) = (first.params, first.n);
                // One solver per worker, moved between points by (eta_t, kappa2); a new one
                // when another parameter or the grid differs.
                let reusable = slot.as_ref().is_some_and(|m| {
                    m.n() == n
                        && ModelParams {
                            eta_t: p.eta_t,
                            kappa2: p.kappa2,
                            ..*m.params()
                        } == p
                });
                if !reusable {
                    *slot = point_model::for_map(p, n).ok();
                }
                let Some(model) = slot.as_mut() else {
                    return (Vec::new(), 0);
                };
                model.set_control(p.eta_t, p.kappa2);
                let mut states = 0;
                let c = audit_point(model, rows, label, &mut states);
                (c, states)
            },
        )
        .collect()
}

/// Audits the map in `dir` (its `runs.parquet` and `points.parquet`), with the steady
/// equations and eigenvalues of its model: the paper's 2-mode model, or the general one with
/// the map's shape modes `2..K` (`params.modes`). Completeness and labels are checked at every
/// point; the stable states at every point, or with `sample` at that sample of points (the
/// full audit of a large map takes minutes; a sample shows a stale or edited map in seconds).
pub fn audit(dir: &Path, sample: Option<Sample>) -> Result<Audit, SweepError> {
    let runs_path = dir.join(tables::RUNS);
    let runs = by_point(tables::runs(&runs_path)?)?;
    let points = tables::points(&dir.join(tables::POINTS))?;
    if points.is_empty() || runs.is_empty() {
        return Err(SweepError::Invalid(format!(
            "{}: the map has {} points and {} runs; there is nothing to certify",
            dir.display(),
            points.len(),
            runs.len()
        )));
    }
    let ics: Vec<String> = tables::stored_spec(&runs_path)?
        .initial_conditions
        .iter()
        .map(|ic| ic.name.clone())
        .collect();
    let complete = completeness::completeness(&points, &runs, &ics);
    let labelled: BTreeMap<u32, String> = points.into_iter().map(|p| (p.point, p.label)).collect();
    one_model(dir, &runs)?;
    let mismatched: Vec<Contradiction> = runs
        .iter()
        .filter_map(|(p, rows)| {
            let rows: Vec<&Row> = rows.iter().collect();
            completeness::label_mismatch(&rows, labelled.get(p)?)
        })
        .collect();
    let drawn = sample.map(|s| s.draw(runs.keys().copied().filter(|p| labelled.contains_key(p))));
    let groups: Vec<(&String, Vec<&Row>)> = runs
        .iter()
        .filter(|(p, _)| drawn.as_ref().is_none_or(|d| d.contains(p)))
        .filter_map(|(p, rows)| Some((labelled.get(p)?, rows.iter().collect())))
        .collect();
    if let Some(first) = groups.first().and_then(|(_, r)| r.first()) {
        // Fails here, not in a worker, if the solver cannot be made.
        point_model::for_map(first.params, first.n)?;
    }
    let results = check_points(&groups);
    let states_checked = results.iter().map(|(_, s)| s).sum();
    let states_points = groups.len();
    let contradictions: Vec<Contradiction> = complete
        .into_iter()
        .chain(mismatched)
        .chain(results.into_iter().flat_map(|(c, _)| c))
        .collect();
    let flawed: BTreeSet<u32> = contradictions
        .iter()
        .map(|c| c.point)
        .filter(|p| labelled.contains_key(p))
        .collect();
    Ok(Audit {
        points: labelled.len(),
        runs: runs.values().map(Vec::len).sum(),
        points_clean: labelled.len().saturating_sub(flawed.len()),
        sampled: drawn.map(|_| states_points),
        states_checked,
        contradictions,
    })
}
