//! `droplet audit`: every point's label checked against the full model's stable states at
//! that point, independently of how the runs ended.
//!
//! A point's label names the classes its runs ended on ([`crate::phase`]); each class must be
//! a stable steady state of the PDE model there (design notes Sect. 6). For every point:
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
//! Roots met twice at one point (runs from several initial conditions on one state) are
//! checked once. Points run in parallel, one steady solver per worker.
use crate::error::SweepError;
use crate::phase::classify_point;
use crate::store::{RunRecord, Store};
use droplet_solver::newton::{solve, NewtonOptions};
use droplet_solver::stability::Linearization;
use droplet_solver::verdict::{assess, Verdict};
use droplet_solver::{ModelKind, ModelParams, RunStatus, SchemeKind, StateClass, SteadySolver};
use rayon::prelude::*;
use serde::Serialize;
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
}

impl Kind {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Unsettled => "unsettled",
            Self::UnstableDisk => "unstable_disk",
            Self::NoRoot => "no_root",
            Self::OtherClass => "other_class",
            Self::UnstableRoot => "unstable_root",
        }
    }
}

/// One contradiction: the run that caused it and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Contradiction {
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
    /// Points whose label has no contradiction.
    pub points_clean: usize,
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

/// Speed and deformation of `(vx, vy, a2, b2)`.
fn class_of(z: &[f64; 4]) -> StateClass {
    StateClass::of(z[0].hypot(z[1]), z[2].hypot(z[3]))
}

/// The verdict of the steady state near `z` at `params`: the root and its eigenvalues, or
/// `None` when Newton does not converge from `z`.
fn root_near(solver: &mut SteadySolver, z: [f64; 4]) -> Option<([f64; 4], Verdict)> {
    let p = *solver.params();
    let opts = NewtonOptions {
        tol: 1e-11,
        max_iter: 30,
        fd_step: 1e-6,
        max_step: vec![f64::INFINITY, f64::INFINITY, 0.2, 0.2],
    };
    let sol = solve(
        |x| {
            let f = solver.forces(x[0], x[1], x[2], x[3]);
            droplet_solver::dynamics::force_balance(&p, [x[0], x[1], x[2], x[3]], &f).to_vec()
        },
        &z,
        &opts,
    )
    .ok()?;
    let root = [sol.x[0], sol.x[1], sol.x[2], sol.x[3]];
    Some((root, assess(&Linearization::at(solver, root), root)))
}

/// The growing eigenvalues of a verdict, as text.
fn growth(v: &Verdict) -> String {
    format!(
        "{} growing mode(s), largest {:+.3e}",
        v.unstable, v.max_re
    )
}

/// Audits the runs of one point (all stored; spec order of initial conditions).
fn audit_point(
    solver: &mut SteadySolver,
    runs: &[&RunRecord],
    label: &str,
    states: &mut usize,
) -> Vec<Contradiction> {
    let mut out = Vec::new();
    let mut disk: Option<Verdict> = None;
    let mut roots: Vec<([f64; 4], Option<([f64; 4], Verdict)>)> = Vec::new();
    for r in runs {
        let (eta_t, kappa2) = (r.params.eta_t, r.params.kappa2);
        let o = &r.outcome;
        let mut add = |kind: Kind, detail: String| {
            out.push(Contradiction {
                eta_t,
                kappa2,
                label: label.to_string(),
                ic: r.ic.name.clone(),
                class: o.class.map(|c| c.as_str().to_string()),
                kind,
                detail,
                key: r.key.clone(),
            })
        };
        match (o.status, o.class) {
            (RunStatus::Diverged, _) => {}
            (RunStatus::Steady, Some(StateClass::IC)) => {
                let v = disk.get_or_insert_with(|| {
                    *states += 1;
                    assess(&Linearization::at(solver, [0.0; 4]), [0.0; 4])
                });
                if !v.stable() {
                    add(
                        Kind::UnstableDisk,
                        format!("the resting disk is unstable here: {}", growth(v)),
                    );
                }
            }
            (RunStatus::Steady, Some(class)) => {
                let z = o.state.monitored();
                let known = roots
                    .iter()
                    .find(|(start, _)| droplet_solver::state::max_distance(start, &z) < 1e-9);
                let found = match known {
                    Some((_, f)) => f.clone(),
                    None => {
                        let f = root_near(solver, z);
                        *states += usize::from(f.is_some());
                        roots.push((z, f.clone()));
                        f
                    }
                };
                match found {
                    None => add(
                        Kind::NoRoot,
                        format!("Newton finds no steady state from the run's final state {z:?}"),
                    ),
                    Some((root, _)) if class_of(&root) != class => add(
                        Kind::OtherClass,
                        format!(
                            "the steady state there is {} (v = {:.6}, s = {:.6})",
                            class_of(&root),
                            root[0].hypot(root[1]),
                            root[2].hypot(root[3])
                        ),
                    ),
                    Some((_, v)) if !v.stable() => add(
                        Kind::UnstableRoot,
                        format!("the {class} state is unstable here: {}", growth(&v)),
                    ),
                    Some(_) => {}
                }
            }
            _ => add(
                Kind::Unsettled,
                format!(
                    "{} at t = {:.1}: {}{}",
                    o.status.as_str(),
                    o.t_end,
                    o.unsettled.map_or("not ended on a stable state", |u| u.as_str()),
                    o.heading
                        .map_or(String::new(), |h| format!(", heading to {h}"))
                ),
            ),
        }
    }
    out
}

/// Audits the sweep in `dir` (its stored spec and runs; refused while a sweep works there).
pub fn audit(dir: &Path) -> Result<Audit, SweepError> {
    let store = Store::open_idle(dir)?;
    let spec = crate::spec::load_stored(dir)?;
    if spec.solver.model != ModelKind::Pde || spec.solver.scheme != SchemeKind::Spectral {
        return Err(SweepError::Invalid(format!(
            "{}: audit checks maps of the PDE model with the spectral scheme (its steady \
             equations and eigenvalues); this sweep has model {} and scheme {}",
            dir.display(),
            spec.solver.model.as_str(),
            spec.solver.scheme.as_str()
        )));
    }
    let plan = crate::level_walk::stored_plan(&spec, &store)?;
    let records = store.load_many(plan.tasks().map(|t| t.key));
    let mut by_point: Vec<Vec<&RunRecord>> = vec![Vec::new(); plan.points.len()];
    let mut missing = 0;
    for t in plan.tasks() {
        match records.get(&t.key) {
            Some(r) => by_point[t.point].push(r),
            None => missing += 1,
        }
    }
    if missing > 0 {
        return Err(SweepError::Invalid(format!(
            "{}: {missing} runs are not stored (the sweep is unfinished); finish it with \
             `droplet sweep` before auditing (`droplet status {}` counts them)",
            dir.display(),
            dir.display()
        )));
    }
    let n = spec.solver.n;
    // Fails here, not in a worker, if the solver cannot be made.
    SteadySolver::new(spec.params, n)?;
    let results: Vec<(Vec<Contradiction>, usize)> = by_point
        .par_iter()
        .map_init(
            || None::<SteadySolver>,
            |slot, runs| {
                let Some(first) = runs.first() else {
                    return (Vec::new(), 0);
                };
                let p = first.params;
                // One solver per worker, moved between points by (eta_t, kappa2); a new one
                // when another parameter differs (a sweep over it).
                let reusable = slot.as_ref().is_some_and(|s| {
                    ModelParams {
                        eta_t: p.eta_t,
                        kappa2: p.kappa2,
                        ..*s.params()
                    } == p
                });
                if !reusable {
                    *slot = SteadySolver::new(p, n).ok();
                }
                let Some(solver) = slot.as_mut() else {
                    return (Vec::new(), 0);
                };
                solver.set_control(p.eta_t, p.kappa2);
                let label = classify_point(runs.iter().copied()).label;
                let mut states = 0;
                let c = audit_point(solver, runs, &label, &mut states);
                (c, states)
            },
        )
        .collect();
    let points = plan.points.len();
    let points_clean = results.iter().filter(|(c, _)| c.is_empty()).count();
    Ok(Audit {
        points,
        runs: plan.len(),
        points_clean,
        states_checked: results.iter().map(|(_, s)| s).sum(),
        contradictions: results.into_iter().flat_map(|(c, _)| c).collect(),
    })
}
