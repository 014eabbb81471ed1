//! The `K`-mode MD branch along a line as Parquet (`droplet continue --modes K`,
//! [`crate::studies::mode_continuation`]): one row per state, in order along the branch:
//! `eta_t`, `kappa2`, the varied parameter's value `at`, `v`, the paper's `s = |a2|`, the total
//! deformation `sqrt(sum a_k^2)`, `a2 .. aK`, whether it is a fold, its stability (the rotation
//! mode set aside), the largest real part of the other eigenvalues, the rotation mode's and
//! the number of growing modes.
use crate::error::SweepError;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::tables::sweep_tables::{metadata, write_parquet};
use droplet_solver::continuation::mode_line::{ModeBranch, ModeBranchPoint};
use polars::prelude::*;
use std::path::{Path, PathBuf};

/// `sqrt(sum_k a_k^2)`: the total deformation of a state on the x axis.
pub fn deformation(p: &ModeBranchPoint) -> f64 {
    p.a.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Writes `dir/<stem>.parquet`; `line` (e.g. `kappa2 = 0.13, eta_t from 0.075 to 0.1`), the
/// grid and the modes go into the metadata.
pub fn write(
    dir: &Path,
    stem: &str,
    branch: &ModeBranch,
    line: &str,
    n: usize,
    params: &droplet_solver::model::params::ModelParams,
) -> Result<PathBuf, SweepError> {
    let pts = &branch.points;
    let f = |g: &dyn Fn(&ModeBranchPoint) -> f64| pts.iter().map(g).collect::<Vec<f64>>();
    let mut columns = vec![
        Column::new("branch".into(), vec!["md"; pts.len()]),
        Column::new("modes".into(), vec![branch.k_max as u32; pts.len()]),
        Column::new(ETA_T.into(), f(&|p| p.eta_t)),
        Column::new(KAPPA2.into(), f(&|p| p.kappa2)),
        Column::new("at".into(), f(&|p| p.at)),
        Column::new("v".into(), f(&|p| p.v)),
        Column::new("s".into(), f(&|p| p.a[0].abs())),
        Column::new("deformation".into(), f(&deformation)),
    ];
    for k in 2..=branch.k_max {
        columns.push(Column::new(format!("a{k}").into(), f(&|p| p.a[k - 2])));
    }
    columns.extend([
        Column::new(
            "fold".into(),
            pts.iter().map(|p| p.fold).collect::<Vec<bool>>(),
        ),
        Column::new(
            "stable".into(),
            pts.iter()
                .map(|p| p.verdict.stable())
                .collect::<Vec<bool>>(),
        ),
        Column::new("leading_re".into(), f(&|p| p.verdict.max_re)),
        Column::new(
            "rotation_eig".into(),
            pts.iter()
                .map(|p| p.verdict.rotation)
                .collect::<Vec<Option<f64>>>(),
        ),
        Column::new(
            "unstable".into(),
            pts.iter()
                .map(|p| p.verdict.unstable as u32)
                .collect::<Vec<u32>>(),
        ),
    ]);
    let mut df = DataFrame::new(pts.len(), columns)?;
    let mut meta = metadata(None);
    meta.push(("line".into(), line.to_string()));
    meta.push(("n".into(), n.to_string()));
    // Every model parameter of the line at its start, the varied one included.
    meta.push((
        "params".into(),
        serde_json::to_string(params).expect("parameters serialise"),
    ));
    meta.push(("modes".into(), branch.k_max.to_string()));
    meta.push(("eta_k_exponent".into(), branch.eta_k_exponent.to_string()));
    meta.push((
        "end".into(),
        serde_json::to_value(branch.end)
            .ok()
            .and_then(|v| v.as_str().map(String::from))
            .unwrap_or_default(),
    ));
    let path = dir.join(format!("{stem}.parquet"));
    write_parquet(&mut df, &path, meta)?;
    Ok(path)
}
