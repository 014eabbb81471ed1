//! `truncation.parquet`: one row per number of shape modes `K` (`droplet truncation`,
//! [`crate::studies::truncation`]): the Fig. 1c MD state (`v`, the paper's `s = |a2|`, the
//! total deformation, whether it is stable, its largest eigenvalue's real part and its rotation
//! mode's, `a2 .. aKmax`, null beyond a row's `K`), the resting disk's onset of
//! motion at `kappa2` = 0.13, the MD fold there (`eta_t`, `v`), the IC/MD band's width, and
//! the seconds each took (the boundaries of the Fig. 2a window for each `K` are in
//! `truncation_boundaries.parquet`, curves named `K = k: <boundary>`).
use crate::error::SweepError;
use crate::tables::sweep_tables::{metadata, write_parquet};
use droplet_solver::continuation::fold_curve::Fold;
use droplet_solver::roots::steady_solver::MirrorState;
use droplet_solver::roots::thresholds::IcThresholds;
use droplet_solver::roots::verdict::Verdict;
use polars::prelude::*;
use std::path::{Path, PathBuf};

/// One `K`'s results.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TruncationRow {
    /// Modes `2..=k_max`.
    pub k_max: usize,
    /// The MD state at Fig. 1c.
    pub fig1c: MirrorState,
    /// Its stability, the rotation mode set aside.
    pub fig1c_verdict: Verdict,
    /// `sqrt(sum a_k^2)` there.
    pub deformation: f64,
    pub fig1c_seconds: f64,
    /// The resting disk's onsets at the band line's `kappa2`.
    pub disk: IcThresholds,
    /// The MD fold on the band line, if found.
    pub fold: Option<Fold>,
    pub fold_seconds: f64,
    /// The phase boundaries in the Fig. 2a window (`truncation_boundaries.parquet`).
    pub boundaries_seconds: f64,
}

/// The file's name in a directory.
pub const FILE: &str = "truncation.parquet";

/// Writes `dir/truncation.parquet`.
pub fn write(dir: &Path, rows: &[TruncationRow], n: usize) -> Result<PathBuf, SweepError> {
    let k_top = rows.iter().map(|r| r.k_max).max().unwrap_or(2);
    let f = |g: &dyn Fn(&TruncationRow) -> f64| rows.iter().map(g).collect::<Vec<f64>>();
    let opt = |g: &dyn Fn(&TruncationRow) -> Option<f64>| {
        rows.iter().map(g).collect::<Vec<Option<f64>>>()
    };
    let mut columns = vec![
        Column::new(
            "k_max".into(),
            rows.iter().map(|r| r.k_max as u32).collect::<Vec<_>>(),
        ),
        Column::new("v_fig1c".into(), f(&|r| r.fig1c.v)),
        Column::new("s_fig1c".into(), f(&|r| r.fig1c.a[0].abs())),
        Column::new("deformation_fig1c".into(), f(&|r| r.deformation)),
        Column::new(
            "stable_fig1c".into(),
            rows.iter()
                .map(|r| r.fig1c_verdict.stable())
                .collect::<Vec<_>>(),
        ),
        Column::new("leading_fig1c".into(), f(&|r| r.fig1c_verdict.max_re)),
        Column::new("rotation_fig1c".into(), opt(&|r| r.fig1c_verdict.rotation)),
    ];
    for k in 2..=k_top {
        columns.push(Column::new(
            format!("a{k}_fig1c").into(),
            opt(&|r| r.fig1c.a.get(k - 2).copied()),
        ));
    }
    columns.extend([
        Column::new("onset_eta_t".into(), f(&|r| r.disk.eta_t)),
        Column::new("fold_eta_t".into(), opt(&|r| r.fold.as_ref().map(|x| x.x))),
        Column::new("fold_v".into(), opt(&|r| r.fold.as_ref().map(|x| x.v))),
        Column::new(
            "band_width".into(),
            opt(&|r| r.fold.as_ref().map(|x| x.x - r.disk.eta_t)),
        ),
        Column::new("fig1c_seconds".into(), f(&|r| r.fig1c_seconds)),
        Column::new("fold_seconds".into(), f(&|r| r.fold_seconds)),
        Column::new("boundaries_seconds".into(), f(&|r| r.boundaries_seconds)),
    ]);
    let mut df = DataFrame::new(rows.len(), columns)?;
    let mut meta = metadata(None);
    meta.push(("n".into(), n.to_string()));
    meta.push((
        "points".into(),
        "fig1c: eta_t 0.085, kappa2 0.112; band line: kappa2 0.13, eta_t 0.07-0.10".into(),
    ));
    let path = dir.join(FILE);
    write_parquet(&mut df, &path, meta)?;
    Ok(path)
}
