//! A finished map's tables read back as typed rows (`runs.parquet`, `points.parquet`) with the
//! spec stored in their metadata: what `droplet audit`, and `droplet status` and `droplet plot`
//! on a committed result directory (one without `runs/`), work from.
use crate::error::SweepError;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::spec::SweepSpec;
use droplet_solver::{model::classify::StateClass, model::params::ModelParams};
use polars::prelude::*;
use std::path::Path;

/// The runs table of a map directory.
pub const RUNS: &str = "runs.parquet";

/// The points table of a map directory.
pub const POINTS: &str = "points.parquet";

/// One run as the runs table has it.
#[derive(Debug, Clone)]
pub struct RunRow {
    pub point: u32,
    pub params: ModelParams,
    pub n: usize,
    pub model: String,
    pub scheme: String,
    pub ic: String,
    pub status: String,
    pub class: Option<StateClass>,
    /// `(vx, vy, a2, b2)` at the end.
    pub z: [f64; 4],
    /// The whole state at the end, `(vx, vy, a2..aK, b2..bK)` (the K-mode model's unknowns;
    /// `z` when `K = 2`), with `K` the shape modes of `params` (2 in a table without a
    /// `modes` column, their friction law's exponent 0 without an `eta_k_exponent` one).
    pub state: Vec<f64>,
    pub v: f64,
    pub s: f64,
    pub t_end: f64,
    pub wall_s: f64,
    pub unsettled: Option<String>,
    pub heading: Option<String>,
    /// How a steady run ended (`steady_by_newton`, ...; `None` in tables without the column).
    pub ended_by: Option<String>,
    pub key: String,
}

/// One point as the points table has it.
#[derive(Debug, Clone)]
pub struct PointRow {
    pub point: u32,
    /// Its coordinates in the sweep's plane ([`crate::spec::axes::Plane`], from the spec in
    /// the table's metadata; the paper's plane for a table without one).
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub level: u32,
    pub label: String,
    pub settled: bool,
    pub n_runs: u32,
    /// Its runs that left the model (`diverged`; 0 in a table without the column).
    pub n_diverged: u32,
}

/// Whether `dir` is a map known only by its tables: `points.parquet` but no run store.
pub fn is_tables_only(dir: &Path) -> bool {
    !dir.join("runs").is_dir() && dir.join(POINTS).is_file()
}

/// Reads a Parquet table, saying what to do when it is not there.
pub fn frame(path: &Path) -> Result<DataFrame, SweepError> {
    let file = std::fs::File::open(path).map_err(|e| {
        SweepError::Invalid(format!(
            "{}: {e}; a finished sweep writes runs.parquet and points.parquet (finish the \
             sweep, or `droplet merge` its shards, first)",
            path.display()
        ))
    })?;
    Ok(ParquetReader::new(file).finish()?)
}

/// The spec a table was made from (its `spec` metadata).
pub fn stored_spec(path: &Path) -> Result<SweepSpec, SweepError> {
    let meta = crate::tables::sweep_tables::read_metadata(path)?;
    let text = meta.get("spec").ok_or_else(|| {
        SweepError::Invalid(format!(
            "{}: the table has no spec in its metadata, so its grid is unknown",
            path.display()
        ))
    })?;
    let stem = path
        .parent()
        .and_then(|d| d.file_name())
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default();
    Ok(crate::spec::parse(
        text,
        &path.display().to_string(),
        &stem,
    )?)
}

fn floats(df: &DataFrame, name: &str) -> Result<Vec<f64>, SweepError> {
    let c = df.column(name)?.f64()?.clone();
    Ok((0..c.len()).map(|i| c.get(i).unwrap_or(f64::NAN)).collect())
}

fn strings(df: &DataFrame, name: &str) -> Result<Vec<Option<String>>, SweepError> {
    let c = df.column(name)?.str()?.clone();
    Ok((0..c.len()).map(|i| c.get(i).map(str::to_string)).collect())
}

/// A string column that older tables lack (all `None` then).
fn optional_strings(df: &DataFrame, name: &str) -> Result<Vec<Option<String>>, SweepError> {
    match df.column(name) {
        Ok(_) => strings(df, name),
        Err(_) => Ok(vec![None; df.height()]),
    }
}

fn u32s(df: &DataFrame, name: &str) -> Result<Vec<u32>, SweepError> {
    let c = df.column(name)?.u32()?.clone();
    Ok((0..c.len()).map(|i| c.get(i).unwrap_or(0)).collect())
}

/// A bool column, `default` where the table lacks it.
fn bools_or(df: &DataFrame, name: &str, default: bool) -> Result<Vec<bool>, SweepError> {
    let Ok(c) = df.column(name) else {
        return Ok(vec![default; df.height()]);
    };
    let c = c.bool()?.clone();
    Ok((0..c.len()).map(|i| c.get(i).unwrap_or(default)).collect())
}

/// A u32 column, 0 where the table lacks it.
fn u32s_or_zero(df: &DataFrame, name: &str) -> Result<Vec<u32>, SweepError> {
    u32s_or(df, name, 0)
}

/// A u32 column, `default` where the table lacks it.
fn u32s_or(df: &DataFrame, name: &str, default: u32) -> Result<Vec<u32>, SweepError> {
    match df.column(name) {
        Ok(_) => u32s(df, name),
        Err(_) => Ok(vec![default; df.height()]),
    }
}

/// Every run of a runs table, in table order.
pub fn runs(path: &Path) -> Result<Vec<RunRow>, SweepError> {
    let df = frame(path)?;
    let names = [
        ETA_T, KAPPA2, "eta2", "radius", "sigma", "box_len", "mass", "vx", "vy", "a2", "b2", "v",
        "s", "t_end", "wall_s",
    ];
    let cols = names
        .iter()
        .map(|n| floats(&df, n))
        .collect::<Result<Vec<_>, _>>()?;
    let f = |name: &str, i: usize| cols[names.iter().position(|n| *n == name).unwrap()][i];
    let texts = ["ic", "status", "class", "key", "model", "scheme"];
    let text = texts
        .iter()
        .map(|n| strings(&df, n))
        .collect::<Result<Vec<_>, _>>()?;
    let t = |name: &str, i: usize| {
        text[texts.iter().position(|n| *n == name).unwrap()][i]
            .clone()
            .unwrap_or_default()
    };
    let (point, n) = (u32s(&df, "point")?, u32s(&df, "n")?);
    let (unsettled, heading, ended_by) = (
        optional_strings(&df, "unsettled")?,
        optional_strings(&df, "heading")?,
        optional_strings(&df, "ended_by")?,
    );
    let modes = u32s_or(&df, "modes", 2)?;
    let eta_k_exponent = match df.column("eta_k_exponent") {
        Ok(_) => floats(&df, "eta_k_exponent")?,
        Err(_) => vec![0.0; df.height()],
    };
    let k_top = modes.iter().copied().max().unwrap_or(2) as usize;
    let a_k = (3..=k_top)
        .map(|k| floats(&df, &format!("a{k}")))
        .collect::<Result<Vec<_>, _>>()?;
    let b_k = (3..=k_top)
        .map(|k| floats(&df, &format!("b{k}")))
        .collect::<Result<Vec<_>, _>>()?;
    let state = |i: usize| -> Vec<f64> {
        let k = modes[i] as usize;
        let mut z = vec![f("vx", i), f("vy", i), f("a2", i)];
        z.extend(a_k[..k - 2].iter().map(|c| c[i]));
        z.push(f("b2", i));
        z.extend(b_k[..k - 2].iter().map(|c| c[i]));
        z
    };
    Ok((0..df.height())
        .map(|i| RunRow {
            point: point[i],
            params: ModelParams {
                eta_t: f(ETA_T, i),
                kappa2: f(KAPPA2, i),
                eta2: f("eta2", i),
                radius: f("radius", i),
                sigma: f("sigma", i),
                box_len: f("box_len", i),
                mass: f("mass", i),
                modes: modes[i] as usize,
                eta_k_exponent: eta_k_exponent[i],
            },
            n: n[i] as usize,
            model: t("model", i),
            scheme: t("scheme", i),
            ic: t("ic", i),
            status: t("status", i),
            class: StateClass::parse(&t("class", i)),
            z: [f("vx", i), f("vy", i), f("a2", i), f("b2", i)],
            state: state(i),
            v: f("v", i),
            s: f("s", i),
            t_end: f("t_end", i),
            wall_s: f("wall_s", i),
            unsettled: unsettled[i].clone(),
            heading: heading[i].clone(),
            ended_by: ended_by[i].clone(),
            key: t("key", i),
        })
        .collect())
}

/// Every point of a points table, in table order.
pub fn points(path: &Path) -> Result<Vec<PointRow>, SweepError> {
    let df = frame(path)?;
    // A table without its spec (edited by another tool) is read in the paper's plane.
    let plane = stored_spec(path).map_or(crate::spec::axes::Plane::PAPER, |s| s.grid.plane());
    let eta = floats(&df, plane.x.name())?;
    let other = |p: Option<crate::spec::axes::Param>| match p {
        Some(p) => floats(&df, p.name()),
        None => Ok(vec![0.0; df.height()]),
    };
    let (kappa, slice) = (other(plane.y)?, other(plane.z)?);
    let (point, level, n_runs) = (
        u32s(&df, "point")?,
        u32s_or_zero(&df, "level")?,
        u32s(&df, "n_runs")?,
    );
    let (label, settled) = (strings(&df, "class")?, bools_or(&df, "settled", true)?);
    let n_diverged = u32s_or_zero(&df, "n_diverged")?;
    Ok((0..df.height())
        .map(|i| PointRow {
            point: point[i],
            x: eta[i],
            y: kappa[i],
            z: slice[i],
            level: level[i],
            label: label[i].clone().unwrap_or_default(),
            settled: settled[i],
            n_runs: n_runs[i],
            n_diverged: n_diverged[i],
        })
        .collect())
}
