//! What the audit checks without solving anything, on every point: that the map is complete
//! (every point of the points table has one run of each of the spec's initial conditions,
//! and no run is foreign), and that each point's label is the one its runs give.
use super::{Contradiction, Kind};
use crate::tables::read::{PointRow, RunRow as Row};
use droplet_solver::contract::outcome::RunStatus;
use droplet_solver::model::classify::StateClass;
use std::collections::{BTreeMap, BTreeSet};

/// The label mismatch of one point: the points table's `label` against the one its `runs`
/// give (`None` when they agree).
pub(super) fn label_mismatch(runs: &[&Row], label: &str) -> Option<Contradiction> {
    let expected = expected_label(runs);
    let r = runs.first().filter(|_| expected != label)?;
    Some(Contradiction {
        point: r.point,
        eta_t: r.params.eta_t,
        kappa2: r.params.kappa2,
        label: label.to_string(),
        ic: "-".into(),
        class: None,
        kind: Kind::LabelMismatch,
        detail: format!("the points table says {label}, its runs give {expected}"),
        key: "-".into(),
    })
}

/// The label a point's runs give ([`crate::map::point_class`]: the classes of the runs that ended
/// steady).
fn expected_label(runs: &[&Row]) -> String {
    let classes: BTreeSet<StateClass> = runs
        .iter()
        .filter(|r| r.status == RunStatus::Steady.as_str())
        .filter_map(|r| r.class)
        .collect();
    let count = |status: &str| runs.iter().filter(|r| r.status == status).count();
    let diverged = count(RunStatus::Diverged.as_str());
    let unsettled = runs.len() - count(RunStatus::Steady.as_str()) - diverged;
    crate::map::point_class::label_of(&classes, runs.len(), diverged, unsettled)
}

/// Whether every point of the points table has exactly one run of each of the spec's
/// initial conditions `ics`, and no run is of another condition or of a point it does not
/// list: a map with a run deleted, duplicated or foreign is not certified, whatever its
/// other runs show. (A point's label is then also checked against the runs it has.)
pub(super) fn completeness(
    points: &[PointRow],
    runs: &BTreeMap<u32, Vec<Row>>,
    ics: &[String],
) -> Vec<Contradiction> {
    let mut out = Vec::new();
    let mut flag = |(point, eta_t, kappa2): (u32, f64, f64),
                    label: &str,
                    ic: &str,
                    kind: Kind,
                    detail: String,
                    key: &str| {
        out.push(Contradiction {
            point,
            eta_t,
            kappa2,
            label: label.to_string(),
            ic: ic.to_string(),
            class: None,
            kind,
            detail,
            key: key.to_string(),
        })
    };
    let listed: BTreeSet<u32> = points.iter().map(|p| p.point).collect();
    for (p, rows) in runs.iter().filter(|(p, _)| !listed.contains(p)) {
        for r in rows {
            let detail = format!("a run of point {p}, which points.parquet does not list");
            let at = (*p, r.params.eta_t, r.params.kappa2);
            flag(at, "-", &r.ic, Kind::UnknownRun, detail, &r.key);
        }
    }
    for point in points {
        let rows = runs.get(&point.point).map_or(&[][..], Vec::as_slice);
        // A point without runs is named by its coordinates in the sweep's plane.
        let (eta_t, kappa2) = rows
            .first()
            .map_or((point.x, point.y), |r| (r.params.eta_t, r.params.kappa2));
        let at = (point.point, eta_t, kappa2);
        for ic in ics {
            let of_ic: Vec<&Row> = rows.iter().filter(|r| &r.ic == ic).collect();
            match of_ic.len() {
                1 => {}
                0 => flag(
                    at,
                    &point.label,
                    ic,
                    Kind::MissingRun,
                    format!(
                        "point {} has no run from initial condition {ic}",
                        point.point
                    ),
                    "-",
                ),
                n => flag(
                    at,
                    &point.label,
                    ic,
                    Kind::DuplicateRun,
                    format!(
                        "point {} has {n} runs from initial condition {ic}",
                        point.point
                    ),
                    &of_ic[1].key,
                ),
            }
        }
        for r in rows.iter().filter(|r| !ics.contains(&r.ic)) {
            let detail = format!(
                "initial condition {} is not one of the spec's ({})",
                r.ic,
                ics.join(", ")
            );
            flag(at, &point.label, &r.ic, Kind::UnknownRun, detail, &r.key);
        }
    }
    out
}
