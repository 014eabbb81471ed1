//! `boundaries.parquet`: phase boundaries as a long table (`model` = `pde` / `ode`, `curve`,
//! the plane's two coordinates, points in order along each curve): `eta_t`, `kappa2` in the
//! paper's plane, the sweep's axes over a sweep in another plane
//! ([`crate::studies::across`]). The reduced model's are analytic
//! (Fig. 3a); the full model's come from `droplet boundaries` (continuation of the
//! bifurcation points). A sweep's `droplet plot` rewrites the ODE rows and keeps the PDE rows.
use crate::error::SweepError;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::tables::sweep_tables::{metadata, write_parquet};
use droplet_solver::contract::settings::ModelKind;
use polars::prelude::*;
use std::path::Path;

/// The file's name in a directory.
pub const FILE: &str = "boundaries.parquet";

/// One boundary curve of one model.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedCurve {
    /// The full model (`pde`, from continuation) or the reduced one (`ode`, analytic).
    pub model: ModelKind,
    pub name: String,
    /// The plane's `(x, y)` (`(eta_t, kappa2)` in the paper's plane) in order along the
    /// curve.
    pub points: Vec<(f64, f64)>,
}

impl NamedCurve {
    /// The curves of one model, named by their boundary; a boundary in several pieces gets
    /// `name (2)`, `name (3)`, ... for the second and later.
    pub fn from_boundaries(
        model: ModelKind,
        curves: &[droplet_solver::reduced::boundaries::Boundary],
    ) -> Vec<Self> {
        // A condition whose zero set has several pieces: "name", "name (2)", ...
        let mut seen: Vec<&str> = Vec::new();
        curves
            .iter()
            .map(|c| {
                seen.push(c.name);
                let k = seen.iter().filter(|n| **n == c.name).count();
                Self {
                    model,
                    name: match k {
                        1 => c.name.to_string(),
                        _ => format!("{} ({k})", c.name),
                    },
                    points: c.points.clone(),
                }
            })
            .collect()
    }
}

/// Writes curves of the paper's plane to `path`, with the sweep's spec (if any) and `extra` in
/// the metadata.
pub fn write(
    path: &Path,
    curves: &[NamedCurve],
    spec: Option<&str>,
    extra: Vec<(String, String)>,
) -> Result<(), SweepError> {
    write_in(path, (ETA_T, KAPPA2), curves, spec, extra)
}

/// As [`write`], for curves in the plane whose axes are named `names`.
pub fn write_in(
    path: &Path,
    names: (&str, &str),
    curves: &[NamedCurve],
    spec: Option<&str>,
    extra: Vec<(String, String)>,
) -> Result<(), SweepError> {
    let rows: Vec<(&NamedCurve, (f64, f64))> = curves
        .iter()
        .flat_map(|c| c.points.iter().map(move |p| (c, *p)))
        .collect();
    let mut df = DataFrame::new(
        rows.len(),
        vec![
            Column::new(
                "model".into(),
                rows.iter()
                    .map(|(c, _)| c.model.as_str())
                    .collect::<Vec<_>>(),
            ),
            Column::new(
                "curve".into(),
                rows.iter().map(|(c, _)| c.name.clone()).collect::<Vec<_>>(),
            ),
            Column::new(
                names.0.into(),
                rows.iter().map(|(_, p)| p.0).collect::<Vec<_>>(),
            ),
            Column::new(
                names.1.into(),
                rows.iter().map(|(_, p)| p.1).collect::<Vec<_>>(),
            ),
        ],
    )?;
    let mut meta = metadata(spec);
    meta.extend(extra);
    write_parquet(&mut df, path, meta)
}

/// The curves of `model` in the paper's plane stored in `path` (none if the file does not
/// exist, predates the `model` column, or holds another plane's curves).
pub fn read(path: &Path, model: ModelKind) -> Result<Vec<NamedCurve>, SweepError> {
    read_in(path, (ETA_T, KAPPA2), model)
}

/// As [`read`], for curves in the plane whose axes are named `axes`.
pub fn read_in(
    path: &Path,
    axes: (&str, &str),
    model: ModelKind,
) -> Result<Vec<NamedCurve>, SweepError> {
    if !path.exists() {
        return Ok(Vec::new());
    }
    let file = std::fs::File::open(path).map_err(|e| SweepError::io(path, e))?;
    let df = ParquetReader::new(file).finish()?;
    if df.column("model").is_err() || df.column(axes.0).is_err() || df.column(axes.1).is_err() {
        return Ok(Vec::new());
    }
    let models = df.column("model")?.str()?.clone();
    let names = df.column("curve")?.str()?.clone();
    let eta = df.column(axes.0)?.f64()?.clone();
    let kappa = df.column(axes.1)?.f64()?.clone();
    let mut out: Vec<NamedCurve> = Vec::new();
    for i in 0..df.height() {
        if models.get(i) != Some(model.as_str()) {
            continue;
        }
        let name = names.get(i).unwrap_or_default().to_string();
        let p = (
            eta.get(i).unwrap_or(f64::NAN),
            kappa.get(i).unwrap_or(f64::NAN),
        );
        match out.last_mut() {
            Some(c) if c.name == name => c.points.push(p),
            _ => out.push(NamedCurve {
                model,
                name,
                points: vec![p],
            }),
        }
    }
    Ok(out)
}
