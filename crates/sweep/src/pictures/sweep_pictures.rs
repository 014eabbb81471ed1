//! The pictures of a sweep from its runs: the phase map (Fig. 2a) with the reduced model's
//! analytic boundaries (and their table, `boundaries.parquet`), and for a 1-D sweep the
//! bifurcation lines (Fig. 2b).
use crate::error::SweepError;
use crate::map::phase_map::PhaseMap;
use crate::pictures::branch_pictures::branch_drawing;
use crate::pictures::line_figure::{vs_parameter, Marker};
use crate::pictures::map_figure::{phase_map, Curve, MapPoint};
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::spec::SweepSpec;
use crate::store::run_store::Store;
use crate::tables::boundaries::NamedCurve;
use droplet_solver::contract::settings::ModelKind;
use droplet_solver::reduced::bifurcation::Axis;
use droplet_solver::reduced::boundaries::boundaries;
use droplet_solver::reduced::coefficients::Coefficients;
use std::path::{Path, PathBuf};

/// The pictures [`plot`] wrote, and how many of the map's points lack a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawn {
    pub files: Vec<PathBuf>,
    pub points: usize,
    /// Points drawn as `missing` (a run not finished, or stored but unreadable).
    pub missing: usize,
}

/// Draws `phase_map.png` / `.svg` of the sweep in `dir` (points without all runs: `missing`),
/// from one consistent snapshot: refused while a sweep or shard works on `dir`. A directory
/// with no run store (a committed result) is drawn from its tables.
pub fn plot(dir: &Path) -> Result<Drawn, SweepError> {
    if crate::tables::read::is_tables_only(dir) {
        let spec = crate::tables::read::stored_spec(&dir.join(crate::tables::read::POINTS))?;
        let drawing = MapDrawing::from_tables(dir)?;
        let files = draw(dir, &spec, &drawing)?;
        return Ok(Drawn {
            files,
            points: drawing.points.len(),
            missing: 0,
        });
    }
    let store = Store::open_idle(dir)?;
    let spec = crate::spec::load_stored(dir)?;
    let plan = crate::map::levels::stored_plan(&spec, &store)?;
    let records = store.load_many(plan.tasks().map(|t| t.key));
    let map = PhaseMap::new(&plan, &records);
    let files = plot_records(dir, &spec, &plan, &records, &map)?;
    Ok(Drawn {
        files,
        points: map.points.len(),
        missing: map.points.iter().filter(|p| !p.complete()).count(),
    })
}

/// What a sweep's pictures show: each point's label and where each settled run ended.
#[derive(Debug, Clone, Default)]
pub struct MapDrawing {
    /// `(eta_t, kappa2, label)` of every point.
    pub points: Vec<(f64, f64, String)>,
    /// Every run that ended on a stable state.
    pub ends: Vec<RunEnd>,
}

/// Where one settled run ended.
#[derive(Debug, Clone, PartialEq)]
pub struct RunEnd {
    pub eta_t: f64,
    pub kappa2: f64,
    pub class: String,
    pub v: f64,
    pub s: f64,
}

impl MapDrawing {
    /// From a sweep's plan, its stored runs and its map.
    pub fn from_runs(
        plan: &crate::store::plan::Plan,
        records: &std::collections::HashMap<String, crate::store::run_store::RunRecord>,
        map: &PhaseMap,
    ) -> Self {
        let points = map
            .points
            .iter()
            .map(|p| (p.eta_t, p.kappa2, p.shown_label().to_string()))
            .collect();
        let ends = plan
            .tasks()
            .filter_map(|t| records.get(&t.key).map(|r| (t, r)))
            .filter_map(|(t, r)| {
                let (eta_t, kappa2) = plan.points[t.point];
                let o = &r.outcome;
                o.class.map(|c| RunEnd {
                    eta_t,
                    kappa2,
                    class: c.as_str().to_string(),
                    v: o.v,
                    s: o.s,
                })
            })
            .collect();
        Self { points, ends }
    }

    /// From a finished map's tables (`points.parquet`, `runs.parquet`).
    pub fn from_tables(dir: &Path) -> Result<Self, SweepError> {
        use crate::tables::read;
        let points = read::points(&dir.join(read::POINTS))?
            .into_iter()
            .map(|p| (p.eta_t, p.kappa2, p.label))
            .collect();
        let ends = read::runs(&dir.join(read::RUNS))?
            .into_iter()
            .filter_map(|r| {
                r.class.map(|c| RunEnd {
                    eta_t: r.params.eta_t,
                    kappa2: r.params.kappa2,
                    class: c.as_str().to_string(),
                    v: r.v,
                    s: r.s,
                })
            })
            .collect();
        Ok(Self { points, ends })
    }
}

/// As [`plot`], from records already loaded (a sweep or merge that just wrote the tables).
pub fn plot_records(
    dir: &Path,
    spec: &SweepSpec,
    plan: &crate::store::plan::Plan,
    records: &std::collections::HashMap<String, crate::store::run_store::RunRecord>,
    map: &PhaseMap,
) -> Result<Vec<PathBuf>, SweepError> {
    draw(dir, spec, &MapDrawing::from_runs(plan, records, map))
}

/// Draws a sweep's pictures into `dir`: the phase map (a 2-D sweep) with the boundaries
/// (writing `boundaries.parquet`: the reduced model's analytic ones, and the full model's if
/// `droplet boundaries` put them there), and the bifurcation lines (a 1-D sweep).
pub fn draw(
    dir: &Path,
    spec: &SweepSpec,
    drawing: &MapDrawing,
) -> Result<Vec<PathBuf>, SweepError> {
    // A refined map: each point drawn as the quarters of the unsplit cells it is a corner of.
    let mut tiles = spec.refine.map(|lattice| {
        let nodes = drawing
            .points
            .iter()
            .map(|&(e, k, _)| lattice.node_of((e, k)))
            .collect();
        (lattice, lattice.tiles(&nodes))
    });
    let pts: Vec<MapPoint> = drawing
        .points
        .iter()
        .map(|(eta_t, kappa2, label)| MapPoint {
            eta_t: *eta_t,
            kappa2: *kappa2,
            label: label.clone(),
            tiles: tiles
                .as_mut()
                .and_then(|(l, t)| t.remove(&l.node_of((*eta_t, *kappa2))))
                .unwrap_or_default(),
        })
        .collect();
    let model = spec.solver.model.as_str().to_uppercase();
    let title = format!(
        "{}: {model} phase map ({} ICs per point)",
        spec.name,
        spec.initial_conditions.len()
    );
    // The reduced model's analytic boundaries (Fig. 3a), over both ODE and PDE maps.
    let coef = Coefficients::new(spec.params.radius, spec.solver.h0);
    let span = |v: &[f64]| {
        v.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            })
    };
    let ode = NamedCurve::from_boundaries(
        ModelKind::Ode,
        &boundaries(&coef, span(&spec.eta_t), span(&spec.kappa2)),
    );
    // The full model's boundaries, if `droplet boundaries` put them here, are kept.
    let path = dir.join(crate::tables::boundaries::FILE);
    let pde = crate::tables::boundaries::read(&path, ModelKind::Pde)?;
    let all: Vec<NamedCurve> = pde.into_iter().chain(ode).collect();
    crate::tables::boundaries::write(&path, &all, Some(&spec.source), Vec::new())?;
    let drawn: Vec<Curve> = all.iter().map(Curve::of).collect();
    let mut files = if spec.eta_t.len() > 1 && spec.kappa2.len() > 1 {
        phase_map(dir, "phase_map", &title, &pts, &drawn)?
    } else {
        Vec::new()
    };
    files.push(path);
    files.extend(lines(dir, spec, &drawing.ends)?);
    Ok(files)
}

/// For a 1-D sweep (one axis with one value, Fig. 2b): `bifurcation_lines.png` / `.svg`,
/// `v` and `s` of every run that ended on a stable state against the swept parameter,
/// coloured by class, over the full model's branches along the line (PDE spectral sweeps:
/// [`pde_branches`], solid where stable, dashed where unstable) — the way a physicist
/// draws Fig. 2b, every run's end on a solid branch.
fn lines(dir: &Path, spec: &SweepSpec, ends: &[RunEnd]) -> Result<Vec<PathBuf>, SweepError> {
    let (along_eta, fixed) = match (spec.eta_t.len(), spec.kappa2.len()) {
        (n, 1) if n > 1 => (true, format!("{KAPPA2} = {}", spec.kappa2[0])),
        (1, n) if n > 1 => (false, format!("{ETA_T} = {}", spec.eta_t[0])),
        _ => return Ok(Vec::new()),
    };
    let mut markers: Vec<Marker> = ends
        .iter()
        .map(|e| Marker {
            x: if along_eta { e.eta_t } else { e.kappa2 },
            v: e.v,
            s: e.s,
            key: e.class.clone(),
            bold: true,
        })
        .collect();
    if markers.is_empty() {
        return Ok(Vec::new());
    }
    let axis = if along_eta { Axis::EtaT } else { Axis::Kappa2 };
    let (lines, events, vlines) = branch_drawing(&pde_branches(spec, axis), axis);
    markers.extend(events.into_iter().map(|e| Marker { bold: false, ..e }));
    let ic_names: Vec<&str> = spec
        .initial_conditions
        .iter()
        .map(|i| i.name.as_str())
        .collect();
    let title = format!(
        "{}: {} runs (ICs {}) on the branches, {fixed}",
        spec.name,
        spec.solver.model.as_str().to_uppercase(),
        ic_names.join(", ")
    );
    vs_parameter(
        dir,
        "bifurcation_lines",
        &title,
        if along_eta { ETA_T } else { KAPPA2 },
        &markers,
        &lines,
        &vlines,
    )
}

/// The full model's branches (IC, ID, MD moving along either axis; on the x axis) along a
/// 1-D sweep's line, by continuation at the sweep's grid: empty for the ODE model and the
/// paper's scheme (their steady states are other equations), and without the families
/// that have no state on the line.
fn pde_branches(spec: &SweepSpec, axis: Axis) -> Vec<droplet_solver::continuation::branch::Branch> {
    use droplet_solver::continuation::{branch::follow, branch::Line, problem::Family};
    if spec.solver.model != droplet_solver::contract::settings::ModelKind::Pde
        || spec.solver.scheme != droplet_solver::stepping::SchemeKind::Spectral
    {
        return Vec::new();
    }
    let values = match axis {
        Axis::EtaT => &spec.eta_t,
        Axis::Kappa2 => &spec.kappa2,
    };
    let (from, to) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let base = droplet_solver::model::params::ModelParams {
        eta_t: spec.eta_t[0],
        kappa2: spec.kappa2[0],
        ..spec.params
    };
    let line = Line {
        base,
        n: spec.solver.n,
        parameter: axis,
        from,
        to,
        max_points: 400,
        opts: Default::default(),
    };
    [Family::IC, Family::ID, Family::MdMinor, Family::MdMajor]
        .iter()
        .filter_map(|f| {
            follow(
                &line,
                *f,
                droplet_solver::roots::steady_solver::MirrorAxis::X,
            )
            .ok()
        })
        .collect()
}
