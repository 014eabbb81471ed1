//! A single run's time series, `(t, x, y, vx, vy, a2, b2, v, s)` per row (a `K`-mode run's
//! also `a3..aK, b3..bK`), as Parquet with the run's parameters, settings and initial
//! condition in the metadata.
use crate::error::SweepError;
use crate::tables::sweep_tables::{f64_col, metadata, write_parquet};
use droplet_solver::{
    contract::outcome::SeriesRow, contract::settings::SolverSettings,
    model::initial::InitialCondition, model::params::ModelParams,
};
use polars::prelude::*;
use std::path::Path;

/// The time series of one run.
pub fn series_frame(series: &[SeriesRow]) -> Result<DataFrame, SweepError> {
    let f = |g: fn(&SeriesRow) -> f64| series.iter().map(g).collect::<Vec<f64>>();
    let cols = vec![
        f64_col("t", f(|r| r.t)),
        f64_col("x", f(|r| r.x)),
        f64_col("y", f(|r| r.y)),
        f64_col("vx", f(|r| r.vx)),
        f64_col("vy", f(|r| r.vy)),
        f64_col("a2", f(|r| r.a2)),
        f64_col("b2", f(|r| r.b2)),
        f64_col("v", f(|r| r.v)),
        f64_col("s", f(|r| r.s)),
    ];
    Ok(DataFrame::new(series.len(), cols)?)
}
/// The `a3..aK, b3..bK` columns of a `K`-mode run's series (`higher`: per row, `a_3..a_K`
/// then `b_3..b_K`).
fn shape_columns(higher: &[Vec<f64>]) -> Vec<Column> {
    let k = higher.first().map_or(2, |h| h.len() / 2 + 2);
    let mut cols = Vec::new();
    for (name, offset) in [("a", 0), ("b", k - 2)] {
        for m in 3..=k {
            let v: Vec<f64> = higher.iter().map(|h| h[offset + m - 3]).collect();
            cols.push(f64_col(&format!("{name}{m}"), v));
        }
    }
    cols
}

/// Writes `series` to `path`; a `K`-mode run's (non-empty `higher`, one row per row of
/// `series`) gains the columns `a3..aK`, `b3..bK`.
pub fn write(
    path: &Path,
    series: &[SeriesRow],
    higher: &[Vec<f64>],
    params: &ModelParams,
    settings: &SolverSettings,
    ic: &InitialCondition,
) -> Result<(), SweepError> {
    let mut df = series_frame(series)?;
    if !higher.is_empty() {
        df = df.hstack(&shape_columns(higher))?;
    }
    let mut meta = metadata(None);
    meta.push((
        "params".into(),
        serde_json::to_string(&params).expect("json"),
    ));
    meta.push((
        "settings".into(),
        serde_json::to_string(&settings).expect("json"),
    ));
    meta.push(("ic".into(), ic.name.clone()));
    write_parquet(&mut df, path, meta)?;
    Ok(())
}
