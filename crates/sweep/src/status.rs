//! Progress and class counts of a sweep directory, finished or not, and its picture.
use crate::error::SweepError;
use crate::plan::plan;
use crate::plot::{phase_map, vs_parameter, Curve, MapPoint, Marker};
use crate::spec::{parse, SweepSpec};
use crate::store::Store;
use crate::tables::point_classes;
use droplet_solver::reduced::boundaries::boundaries;
use droplet_solver::reduced::Coefficients;
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
    pub cpu_s: f64,
}

/// Counts of each label.
pub fn tally(labels: impl IntoIterator<Item = String>) -> BTreeMap<String, usize> {
    let mut out = BTreeMap::new();
    for l in labels {
        *out.entry(l).or_default() += 1;
    }
    out
}

/// The spec stored in a sweep directory.
pub fn stored_spec(dir: &Path) -> Result<SweepSpec, SweepError> {
    let path = dir.join("spec.yaml");
    let text = std::fs::read_to_string(&path).map_err(|e| SweepError::io(&path, e))?;
    Ok(parse(&text, &path.display().to_string(), "sweep")?)
}

/// Reads the status of the sweep in `dir`.
pub fn status(dir: &Path) -> Result<SweepStatus, SweepError> {
    let store = Store::open_read(dir)?;
    let spec = stored_spec(dir)?;
    let plan = plan(&spec);
    let mut records = std::collections::HashMap::new();
    let mut runs_corrupt = 0;
    for t in plan.tasks() {
        match store.check(&t.key) {
            crate::store::Stored::Valid(r) => {
                records.insert(t.key, *r);
            }
            crate::store::Stored::Corrupt(_) => runs_corrupt += 1,
            crate::store::Stored::Missing => {}
        }
    }
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
    let point_counts = tally(
        point_classes(&plan, &records)
            .into_iter()
            .filter(|(_, per_ic)| per_ic.iter().all(|x| x.is_some()))
            .map(|(c, _)| c.label),
    );
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
        cpu_s,
    })
}

/// Draws `phase_map.png` / `.svg` of the sweep in `dir` (points without all runs: `missing`).
pub fn plot(dir: &Path) -> Result<Vec<PathBuf>, SweepError> {
    let store = Store::open_read(dir)?;
    let spec = stored_spec(dir)?;
    let plan = plan(&spec);
    let records = store.load_many(plan.tasks().map(|t| t.key));
    plot_records(dir, &spec, &plan, &records)
}

/// As [`plot`], from records already loaded (a sweep or merge that just wrote the tables).
pub fn plot_records(
    dir: &Path,
    spec: &SweepSpec,
    plan: &crate::plan::Plan,
    records: &std::collections::HashMap<String, crate::store::RunRecord>,
) -> Result<Vec<PathBuf>, SweepError> {
    let pts: Vec<MapPoint> = point_classes(plan, records)
        .into_iter()
        .zip(&plan.points)
        .map(|((c, per_ic), &(eta_t, kappa2))| MapPoint {
            eta_t,
            kappa2,
            label: if per_ic.iter().all(|x| x.is_some()) {
                c.label
            } else {
                "missing".into()
            },
        })
        .collect();
    let model = spec.solver.model.as_str().to_uppercase();
    let title = format!(
        "{}: {model} phase map ({} ICs per point)",
        spec.name,
        plan.ic_names.len()
    );
    // The reduced model's analytic boundaries (Fig. 3a), over both ODE and PDE maps.
    let coef = Coefficients::new(spec.params.radius, spec.solver.h0);
    let span = |v: &[f64]| {
        v.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            })
    };
    let curves = boundaries(&coef, span(&spec.eta_t), span(&spec.kappa2));
    let mut df = crate::tables::boundaries_frame(&curves)?;
    let path = dir.join("boundaries.parquet");
    crate::tables::write_parquet(&mut df, &path, crate::tables::metadata(Some(&spec.source)))?;
    let drawn: Vec<Curve> = curves
        .into_iter()
        .map(|c| Curve {
            label: format!("ODE: {}", c.name),
            points: c.points,
        })
        .collect();
    let mut files = if spec.eta_t.len() > 1 && spec.kappa2.len() > 1 {
        phase_map(dir, "phase_map", &title, &pts, &drawn)?
    } else {
        Vec::new()
    };
    files.push(path);
    files.extend(lines(dir, spec, plan, records)?);
    Ok(files)
}

/// For a 1-D sweep (one axis with one value, Fig. 2b): `bifurcation_lines.png` / `.svg`,
/// `v` and `s` of every run against the swept parameter, coloured by class (bold: steady).
fn lines(
    dir: &Path,
    spec: &SweepSpec,
    plan: &crate::plan::Plan,
    records: &std::collections::HashMap<String, crate::store::RunRecord>,
) -> Result<Vec<PathBuf>, SweepError> {
    let (along_eta, fixed) = match (spec.eta_t.len(), spec.kappa2.len()) {
        (n, 1) if n > 1 => (true, format!("kappa2 = {}", spec.kappa2[0])),
        (1, n) if n > 1 => (false, format!("eta_t = {}", spec.eta_t[0])),
        _ => return Ok(Vec::new()),
    };
    let markers: Vec<Marker> = plan
        .tasks()
        .filter_map(|t| records.get(&t.key).map(|r| (t, r)))
        .filter(|(_, r)| r.outcome.class.is_some())
        .map(|(t, r)| {
            let (eta, kappa) = plan.points[t.point];
            Marker {
                x: if along_eta { eta } else { kappa },
                v: r.outcome.v,
                s: r.outcome.s,
                key: r
                    .outcome
                    .class
                    .map(|c| c.as_str().to_string())
                    .unwrap_or_default(),
                bold: r.outcome.status == droplet_solver::RunStatus::Steady,
            }
        })
        .collect();
    if markers.is_empty() {
        return Ok(Vec::new());
    }
    let title = format!(
        "{}: {} runs, {fixed} (ICs {})",
        spec.name,
        spec.solver.model.as_str().to_uppercase(),
        plan.ic_names.join(", ")
    );
    vs_parameter(
        dir,
        "bifurcation_lines",
        &title,
        if along_eta { "eta_t" } else { "kappa2" },
        &markers,
        &[],
        &[],
    )
}
