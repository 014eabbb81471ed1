//! The reduced model's bifurcation diagram along a line as Parquet: `<stem>.parquet` (every
//! steady state: branch, parameters, `v`, `s`, largest real part of the eigenvalues,
//! stability) and `<stem>_events.parquet` (P / SN points), with the coefficients and the line
//! in the metadata.
use crate::error::SweepError;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::tables::sweep_tables::{metadata, write_parquet};
use droplet_solver::model::param::ModelParam;
use droplet_solver::reduced::bifurcation::{Event, SteadyPoint};
use droplet_solver::reduced::coefficients::Coefficients;
use polars::prelude::*;
use std::path::{Path, PathBuf};

/// Writes both tables into `dir`; returns their paths.
pub fn write(
    dir: &Path,
    stem: &str,
    pts: &[SteadyPoint],
    events: &[Event],
    axis: ModelParam,
    c: &Coefficients,
    line: &str,
) -> Result<[PathBuf; 2], SweepError> {
    let x_label = axis.name();
    let mut df = DataFrame::new(
        pts.len(),
        vec![
            Column::new(
                "branch".into(),
                pts.iter()
                    .map(|p| p.branch.as_str().to_string())
                    .collect::<Vec<_>>(),
            ),
            Column::new(
                ETA_T.into(),
                pts.iter().map(|p| p.params.eta_t).collect::<Vec<_>>(),
            ),
            Column::new(
                KAPPA2.into(),
                pts.iter().map(|p| p.params.kappa2).collect::<Vec<_>>(),
            ),
            Column::new("v".into(), pts.iter().map(|p| p.v).collect::<Vec<_>>()),
            Column::new("s".into(), pts.iter().map(|p| p.s).collect::<Vec<_>>()),
            Column::new(
                "max_re_eigenvalue".into(),
                pts.iter().map(|p| p.max_re).collect::<Vec<_>>(),
            ),
            Column::new(
                "stable".into(),
                pts.iter().map(|p| p.stable).collect::<Vec<_>>(),
            ),
        ],
    )?;
    let mut ev = DataFrame::new(
        events.len(),
        vec![
            Column::new(
                "kind".into(),
                events
                    .iter()
                    .map(|e| e.kind.to_string())
                    .collect::<Vec<_>>(),
            ),
            Column::new(
                "branch".into(),
                events
                    .iter()
                    .map(|e| e.branch.as_str().to_string())
                    .collect::<Vec<_>>(),
            ),
            Column::new(
                x_label.into(),
                events.iter().map(|e| e.at).collect::<Vec<_>>(),
            ),
        ],
    )?;
    let mut meta = metadata(None);
    meta.push((
        "coefficients".into(),
        serde_json::to_string(&c).expect("json"),
    ));
    meta.push(("line".into(), line.to_string()));
    let p1 = dir.join(format!("{stem}.parquet"));
    let p2 = dir.join(format!("{stem}_events.parquet"));
    write_parquet(&mut df, &p1, meta.clone())?;
    write_parquet(&mut ev, &p2, meta)?;
    Ok([p1, p2])
}
