//! Parquet tables: `runs.parquet` (one row per run), `points.parquet` (one row per point),
//! time series; each with key-value metadata (spec, its hash, versions, git commit).
use crate::error::SweepError;
use crate::map::phase_map::PhaseMap;
use crate::map::point_class::PointClass;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::spec::SweepSpec;
use crate::store::plan::Plan;
use crate::store::run_store::RunRecord;
use crate::store::run_store::Store;
use droplet_solver::contract::settings::SolverSettings;
use polars::prelude::*;
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use std::fs::File;
use std::path::{Path, PathBuf};

/// Git commit of the build (`-dirty` when the tree had changes).
pub const GIT_COMMIT: &str = env!("DROPLET_GIT_COMMIT");

/// Metadata written into every table.
pub fn metadata(spec_text: Option<&str>) -> Vec<(String, String)> {
    let mut kv = vec![
        (
            "droplet_version".to_string(),
            env!("CARGO_PKG_VERSION").to_string(),
        ),
        (
            "solver_version".to_string(),
            droplet_solver::SOLVER_VERSION.to_string(),
        ),
        ("git_commit".to_string(), GIT_COMMIT.to_string()),
    ];
    if let Some(text) = spec_text {
        let hash: String = Sha256::digest(text.as_bytes())
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect();
        kv.push(("spec".to_string(), text.to_string()));
        kv.push(("spec_sha256".to_string(), hash));
    }
    kv
}

/// Writes `df` to `path` with metadata (atomically, see [`crate::store::atomic::write_atomic`]).
pub fn write_parquet(
    df: &mut DataFrame,
    path: &Path,
    meta: Vec<(String, String)>,
) -> Result<(), SweepError> {
    let mut bytes = Vec::new();
    ParquetWriter::new(&mut bytes)
        .with_key_value_metadata(Some(KeyValueMetadata::from_static(meta)))
        .finish(df)?;
    crate::store::atomic::write_atomic(path, &bytes)?;
    Ok(())
}

/// Reads the key-value metadata of a Parquet file.
pub fn read_metadata(path: &Path) -> Result<HashMap<String, String>, SweepError> {
    let file = File::open(path).map_err(|e| SweepError::io(path, e))?;
    let mut reader = ParquetReader::new(file);
    let md = reader.get_metadata()?;
    Ok(md
        .key_value_metadata()
        .iter()
        .flatten()
        .filter_map(|kv| kv.value.clone().map(|v| (kv.key.clone(), v)))
        .collect())
}

pub(crate) fn f64_col(name: &str, v: Vec<f64>) -> Column {
    Column::new(name.into(), v)
}

pub(crate) fn str_col(name: &str, v: Vec<String>) -> Column {
    Column::new(name.into(), v)
}

/// A setting's values over `rows`, null in the rows of runs that do not read it
/// (`SolverSettings::unread_reason`): a row records only what made its run.
fn read<T>(
    rows: &[(crate::store::plan::Task, &RunRecord)],
    field: &str,
    value: impl Fn(&SolverSettings) -> T,
) -> Vec<Option<T>> {
    rows.iter()
        .map(|(_, r)| {
            r.settings
                .reads(r.params.modes, field)
                .then(|| value(&r.settings))
        })
        .collect()
}

/// The runs table for `plan` from the stored `records` (runs not stored are left out).
pub fn runs_frame(
    plan: &Plan,
    records: &HashMap<String, RunRecord>,
) -> Result<DataFrame, SweepError> {
    let rows: Vec<(crate::store::plan::Task, &RunRecord)> = plan
        .tasks()
        .filter_map(|t| records.get(&t.key).map(|r| (t, r)))
        .collect();
    let mut cols = input_columns(&rows);
    cols.extend(outcome_columns(&rows));
    let records: Vec<&RunRecord> = rows.iter().map(|(_, r)| *r).collect();
    cols.extend(crate::tables::shape_columns::run_columns(&records));
    Ok(DataFrame::new(rows.len(), cols)?)
}

/// The runs table's columns of what made each run: its point, parameters, initial condition
/// and settings.
fn input_columns(rows: &[(crate::store::plan::Task, &RunRecord)]) -> Vec<Column> {
    let f = |g: &dyn Fn(&RunRecord) -> f64| rows.iter().map(|(_, r)| g(r)).collect::<Vec<f64>>();
    vec![
        Column::new(
            "point".into(),
            rows.iter()
                .map(|(t, _)| t.point as u32)
                .collect::<Vec<u32>>(),
        ),
        f64_col(ETA_T, f(&|r| r.params.eta_t)),
        f64_col(KAPPA2, f(&|r| r.params.kappa2)),
        str_col("ic", rows.iter().map(|(t, _)| t.ic.name.clone()).collect()),
        f64_col("ic_vx", f(&|r| r.ic.vx)),
        f64_col("ic_vy", f(&|r| r.ic.vy)),
        f64_col("ic_a2", f(&|r| r.ic.a2)),
        f64_col("ic_b2", f(&|r| r.ic.b2)),
        f64_col("eta2", f(&|r| r.params.eta2)),
        f64_col("radius", f(&|r| r.params.radius)),
        f64_col("sigma", f(&|r| r.params.sigma)),
        f64_col("box_len", f(&|r| r.params.box_len)),
        f64_col("mass", f(&|r| r.params.mass)),
        str_col(
            "model",
            rows.iter()
                .map(|(_, r)| r.settings.model.as_str().to_string())
                .collect(),
        ),
        Column::new("h0".into(), read(rows, "h0", |s| s.h0)),
        Column::new(
            "scheme".into(),
            read(rows, "scheme", |s| s.scheme.to_string()),
        ),
        Column::new("n".into(), read(rows, "n", |s| s.n as u32)),
        f64_col("dt", f(&|r| r.settings.dt)),
        Column::new("tol".into(), read(rows, "tol", |s| s.tol)),
        Column::new("dt_max".into(), read(rows, "dt_max", |s| s.dt_max)),
        f64_col("t_max", f(&|r| r.settings.t_max)),
        f64_col("steady_tol", f(&|r| r.settings.steady_tol)),
        Column::new(
            "steady_window".into(),
            read(rows, "steady_window", |s| s.steady_window),
        ),
        str_col(
            "steady",
            rows.iter()
                .map(|(_, r)| r.settings.steady.as_str().to_string())
                .collect(),
        ),
        Column::new(
            "stop_beside_saddle".into(),
            read(rows, "stop_beside_saddle", |s| s.stop_beside_saddle),
        ),
        Column::new(
            "leap_departures".into(),
            read(rows, "leap_departures", |s| s.leap_departures),
        ),
        Column::new("landing".into(), read(rows, "landing", |s| s.landing)),
        Column::new("run_on".into(), read(rows, "run_on", |s| s.run_on)),
        Column::new(
            "projective_steps".into(),
            read(rows, "projective_steps", |s| s.projective_steps),
        ),
    ]
}

/// The runs table's columns of how each run ended.
fn outcome_columns(rows: &[(crate::store::plan::Task, &RunRecord)]) -> Vec<Column> {
    let f = |g: &dyn Fn(&RunRecord) -> f64| rows.iter().map(|(_, r)| g(r)).collect::<Vec<f64>>();
    vec![
        str_col(
            "status",
            rows.iter()
                .map(|(_, r)| r.outcome.status.as_str().to_string())
                .collect(),
        ),
        Column::new(
            "class".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.class.map(|c| c.as_str().to_string()))
                .collect::<Vec<Option<String>>>(),
        ),
        Column::new(
            "unsettled".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.unsettled.map(|u| u.as_str().to_string()))
                .collect::<Vec<Option<String>>>(),
        ),
        Column::new(
            "heading".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.heading.map(|c| c.as_str().to_string()))
                .collect::<Vec<Option<String>>>(),
        ),
        f64_col("v", f(&|r| r.outcome.v)),
        f64_col("s", f(&|r| r.outcome.s)),
        f64_col("vx", f(&|r| r.outcome.state.vx)),
        f64_col("vy", f(&|r| r.outcome.state.vy)),
        f64_col("a2", f(&|r| r.outcome.state.a2)),
        f64_col("b2", f(&|r| r.outcome.state.b2)),
        f64_col("t_end", f(&|r| r.outcome.t_end)),
        Column::new(
            "t_steady".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.t_steady)
                .collect::<Vec<Option<f64>>>(),
        ),
        f64_col("t_leapt", f(&|r| r.outcome.t_leapt)),
        f64_col("t_projected", f(&|r| r.outcome.t_projected)),
        Column::new(
            "steps".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.steps)
                .collect::<Vec<u64>>(),
        ),
        Column::new(
            "rejected".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.rejected)
                .collect::<Vec<u64>>(),
        ),
        Column::new(
            "max_step_error".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.max_step_error)
                .collect::<Vec<Option<f64>>>(),
        ),
        Column::new(
            "ended_by".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.ended_by.map(|e| e.as_str().to_string()))
                .collect::<Vec<Option<String>>>(),
        ),
        Column::new(
            "diagnosis".into(),
            rows.iter()
                .map(|(_, r)| r.outcome.diagnosis.clone())
                .collect::<Vec<Option<String>>>(),
        ),
        f64_col("wall_s", f(&|r| r.outcome.wall_s)),
        str_col("key", rows.iter().map(|(t, _)| t.key.clone()).collect()),
    ]
}

/// The points table: coordinates (one column per swept parameter), refinement level and cell size (the grid step of the
/// point's level), point class, the class from each initial condition.
pub fn points_frame(map: &PhaseMap) -> Result<DataFrame, SweepError> {
    let n = map.points.len();
    let mut cols = vec![Column::new(
        "point".into(),
        (0..n as u32).collect::<Vec<u32>>(),
    )];
    // One column per axis, named after its parameter, then the level and the cell's sides.
    let (x, y) = (map.plane.x.name(), map.plane.y.map(|p| p.name()));
    cols.push(f64_col(x, map.points.iter().map(|p| p.x).collect()));
    if let Some(y) = y {
        cols.push(f64_col(y, map.points.iter().map(|p| p.y).collect()));
    }
    if let Some(z) = map.plane.z {
        cols.push(f64_col(z.name(), map.points.iter().map(|p| p.z).collect()));
    }
    cols.push(Column::new(
        "level".into(),
        map.points.iter().map(|p| p.level).collect::<Vec<u32>>(),
    ));
    cols.push(f64_col(
        &format!("d_{x}"),
        map.points.iter().map(|p| p.cell.0).collect(),
    ));
    if let Some(y) = y {
        cols.push(f64_col(
            &format!("d_{y}"),
            map.points.iter().map(|p| p.cell.1).collect(),
        ));
    }
    cols.extend([
        str_col(
            "class",
            map.points.iter().map(|p| p.class.label.clone()).collect(),
        ),
        Column::new(
            "settled".into(),
            map.points
                .iter()
                .map(|p| p.class.settled())
                .collect::<Vec<bool>>(),
        ),
    ]);
    for (i, name) in map.ic_names.iter().enumerate() {
        cols.push(Column::new(
            format!("class_{name}").as_str().into(),
            map.points
                .iter()
                .map(|p| p.per_ic[i].clone())
                .collect::<Vec<Option<String>>>(),
        ));
    }
    for (name, get) in [
        (
            "n_runs",
            (|c: &PointClass| c.n_runs) as fn(&PointClass) -> usize,
        ),
        ("n_steady", |c| c.n_steady),
        ("n_t_max", |c| c.n_t_max),
        ("n_unsettled", |c| c.n_unsettled),
        ("n_diverged", |c| c.n_diverged),
        ("n_certified", |c| c.n_certified),
    ] {
        cols.push(Column::new(
            name.into(),
            map.points
                .iter()
                .map(|p| get(&p.class) as u32)
                .collect::<Vec<u32>>(),
        ));
    }
    cols.extend(crate::tables::shape_columns::point_columns(map));
    Ok(DataFrame::new(n, cols)?)
}

/// Writes `runs.parquet` and `points.parquet` for `plan` from the store.
pub fn write_tables(
    store: &Store,
    spec: &SweepSpec,
    plan: &Plan,
    records: &HashMap<String, RunRecord>,
    map: &PhaseMap,
) -> Result<Vec<PathBuf>, SweepError> {
    let meta = metadata(Some(&spec.source));
    let runs_path = store.dir().join("runs.parquet");
    let points_path = store.dir().join("points.parquet");
    write_parquet(&mut runs_frame(plan, records)?, &runs_path, meta.clone())?;
    write_parquet(&mut points_frame(map)?, &points_path, meta)?;
    Ok(vec![runs_path, points_path])
}
