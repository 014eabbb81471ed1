//! Continuation branches as Parquet: `<stem>.parquet` (every state: family, mirror axis,
//! parameters, `vx, vy, a2, b2, v, s`, with shape modes `2..K`, `K > 2`, also `a3 .. aK`,
//! `b3 .. bK`; class, the two leading eigenvalues with the rotation mode set aside, the
//! rotation mode's eigenvalue, unstable count, stability) and
//! `<stem>_events.parquet` (P / SN / H points, and R where the rotation mode passes the rate the
//! verdict sets aside, with the crossing eigenvalue and the precision
//! of their location in the varied parameter).
use crate::error::SweepError;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::tables::sweep_tables::{metadata, write_parquet};
use droplet_solver::continuation::branch::{Branch, BranchPoint, Line};
use polars::prelude::*;
use std::path::{Path, PathBuf};

fn f64s(name: &str, v: Vec<f64>) -> Column {
    Column::new(name.into(), v)
}

fn strs(name: &str, v: Vec<String>) -> Column {
    Column::new(name.into(), v)
}

/// The `i`-th decisive eigenvalue's real part (NaN if there is none).
fn lead(p: &BranchPoint, i: usize) -> f64 {
    p.verdict.decisive().get(i).map_or(f64::NAN, |l| l.re)
}

fn state_columns(rows: &[(&Branch, &BranchPoint)]) -> Vec<Column> {
    let col = |f: &dyn Fn(&BranchPoint) -> f64| rows.iter().map(|(_, p)| f(p)).collect::<Vec<_>>();
    let mut cols = vec![
        strs(
            "branch",
            rows.iter()
                .map(|(b, _)| b.family.as_str().to_string())
                .collect(),
        ),
        strs(
            "mirror",
            rows.iter()
                .map(|(b, _)| format!("{:?}", b.mirror).to_lowercase())
                .collect(),
        ),
        f64s(ETA_T, col(&|p| p.eta_t)),
        f64s(KAPPA2, col(&|p| p.kappa2)),
        // The varied parameter's value (equal to eta_t or kappa2 on the paper's lines).
        f64s("at", col(&|p| p.at)),
        f64s("vx", col(&|p| p.z[0])),
        f64s("vy", col(&|p| p.z[1])),
        f64s("a2", col(&|p| p.a_k()[0])),
        f64s("b2", col(&|p| p.b_k()[0])),
        f64s("v", col(&|p| p.v)),
        f64s("s", col(&|p| p.s)),
        strs(
            "class",
            rows.iter()
                .map(|(_, p)| p.class.as_str().to_string())
                .collect(),
        ),
        f64s("eig1_re", col(&|p| lead(p, 0))),
        f64s(
            "eig1_im",
            col(&|p| p.verdict.decisive().first().map_or(f64::NAN, |l| l.im)),
        ),
        f64s("eig2_re", col(&|p| lead(p, 1))),
        f64s(
            "rotation_eig",
            col(&|p| p.verdict.rotation.unwrap_or(f64::NAN)),
        ),
        Column::new(
            "unstable".into(),
            rows.iter()
                .map(|(_, p)| p.verdict.unstable as u32)
                .collect::<Vec<u32>>(),
        ),
        Column::new(
            "stable".into(),
            rows.iter()
                .map(|(_, p)| p.verdict.stable())
                .collect::<Vec<bool>>(),
        ),
    ];
    // The higher shape modes, after the 2-mode columns.
    let k_max = rows.first().map_or(2, |(_, p)| p.a_k().len() + 1);
    for (name, pick) in [("a", 0), ("b", 1)] {
        for k in 3..=k_max {
            let amplitude = |p: &BranchPoint| {
                if pick == 0 {
                    p.a_k()[k - 2]
                } else {
                    p.b_k()[k - 2]
                }
            };
            cols.push(f64s(&format!("{name}{k}"), col(&amplitude)));
        }
    }
    cols
}

/// Writes both tables into `dir`; `description` (e.g. `kappa2 = 0.13, eta_t from 0.07 to
/// 0.1`), the grid, the shape modes and the friction law's exponent go into the metadata.
/// Returns their paths.
pub fn write(
    dir: &Path,
    stem: &str,
    branches: &[Branch],
    description: &str,
    line: &Line,
) -> Result<[PathBuf; 2], SweepError> {
    let rows: Vec<(&Branch, &BranchPoint)> = branches
        .iter()
        .flat_map(|b| b.points.iter().map(move |p| (b, p)))
        .collect();
    let mut df = DataFrame::new(rows.len(), state_columns(&rows))?;
    let ev_rows: Vec<(&Branch, &BranchPoint)> = branches
        .iter()
        .flat_map(|b| b.events.iter().map(move |e| (b, &e.point)))
        .collect();
    let events: Vec<_> = branches.iter().flat_map(|b| b.events.iter()).collect();
    let mut cols = vec![
        strs("kind", events.iter().map(|e| e.kind.to_string()).collect()),
        strs("what", events.iter().map(|e| e.what.clone()).collect()),
        f64s(
            "crossing_re",
            events
                .iter()
                .map(|e| e.eigenvalue.map_or(f64::NAN, |l| l[0]))
                .collect(),
        ),
        f64s(
            "crossing_im",
            events
                .iter()
                .map(|e| e.eigenvalue.map_or(f64::NAN, |l| l[1]))
                .collect(),
        ),
        f64s("precision", events.iter().map(|e| e.precision).collect()),
    ];
    cols.extend(state_columns(&ev_rows));
    let mut ev = DataFrame::new(events.len(), cols)?;
    let mut meta = metadata(None);
    meta.push(("line".into(), description.to_string()));
    meta.push(("n".into(), line.n.to_string()));
    meta.push(("modes".into(), line.base.modes.to_string()));
    meta.push((
        "eta_k_exponent".into(),
        line.base.eta_k_exponent.to_string(),
    ));
    // Every model parameter of the line at its start, the varied one included.
    meta.push((
        "params".into(),
        serde_json::to_string(&line.base).expect("parameters serialise"),
    ));
    meta.push((
        "ends".into(),
        branches
            .iter()
            .map(|b| {
                format!(
                    "{} ({:?}): {} | {}",
                    b.family.as_str(),
                    b.mirror,
                    b.ends[0],
                    b.ends[1]
                )
            })
            .collect::<Vec<_>>()
            .join("; "),
    ));
    let p1 = dir.join(format!("{stem}.parquet"));
    let p2 = dir.join(format!("{stem}_events.parquet"));
    write_parquet(&mut df, &p1, meta.clone())?;
    write_parquet(&mut ev, &p2, meta)?;
    Ok([p1, p2])
}
