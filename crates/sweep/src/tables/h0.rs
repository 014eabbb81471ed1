//! The Appendix E fit's table, `h0_fit.parquet`: every deformation-only steady state
//! `(kappa2, s)`, whether it entered the fit, and `p0`, `p2` in the metadata.
use crate::error::SweepError;
use crate::spec::axes::KAPPA2;
use crate::tables::sweep_tables::{metadata, write_parquet};
use droplet_solver::roots::h0_fit::H0Fit;
use polars::prelude::*;
use std::path::{Path, PathBuf};

/// Writes `dir/h0_fit.parquet` for `fit` at grid size `n`.
pub fn write(dir: &Path, fit: &H0Fit, n: usize) -> Result<PathBuf, SweepError> {
    let mut df = DataFrame::new(
        fit.points.len(),
        vec![
            Column::new(
                KAPPA2.into(),
                fit.points.iter().map(|p| p.0).collect::<Vec<_>>(),
            ),
            Column::new(
                "s".into(),
                fit.points.iter().map(|p| p.1).collect::<Vec<_>>(),
            ),
            Column::new(
                "in_fit".into(),
                fit.points
                    .iter()
                    .map(|p| p.1 > 1e-3 && p.1 < 0.3)
                    .collect::<Vec<_>>(),
            ),
        ],
    )?;
    let mut meta = metadata(None);
    meta.push(("p0".into(), fit.p0.to_string()));
    meta.push(("p2".into(), fit.p2.to_string()));
    meta.push((
        "method".into(),
        "exact steady evaluator (Newton, v = 0)".into(),
    ));
    meta.push(("n".into(), n.to_string()));
    let table = dir.join("h0_fit.parquet");
    write_parquet(&mut df, &table, meta)?;
    Ok(table)
}
