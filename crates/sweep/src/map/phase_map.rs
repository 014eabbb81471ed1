//! The phase map of a sweep: every point with its class (from [`crate::map::point_class`]) and the end
//! of each of its runs, computed once from the plan and the stored runs, and read by the
//! points table, `droplet status` and the picture.
use crate::map::end_shape::EndShape;
use crate::map::point_class::{classify_point, PointClass, MISSING};
use crate::map::tally::tally;
use crate::store::plan::Plan;
use crate::store::run_store::RunRecord;
use droplet_solver::contract::outcome::RunStatus;
use std::collections::{BTreeMap, HashMap};

/// One point of the map.
#[derive(Debug, Clone, PartialEq)]
pub struct MapEntry {
    /// Its coordinates (`[x, y, z]`, [`crate::spec::axes::Plane`]).
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// Refinement level (0: the spec's grid).
    pub level: u32,
    /// Cell size `(dx, dy)` of its level.
    pub cell: (f64, f64),
    pub class: PointClass,
    /// How the run from each initial condition ended (spec order): its class, `diverged` or
    /// `unsettled`; `None` while the run is not stored.
    pub per_ic: Vec<Option<String>>,
    /// The shape each initial condition's run settled on (spec order; `None` for a run not
    /// stored or not settled): the K-mode columns of the points table.
    pub shapes: Vec<Option<EndShape>>,
}

impl MapEntry {
    /// Every run of the point is stored.
    pub fn complete(&self) -> bool {
        self.per_ic.iter().all(Option::is_some)
    }

    /// The label to show: the point class, or `missing` while runs are outstanding.
    pub fn shown_label(&self) -> &str {
        if self.complete() {
            &self.class.label
        } else {
            MISSING
        }
    }
}

/// All points of a plan, classified.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseMap {
    /// The swept parameters.
    pub plane: crate::spec::axes::Plane,
    pub points: Vec<MapEntry>,
    pub ic_names: Vec<String>,
}

/// How one run ended, as the points table shows it: the class of the stable state it ended
/// on, `diverged`, or `unsettled`.
fn run_end(r: &RunRecord) -> String {
    match (r.outcome.status, r.outcome.class) {
        (RunStatus::Steady, Some(c)) => c.as_str().to_string(),
        (RunStatus::Diverged, _) => RunStatus::Diverged.as_str().to_string(),
        _ => crate::map::point_class::UNSETTLED.to_string(),
    }
}

impl PhaseMap {
    /// Classifies every point of `plan` from `records` (runs not stored count as absent).
    pub fn new(plan: &Plan, records: &HashMap<String, RunRecord>) -> Self {
        let mut by_point: Vec<Vec<Option<&RunRecord>>> =
            vec![vec![None; plan.ic_names.len()]; plan.points.len()];
        for t in plan.tasks() {
            by_point[t.point][t.ic_index] = records.get(&t.key);
        }
        let points = by_point
            .iter()
            .enumerate()
            .map(|(i, runs)| MapEntry {
                x: plan.points[i][0],
                y: plan.points[i][1],
                z: plan.points[i][2],
                level: plan.levels[i],
                cell: plan.cells[i],
                class: classify_point(runs.iter().flatten().copied()),
                per_ic: runs.iter().map(|r| r.map(run_end)).collect(),
                shapes: runs
                    .iter()
                    .map(|r| {
                        r.filter(|r| r.outcome.status == RunStatus::Steady)
                            .map(EndShape::of)
                    })
                    .collect(),
            })
            .collect();
        Self {
            plane: plan.plane,
            points,
            ic_names: plan.ic_names.clone(),
        }
    }

    /// Count of each point class over the complete points.
    pub fn class_counts(&self) -> BTreeMap<String, usize> {
        tally(
            self.points
                .iter()
                .filter(|p| p.complete())
                .map(|p| p.class.label.clone()),
        )
    }
}
