//! `droplet boundaries --n 192,256,384`: how far the grid moves each phase boundary. The full
//! model's boundaries are computed at every `N` of a list ([`BoundaryStudy`], into `n<N>/`),
//! and each curve at each `N` is compared with the same curve at the previous `N`: its shift
//! is the largest distance, in the `(eta_t, kappa2)` plane, from a point of the finer curve to
//! the coarser curve (a polyline). For the straight onsets this is the change of the
//! threshold itself. Writes `convergence.parquet` and `boundaries_by_n.png/.svg` (every `N`
//! drawn over each other).
use crate::error::SweepError;
use crate::pictures::map_figure::{boundary_picture, Curve, CURVE_COLOURS};
use crate::studies::boundaries::BoundaryStudy;
use crate::tables::boundaries::NamedCurve;
use crate::tables::sweep_tables::{metadata, write_parquet};
use droplet_solver::continuation::polyline::distance_to_polyline;
use droplet_solver::contract::settings::ModelKind;
use polars::prelude::*;
use std::path::PathBuf;

/// One boundary curve at one grid size.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveAtN {
    pub curve: String,
    pub n: usize,
    pub points: usize,
    /// Largest distance from this curve to the same curve at the previous `N` (`None` at the
    /// first `N`, or where the previous `N` has no such curve in the window).
    pub shift: Option<f64>,
}

/// What a convergence study computed and wrote.
#[derive(Debug, Clone)]
pub struct ConvergenceWritten {
    /// The grid sizes, ascending.
    pub ns: Vec<usize>,
    /// Every full-model curve at every `N`, in the order `N`, then curve.
    pub curves: Vec<CurveAtN>,
    /// Wall seconds of the boundaries at each `N`.
    pub seconds: Vec<f64>,
    pub files: Vec<PathBuf>,
}

/// The boundaries of `base` (its window, samples and output directory) at every `N` of `ns`
/// (sorted and deduplicated), each into `<out>/n<N>/`, and their shifts from one `N` to the
/// next.
pub fn run(base: &BoundaryStudy, ns: &[usize]) -> Result<ConvergenceWritten, SweepError> {
    let mut ns = ns.to_vec();
    ns.sort_unstable();
    ns.dedup();
    crate::store::atomic::create_output_dir(&base.out)?;
    let mut seconds = Vec::new();
    let mut files = Vec::new();
    let mut by_n: Vec<Vec<NamedCurve>> = Vec::new();
    for &n in &ns {
        let study = BoundaryStudy {
            out: base.out.join(format!("n{n}")),
            n,
            sweep_spec: None,
            across: None,
            pair: None,
            base: base.base.with_modes(2),
            ..base.clone()
        };
        let done = study.run()?;
        seconds.push(done.seconds);
        files.extend(done.files);
        by_n.push(
            done.curves
                .into_iter()
                .filter(|c| c.model == ModelKind::Pde)
                .collect(),
        );
    }
    let mut curves = Vec::new();
    for (i, (&n, set)) in ns.iter().zip(&by_n).enumerate() {
        for c in set {
            let previous = i
                .checked_sub(1)
                .and_then(|j| by_n[j].iter().find(|p| p.name == c.name));
            curves.push(CurveAtN {
                curve: c.name.clone(),
                n,
                points: c.points.len(),
                shift: previous.and_then(|p| shift(&c.points, &p.points)),
            });
        }
    }
    let table = base.out.join("convergence.parquet");
    write_table(&table, &curves, base)?;
    files.push(table);
    files.extend(picture(base, &ns, &by_n)?);
    Ok(ConvergenceWritten {
        ns,
        curves,
        seconds,
        files,
    })
}

/// The largest distance from a point of `fine` to the polyline `coarse` (`None` if either is
/// empty).
pub fn shift(fine: &[(f64, f64)], coarse: &[(f64, f64)]) -> Option<f64> {
    if fine.is_empty() || coarse.is_empty() {
        return None;
    }
    Some(
        fine.iter()
            .map(|&p| distance_to_polyline(p, coarse))
            .fold(0.0, f64::max),
    )
}

/// `convergence.parquet`: one row per curve and `N`, with the window in the metadata.
fn write_table(
    path: &std::path::Path,
    curves: &[CurveAtN],
    base: &BoundaryStudy,
) -> Result<(), SweepError> {
    let mut df = DataFrame::new(
        curves.len(),
        vec![
            Column::new(
                "curve".into(),
                curves.iter().map(|c| c.curve.clone()).collect::<Vec<_>>(),
            ),
            Column::new(
                "n".into(),
                curves.iter().map(|c| c.n as u32).collect::<Vec<_>>(),
            ),
            Column::new(
                "points".into(),
                curves.iter().map(|c| c.points as u32).collect::<Vec<_>>(),
            ),
            Column::new(
                "shift".into(),
                curves.iter().map(|c| c.shift).collect::<Vec<_>>(),
            ),
        ],
    )?;
    let mut meta = metadata(base.sweep_spec.as_deref());
    meta.push((
        "window".into(),
        format!("eta_t {:?}, kappa2 {:?}", base.eta_t, base.kappa2),
    ));
    write_parquet(&mut df, path, meta)
}

/// Every `N`'s full-model boundaries drawn over each other, one colour per curve (the finest
/// `N` solid, the others dashed).
fn picture(
    base: &BoundaryStudy,
    ns: &[usize],
    by_n: &[Vec<NamedCurve>],
) -> Result<Vec<PathBuf>, SweepError> {
    let finest = ns.len().saturating_sub(1);
    let mut names: Vec<&str> = Vec::new();
    for c in by_n.iter().flatten() {
        if !names.contains(&c.name.as_str()) {
            names.push(&c.name);
        }
    }
    let colour = |name: &str| {
        let i = names.iter().position(|n| *n == name).unwrap_or(0);
        CURVE_COLOURS[i % CURVE_COLOURS.len()]
    };
    let drawn: Vec<Curve> = ns
        .iter()
        .zip(by_n)
        .enumerate()
        .flat_map(|(i, (n, set))| {
            set.iter().map(move |c| Curve {
                label: format!("N = {n}: {}", c.name),
                points: c.points.clone(),
                dashed: i != finest,
                colour: Some(colour(&c.name)),
            })
        })
        .collect();
    let sizes: Vec<String> = ns.iter().map(|n| n.to_string()).collect();
    boundary_picture(
        &base.out,
        "boundaries_by_n",
        &format!(
            "PDE boundaries at N = {} (the finest solid)",
            sizes.join(", ")
        ),
        &drawn,
        base.eta_t,
        base.kappa2,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shift_of_a_straight_onset_is_the_change_of_its_threshold() {
        let coarse = [(0.0764, 0.1), (0.0764, 0.17)];
        let fine = [(0.07645, 0.1), (0.07645, 0.17)];
        assert!((shift(&fine, &coarse).unwrap() - 5e-5).abs() < 1e-15);
        // A point beyond the coarse curve's end is measured to its end point.
        let d = shift(&[(0.0, 0.2)], &coarse).unwrap();
        assert!((d - 0.0764f64.hypot(0.03)).abs() < 1e-15);
        assert_eq!(shift(&[], &coarse), None);
        // A bent curve: the largest of the points' distances.
        let bent = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)];
        assert!((shift(&[(0.5, 0.25), (0.75, 0.5)], &bent).unwrap() - 0.25).abs() < 1e-15);
    }
}
