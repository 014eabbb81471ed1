//! The pictures of a sweep from its runs: the phase map (Fig. 2a) with the reduced model's
//! analytic boundaries (and their table, `boundaries.parquet`), and for a 1-D sweep the
//! bifurcation lines (Fig. 2b).
use crate::error::SweepError;
use crate::map::phase_map::PhaseMap;
use crate::pictures::branch_pictures::branch_drawing;
use crate::pictures::line_figure::{vs_parameter, Marker};
use crate::pictures::map_figure::{phase_map, Curve, MapPoint};
use crate::pictures::slice_figure::{slice_maps, Panel};
use crate::spec::axes::{Param, Point};
use crate::spec::lattice::Node;
use crate::spec::SweepSpec;
use crate::store::run_store::Store;
use crate::tables::boundaries::NamedCurve;
use droplet_solver::contract::settings::ModelKind;
use droplet_solver::reduced::boundaries::boundaries;
use droplet_solver::reduced::coefficients::Coefficients;
use std::collections::{BTreeMap, BTreeSet, HashMap};
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
/// with no run store (a committed result) is drawn from its tables. A finished map (tables
/// written) whose stored runs lack a point is refused, its pictures left as they are.
pub fn plot(dir: &Path) -> Result<Drawn, SweepError> {
    if crate::tables::read::is_tables_only(dir) {
        return plot_tables(dir);
    }
    plot_in(&Store::open_idle(dir)?)
}

/// The pictures of the finished map in `dir` drawn from its tables alone.
pub fn plot_tables(dir: &Path) -> Result<Drawn, SweepError> {
    let spec = crate::tables::read::stored_spec(&dir.join(crate::tables::read::POINTS))?;
    let drawing = MapDrawing::from_tables(dir)?;
    let files = draw(dir, &spec, &drawing)?;
    Ok(Drawn {
        files,
        points: drawing.points.len(),
        missing: 0,
    })
}

/// [`plot`] of the sweep whose store `store` the caller holds open to write (its lock taken).
pub fn plot_in(store: &Store) -> Result<Drawn, SweepError> {
    let dir = store.dir();
    let spec = crate::spec::load_stored(dir)?;
    let plan = crate::map::levels::stored_plan(&spec, store)?;
    let records = store.load_many(plan.tasks().map(|t| t.key));
    let map = PhaseMap::new(&plan, &records);
    let missing = map.points.iter().filter(|p| !p.complete()).count();
    if missing > 0 && dir.join(crate::tables::read::POINTS).is_file() {
        // A finished map's pictures are never replaced by a picture of missing points.
        return Err(SweepError::StaleRuns {
            dir: dir.to_path_buf(),
            missing,
            points: map.points.len(),
        });
    }
    let files = plot_records(dir, &spec, &plan, &records, &map)?;
    Ok(Drawn {
        files,
        points: map.points.len(),
        missing,
    })
}

/// What a sweep's pictures show: each point's label and where each settled run ended.
#[derive(Debug, Clone, Default)]
pub struct MapDrawing {
    /// Every point's coordinates ([`crate::spec::axes::Plane`]), label, and how many of its
    /// runs left the model (`diverged`: the label does not count them).
    pub points: Vec<(Point, String, usize)>,
    /// Every run that ended on a stable state.
    pub ends: Vec<RunEnd>,
}

/// Where one settled run ended.
#[derive(Debug, Clone, PartialEq)]
pub struct RunEnd {
    /// Its point's coordinates in the sweep's plane.
    pub x: f64,
    pub y: f64,
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
            .map(|p| {
                let label = p.shown_label().to_string();
                ([p.x, p.y, p.z], label, p.class.n_diverged)
            })
            .collect();
        let ends = plan
            .tasks()
            .filter_map(|t| records.get(&t.key).map(|r| (t, r)))
            .filter_map(|(t, r)| {
                let [x, y, _] = plan.points[t.point];
                let o = &r.outcome;
                o.class.map(|c| RunEnd {
                    x,
                    y,
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
        let rows = read::points(&dir.join(read::POINTS))?;
        let at: std::collections::HashMap<u32, (f64, f64)> =
            rows.iter().map(|p| (p.point, (p.x, p.y))).collect();
        let points = rows
            .into_iter()
            .map(|p| ([p.x, p.y, p.z], p.label, p.n_diverged as usize))
            .collect();
        let ends = read::runs(&dir.join(read::RUNS))?
            .into_iter()
            .filter_map(|r| {
                let &(x, y) = at.get(&r.point)?;
                r.class.map(|c| RunEnd {
                    x,
                    y,
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
    let pts = map_points(spec, drawing);
    let model = model_title(spec);
    let title = format!(
        "{}: {model} phase map ({} ICs per point)",
        spec.name,
        spec.initial_conditions.len()
    );
    let grid = &spec.grid;
    let mut files = Vec::new();
    let mut drawn: Vec<Curve> = Vec::new();
    if grid.plane().is_paper() {
        // The reduced model's analytic boundaries (Fig. 3a), over both ODE and PDE maps, and
        // the full model's, if `droplet boundaries` put them here: both in the paper's plane.
        let coef = Coefficients::new(spec.params.radius, spec.solver.h0);
        let y = grid.y.as_ref().expect("the paper's plane has two axes");
        let ode = NamedCurve::from_boundaries(
            ModelKind::Ode,
            &boundaries(&coef, grid.x.span(), y.span()),
        );
        let path = dir.join(crate::tables::boundaries::FILE);
        let pde = crate::tables::boundaries::read(&path, ModelKind::Pde)?;
        let all: Vec<NamedCurve> = pde.into_iter().chain(ode).collect();
        crate::tables::boundaries::write(&path, &all, Some(&spec.source), Vec::new())?;
        drawn = all.iter().map(Curve::of).collect();
        files.push(path);
    } else if let Some(y) = &grid.y {
        drawn = plane_boundaries(dir, (grid.x.param.name(), y.param.name()))?;
    }
    let plane_y = grid.y.as_ref().filter(|y| y.values.len() > 1);
    if let Some(y) = plane_y.filter(|_| grid.x.values.len() > 1) {
        let names = (grid.x.param.name(), y.param.name());
        let maps = match &grid.z {
            None => {
                let pts: Vec<MapPoint> = pts.into_iter().map(|(_, p)| p).collect();
                phase_map(dir, "phase_map", &title, names, &pts, &drawn)?
            }
            Some(z) => slices(dir, &title, names, z, pts)?,
        };
        files.splice(0..0, maps);
    }
    files.extend(lines(dir, spec, &drawing.ends)?);
    Ok(files)
}

/// The points of a sweep's drawing as drawn: a refined map's point with the quarters of the
/// unsplit cells it is a corner of, in its own slice; each with its slice's coordinate.
pub(crate) fn map_points(spec: &SweepSpec, drawing: &MapDrawing) -> Vec<(f64, MapPoint)> {
    let mut tiles: HashMap<(u64, Node), Vec<[f64; 4]>> = HashMap::new();
    if let Some(lattice) = spec.refine {
        let mut by_slice: BTreeMap<u64, BTreeSet<Node>> = BTreeMap::new();
        for &([x, y, z], _, _) in &drawing.points {
            by_slice
                .entry(z.to_bits())
                .or_default()
                .insert(lattice.node_of((x, y)));
        }
        for (z, nodes) in by_slice {
            tiles.extend(lattice.tiles(&nodes).into_iter().map(|(n, t)| ((z, n), t)));
        }
    }
    drawing
        .points
        .iter()
        .map(|&([x, y, z], ref label, left_model)| {
            let node = spec.refine.map(|l| l.node_of((x, y)));
            let point = MapPoint {
                x,
                y,
                label: label.clone(),
                left_model,
                tiles: node
                    .and_then(|n| tiles.remove(&(z.to_bits(), n)))
                    .unwrap_or_default(),
            };
            (z, point)
        })
        .collect()
}

/// The model a sweep maps, as its pictures name it: `PDE`, `PDE (shape modes 2..K)`, `ODE`.
pub(crate) fn model_title(spec: &SweepSpec) -> String {
    match spec.params.modes {
        2 => spec.solver.model.as_str().to_uppercase(),
        // The K-mode model's map; the reduced model's curves drawn over it are the 2-mode ODE's.
        k => format!(
            "{} (shape modes 2..{k})",
            spec.solver.model.as_str().to_uppercase()
        ),
    }
}

/// A sweep outside the paper's plane: the boundaries `droplet boundaries` put in its
/// directory in its own plane ([`crate::studies::across`]), the full model's solid and the
/// reduced model's dashed.
fn plane_boundaries(dir: &Path, names: (&str, &str)) -> Result<Vec<Curve>, SweepError> {
    let path = dir.join(crate::tables::boundaries::FILE);
    let mut out = Vec::new();
    for model in [ModelKind::Pde, ModelKind::Ode] {
        let curves = crate::tables::boundaries::read_in(&path, names, model)?;
        out.extend(curves.iter().map(Curve::of));
    }
    Ok(out)
}

/// The maps of a 3-axis sweep: `phase_map_<z>_<value>.png/.svg` for each value of the slice
/// axis `z`, and `phase_map.png/.svg` with all of them side by side.
fn slices(
    dir: &Path,
    title: &str,
    names: (&str, &str),
    z: &crate::spec::Swept,
    pts: Vec<(f64, MapPoint)>,
) -> Result<Vec<PathBuf>, SweepError> {
    let mut panels: Vec<Panel> = z
        .values
        .iter()
        .map(|v| Panel {
            title: format!("{} = {v}", z.param),
            ..Panel::default()
        })
        .collect();
    for (at, p) in pts {
        if let Some(i) = z.values.iter().position(|&v| v == at) {
            panels[i].pts.push(p);
        }
    }
    let mut files = slice_maps(dir, "phase_map", title, names, &panels)?;
    for (v, panel) in z.values.iter().zip(&panels) {
        if panel.pts.is_empty() {
            continue;
        }
        let stem = format!("phase_map_{}_{v}", z.param);
        let one = format!("{title}, {}", panel.title);
        files.extend(phase_map(dir, &stem, &one, names, &panel.pts, &[])?);
    }
    Ok(files)
}

/// For a 1-D sweep (one axis, or a second axis of one value; Fig. 2b):
/// `bifurcation_lines.png` / `.svg`, `v` and `s` of every run that ended on a stable state
/// against the swept parameter, coloured by class, over the full model's branches along the
/// line (PDE spectral sweeps: [`pde_branches`], solid where stable, dashed where unstable) —
/// the way a physicist draws Fig. 2b, every run's end on a solid branch.
fn lines(dir: &Path, spec: &SweepSpec, ends: &[RunEnd]) -> Result<Vec<PathBuf>, SweepError> {
    let grid = &spec.grid;
    let (x, y) = (&grid.x, grid.y.as_ref());
    let (axis, along_x, fixed) = match y {
        None if x.values.len() > 1 => (x, true, String::new()),
        Some(y) if x.values.len() > 1 && y.values.len() == 1 => {
            (x, true, format!(", {} = {}", y.param, y.values[0]))
        }
        Some(y) if x.values.len() == 1 && y.values.len() > 1 => {
            (y, false, format!(", {} = {}", x.param, x.values[0]))
        }
        _ => return Ok(Vec::new()),
    };
    let mut markers: Vec<Marker> = ends
        .iter()
        .map(|e| Marker {
            x: if along_x { e.x } else { e.y },
            v: e.v,
            s: e.s,
            key: e.class.clone(),
            bold: true,
        })
        .collect();
    if markers.is_empty() {
        return Ok(Vec::new());
    }
    let (lines, events, vlines) = match pde_branches(spec, axis.param) {
        Some(branches) => branch_drawing(&branches),
        None => Default::default(),
    };
    markers.extend(events.into_iter().map(|e| Marker { bold: false, ..e }));
    let ic_names: Vec<&str> = spec
        .initial_conditions
        .iter()
        .map(|i| i.name.as_str())
        .collect();
    let title = format!(
        "{}: {} runs (ICs {}) on the branches{fixed}",
        spec.name,
        spec.solver.model.as_str().to_uppercase(),
        ic_names.join(", ")
    );
    vs_parameter(
        dir,
        "bifurcation_lines",
        &title,
        axis.param.name(),
        &markers,
        &lines,
        &vlines,
    )
}

/// The full model's branches (IC, ID, MD moving along either axis; on the x axis) along a
/// 1-D sweep's line, by continuation at the sweep's grid: empty for the ODE model and the
/// paper's scheme (their steady states are other equations), and without the families
/// that have no state on the line.
fn pde_branches(
    spec: &SweepSpec,
    param: Param,
) -> Option<Vec<droplet_solver::continuation::branch::Branch>> {
    use droplet_solver::continuation::{branch::follow, branch::Line, problem::Family};
    let parameter = param.model()?;
    if spec.solver.model != droplet_solver::contract::settings::ModelKind::Pde
        || spec.solver.scheme != droplet_solver::stepping::SchemeKind::Spectral
    {
        return None;
    }
    let (from, to) = spec.grid.axis(param)?.span();
    let (mut base, mut settings) = (spec.params, spec.solver);
    spec.grid
        .plane()
        .apply(spec.grid.first(), &mut base, &mut settings);
    let line = Line {
        base,
        n: settings.n,
        parameter,
        from,
        to,
        max_points: 400,
        opts: Default::default(),
    };
    let branches = [Family::IC, Family::ID, Family::MdMinor, Family::MdMajor]
        .iter()
        .filter_map(|f| follow(&line, *f, droplet_solver::model::mirror::MirrorLine::X).ok())
        .collect();
    Some(branches)
}
