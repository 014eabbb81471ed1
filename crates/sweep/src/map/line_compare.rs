//! A 1-D sweep's class changes (Fig. 2b, time stepping) against the bifurcation points that
//! continuation found on the same line: every change between two neighbouring grid points
//! should have a P / SN point between them. A change without one is explained only if one of
//! its points was classified as a resting state (IC or ID, alone or bistable) where
//! continuation finds that state unstable: the paper's steady test stopping on a slowly growing
//! mode near its onset (the false steady state that the Newton finish is meant to remove).
use crate::error::SweepError;
use crate::spec::axes::{ETA_T, KAPPA2};
use polars::prelude::*;
use std::path::Path;

/// The Fig. 2b lines as committed: `(name, fixed parameter, its value, varied parameter)`;
/// the sweep is `results/fig2b-<name>`, the continuation
/// `results/continuation/continuation_<fixed>_<value>`.
pub const FIG2B_LINES: [(&str, &str, &str, &str); 6] = [
    ("i", ETA_T, "0.082", KAPPA2),
    ("ii", ETA_T, "0.09", KAPPA2),
    ("iii", KAPPA2, "0.16", ETA_T),
    ("iv", KAPPA2, "0.13", ETA_T),
    ("v", KAPPA2, "0.117", ETA_T),
    ("vi", KAPPA2, "0.1", ETA_T),
];

/// One class change between neighbouring grid points, and what continuation says there.
#[derive(Debug, Clone, PartialEq)]
pub struct ClassChange {
    pub lo: f64,
    pub hi: f64,
    pub from: String,
    pub to: String,
    /// `(kind, branch, at)` of the continuation events in `[lo, hi]`.
    pub events: Vec<(String, String, f64)>,
    /// No event between, and one side is an IC or ID classification where that state is
    /// unstable.
    pub false_steady: bool,
}

impl ClassChange {
    pub fn explained(&self) -> bool {
        !self.events.is_empty() || self.false_steady
    }
}

fn read(path: &Path) -> Result<DataFrame, SweepError> {
    let file = std::fs::File::open(path).map_err(|e| SweepError::io(path, e))?;
    Ok(ParquetReader::new(file).finish()?)
}

fn floats(df: &DataFrame, name: &str) -> Result<Vec<f64>, SweepError> {
    let c = df.column(name)?.f64()?.clone();
    Ok((0..c.len()).map(|i| c.get(i).unwrap_or(f64::NAN)).collect())
}

fn strings(df: &DataFrame, name: &str) -> Result<Vec<String>, SweepError> {
    let c = df.column(name)?.str()?.clone();
    Ok((0..c.len())
        .map(|i| c.get(i).unwrap_or_default().to_string())
        .collect())
}

/// [`compare`] for one of [`FIG2B_LINES`], from the repository root.
pub fn compare_fig2b(
    (name, fixed, value, axis): (&str, &str, &str, &str),
) -> Result<Vec<ClassChange>, SweepError> {
    let stem = format!("results/continuation/continuation_{fixed}_{value}");
    compare(
        Path::new(&format!("results/fig2b-{name}/points.parquet")),
        Path::new(&format!("{stem}.parquet")),
        Path::new(&format!("{stem}_events.parquet")),
        axis,
    )
}

/// Compares a line sweep's `points.parquet` with a continuation's `<stem>.parquet` and
/// `<stem>_events.parquet` along `axis` (`eta_t` or `kappa2`).
pub fn compare(
    points: &Path,
    branches: &Path,
    events: &Path,
    axis: &str,
) -> Result<Vec<ClassChange>, SweepError> {
    if axis != ETA_T && axis != KAPPA2 {
        return Err(SweepError::Invalid(format!("unknown axis `{axis}`")));
    }
    let pts = read(points)?;
    let mut line: Vec<(f64, String)> = floats(&pts, axis)?
        .into_iter()
        .zip(strings(&pts, "class")?)
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    let br = read(branches)?;
    // Stability of the resting families along the line.
    let resting: Vec<(String, f64, bool)> = {
        let x = floats(&br, axis)?;
        let fam = strings(&br, "branch")?;
        let st = br.column("stable")?.bool()?.clone();
        (0..x.len())
            .filter(|&i| fam[i] == "IC" || fam[i] == "ID")
            .map(|i| (fam[i].clone(), x[i], st.get(i).unwrap_or(false)))
            .collect()
    };
    let unstable = |family: &str, x: f64| {
        resting
            .iter()
            .filter(|p| p.0 == family)
            .min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs()))
            .is_some_and(|p| !p.2)
    };
    let ev = read(events)?;
    let ev: Vec<(String, String, f64)> = strings(&ev, "kind")?
        .into_iter()
        .zip(strings(&ev, "branch")?)
        .zip(floats(&ev, axis)?)
        .map(|((k, b), x)| (k, b, x))
        .collect();
    let false_rest = |x: f64, class: &str| {
        class
            .split('/')
            .any(|c| (c == "IC" || c == "ID") && unstable(c, x))
    };
    Ok(line
        .windows(2)
        .filter(|w| w[0].1 != w[1].1)
        .map(|w| {
            let (lo, hi) = (w[0].0, w[1].0);
            let events: Vec<_> = ev
                .iter()
                .filter(|e| e.2 >= lo && e.2 <= hi)
                .cloned()
                .collect();
            let false_steady = events.is_empty() && w.iter().any(|(x, c)| false_rest(*x, c));
            ClassChange {
                lo,
                hi,
                from: w[0].1.clone(),
                to: w[1].1.clone(),
                events,
                false_steady,
            }
        })
        .collect())
}
