//! The runs of a map as `droplet audit` reads them from `runs.parquet` (and the points table's
//! columns it needs): typed rows, grouped by point, with the model and scheme checked.
use crate::error::SweepError;
use droplet_solver::{model::classify::StateClass, model::params::ModelParams};
use polars::prelude::*;
use std::collections::BTreeMap;
use std::path::Path;

/// One run as the runs table has it.
#[derive(Debug, Clone)]
pub(super) struct Row {
    pub params: ModelParams,
    pub n: usize,
    pub ic: String,
    pub status: String,
    pub class: Option<StateClass>,
    pub z: [f64; 4],
    pub t_end: f64,
    pub unsettled: Option<String>,
    pub heading: Option<String>,
    pub key: String,
}

pub(super) fn read(path: &Path) -> Result<DataFrame, SweepError> {
    let file = std::fs::File::open(path).map_err(|e| {
        SweepError::Invalid(format!(
            "{}: {e}; audit reads the tables a finished sweep writes (runs.parquet, \
             points.parquet): finish the sweep, or `droplet merge` its shards, first",
            path.display()
        ))
    })?;
    Ok(ParquetReader::new(file).finish()?)
}

fn floats(df: &DataFrame, name: &str) -> Result<Vec<f64>, SweepError> {
    let c = df.column(name)?.f64()?.clone();
    Ok((0..c.len()).map(|i| c.get(i).unwrap_or(f64::NAN)).collect())
}

pub(super) fn strings(df: &DataFrame, name: &str) -> Result<Vec<Option<String>>, SweepError> {
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

pub(super) fn u32s(df: &DataFrame, name: &str) -> Result<Vec<u32>, SweepError> {
    let c = df.column(name)?.u32()?.clone();
    Ok((0..c.len()).map(|i| c.get(i).unwrap_or(0)).collect())
}

/// The runs of `runs.parquet`, by point index.
pub(super) fn read_runs(df: &DataFrame) -> Result<BTreeMap<u32, Vec<Row>>, SweepError> {
    let mut col = BTreeMap::new();
    for name in [
        "eta_t", "kappa2", "eta2", "radius", "sigma", "box_len", "mass", "vx", "vy", "a2", "b2",
        "t_end",
    ] {
        col.insert(name, floats(df, name)?);
    }
    let f = |name: &str, i: usize| col[name][i];
    let mut text = BTreeMap::new();
    for name in ["ic", "status", "class", "key", "model", "scheme"] {
        text.insert(name, strings(df, name)?);
    }
    let t = |name: &str, i: usize| text[name][i].clone();
    let (point, n) = (u32s(df, "point")?, u32s(df, "n")?);
    let (unsettled, heading) = (
        optional_strings(df, "unsettled")?,
        optional_strings(df, "heading")?,
    );
    let mut by_point: BTreeMap<u32, Vec<Row>> = BTreeMap::new();
    for i in 0..df.height() {
        let (model, scheme) = (t("model", i), t("scheme", i));
        if model.as_deref() != Some("pde") || scheme.as_deref() != Some("spectral") {
            return Err(SweepError::Invalid(format!(
                "audit checks maps of the PDE model with the spectral scheme (its steady \
                 equations and eigenvalues); this one has model {} and scheme {}",
                model.unwrap_or_default(),
                scheme.unwrap_or_default()
            )));
        }
        by_point.entry(point[i]).or_default().push(Row {
            params: ModelParams {
                eta_t: f("eta_t", i),
                kappa2: f("kappa2", i),
                eta2: f("eta2", i),
                radius: f("radius", i),
                sigma: f("sigma", i),
                box_len: f("box_len", i),
                mass: f("mass", i),
            },
            n: n[i] as usize,
            ic: t("ic", i).unwrap_or_default(),
            status: t("status", i).unwrap_or_default(),
            class: t("class", i).as_deref().and_then(StateClass::parse),
            z: [f("vx", i), f("vy", i), f("a2", i), f("b2", i)],
            t_end: f("t_end", i),
            unsettled: unsettled[i].clone(),
            heading: heading[i].clone(),
            key: t("key", i).unwrap_or_default(),
        });
    }
    Ok(by_point)
}
