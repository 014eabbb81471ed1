//! Bifurcation diagrams as pictures: the reduced model's steady states along a line (Fig. 3b
//! style) and the full model's continuation branches, both `v` and `s` against the varied
//! parameter, solid where stable and dashed where unstable, with their P / SN points.
use crate::error::SweepError;
use crate::pictures::branch_lines::{branch_lines, BranchSample};
use crate::pictures::line_figure::{vs_parameter, Marker};
use droplet_solver::model::param::ModelParam;
use droplet_solver::reduced::bifurcation::{Branch, Event, SteadyPoint};
use std::path::{Path, PathBuf};

/// The reduced model's bifurcation diagram along a line (Fig. 3b style) as `<stem>.png` and
/// `.svg` in `dir`: branches as lines (solid stable, dashed unstable, closed up at their
/// events), markers only at the P / SN points, each bifurcation labelled once.
pub fn ode_bifurcation(
    dir: &Path,
    stem: &str,
    pts: &[SteadyPoint],
    events: &[Event],
    axis: ModelParam,
    title: &str,
) -> Result<Vec<PathBuf>, SweepError> {
    let x_label = axis.name();
    let x_of = |p: &SteadyPoint| axis.get(&p.params);
    let (lo, hi) = pts
        .iter()
        .map(x_of)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    let span = hi - lo;
    // Branches as lines (solid stable, dashed unstable); markers only at P / SN.
    let samples: Vec<BranchSample> = pts
        .iter()
        .map(|p| BranchSample {
            key: p.branch.as_str().to_string(),
            x: x_of(p),
            v: p.v,
            s: p.s,
            stable: p.stable,
        })
        .collect();
    let at: Vec<(String, f64)> = events
        .iter()
        .map(|e| (e.branch.as_str().to_string(), e.at))
        .collect();
    let lines = branch_lines(&samples, &at);
    let markers: Vec<Marker> = events
        .iter()
        .filter_map(|e| {
            // The state of the event's branch nearest to the event.
            samples
                .iter()
                .filter(|p| p.key == e.branch.as_str())
                .min_by(|a, b| (a.x - e.at).abs().total_cmp(&(b.x - e.at).abs()))
                .map(|p| Marker {
                    x: e.at,
                    v: p.v,
                    s: p.s,
                    key: p.key.clone(),
                    bold: true,
                })
        })
        .collect();
    // Label each bifurcation once (the first of a cluster).
    let mut vlines: Vec<(f64, String)> = Vec::new();
    for e in events {
        if e.branch == Branch::MdMajor {
            continue;
        }
        if !vlines
            .iter()
            .any(|(x, l)| (x - e.at).abs() < span * 0.004 && l == e.kind)
        {
            vlines.push((e.at, e.kind.to_string()));
        }
    }
    vs_parameter(dir, stem, title, x_label, &markers, &lines, &vlines)
}

/// The full model's branches along a line (PDE Fig. 3b): `<stem>.png` / `.svg` in `dir`, each
/// branch drawn in its order along the continuation, solid where stable and dashed where
/// unstable (the rotation mode set aside), a marker and a labelled vertical line at every
/// P / SN / H point.
pub fn continuation(
    dir: &Path,
    stem: &str,
    branches: &[droplet_solver::continuation::branch::Branch],
    parameter: ModelParam,
    title: &str,
) -> Result<Vec<PathBuf>, SweepError> {
    let (lines, markers, vlines) = branch_drawing(branches);
    vs_parameter(
        dir,
        stem,
        title,
        parameter.name(),
        &markers,
        &lines,
        &vlines,
    )
}

/// The lines (solid stable, dashed unstable), event markers and labelled event positions of
/// the full model's branches along a line.
pub(crate) fn branch_drawing(
    branches: &[droplet_solver::continuation::branch::Branch],
) -> (
    Vec<crate::pictures::branch_lines::BranchLine>,
    Vec<Marker>,
    Vec<(f64, String)>,
) {
    use crate::pictures::branch_lines::BranchLine;
    let x_of = |p: &droplet_solver::continuation::branch::BranchPoint| p.at;
    let mut lines: Vec<BranchLine> = Vec::new();
    let mut markers = Vec::new();
    let mut vlines: Vec<(f64, String)> = Vec::new();
    for b in branches {
        let key = b.family.as_str().to_string();
        let mut current: Option<BranchLine> = None;
        for p in &b.points {
            let stable = p.verdict.stable();
            let xyz = (x_of(p), p.v, p.s);
            match current.as_mut() {
                Some(line) if line.stable == stable => line.points.push(xyz),
                _ => {
                    if let Some(mut done) = current.take() {
                        // The pieces meet at the state where stability changes.
                        done.points.push(xyz);
                        lines.push(done);
                    }
                    current = Some(BranchLine {
                        key: key.clone(),
                        points: vec![xyz],
                        stable,
                    });
                }
            }
        }
        lines.extend(current);
        for e in &b.events {
            let x = x_of(&e.point);
            markers.push(Marker {
                x,
                v: e.point.v,
                s: e.point.s,
                key: key.clone(),
                bold: true,
            });
            let (lo, hi) = b
                .points
                .iter()
                .map(x_of)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, c), x| {
                    (a.min(x), c.max(x))
                });
            let near = (hi - lo).abs() * 0.004;
            if !vlines
                .iter()
                .any(|(at, k)| (at - x).abs() <= near && k == e.kind)
            {
                vlines.push((x, e.kind.to_string()));
            }
        }
    }
    (lines, markers, vlines)
}
