//! The shape-mode columns a sweep of the `K`-mode model (spec `params.modes` > 2) adds to its tables.
//! `runs.parquet`: `modes`, `eta_k_exponent` (the friction law of modes `k >= 3`), the higher amplitudes at each run's end `a3 .. aK`, `b3 .. bK`
//! (null beyond a run's own `K`) and the total deformation `sqrt(sum_k a_k^2 + b_k^2)`.
//! `points.parquet`: `modes`, and for each initial condition the state its run settled on,
//! `deformation_<ic>`, `a3_<ic> .. aK_<ic>`, `b3_<ic> .. bK_<ic>` (null for a run not settled).
//! The class stays the paper's, from `v` and `s = sqrt(a2^2 + b2^2)` (mode 2). A 2-mode
//! sweep's tables have none of them, and are unchanged.
use crate::map::end_shape::EndShape;
use crate::map::phase_map::{MapEntry, PhaseMap};
use crate::store::run_store::RunRecord;
use polars::prelude::*;

/// The `a3..aK, b3..bK` columns (suffix `suffix`) of `shapes`.
fn amplitude_columns(shapes: &[Option<EndShape>], k_top: usize, suffix: &str) -> Vec<Column> {
    let mut cols = Vec::new();
    for (name, pick) in [("a", 0), ("b", 1)] {
        for k in 3..=k_top {
            let v: Vec<Option<f64>> = shapes
                .iter()
                .map(|e| {
                    let (a, b) = e.as_ref().map_or((None, None), |e| e.amplitude(k));
                    if pick == 0 {
                        a
                    } else {
                        b
                    }
                })
                .collect();
            cols.push(Column::new(format!("{name}{k}{suffix}").into(), v));
        }
    }
    cols
}

/// The runs table's columns, empty when every run is a 2-mode run.
pub fn run_columns(records: &[&RunRecord]) -> Vec<Column> {
    let k_top = records.iter().map(|r| r.params.modes).max().unwrap_or(2);
    if k_top <= 2 {
        return Vec::new();
    }
    let shapes: Vec<Option<EndShape>> = records.iter().map(|r| Some(EndShape::of(r))).collect();
    let mut cols = vec![Column::new(
        "modes".into(),
        records
            .iter()
            .map(|r| r.params.modes as u32)
            .collect::<Vec<u32>>(),
    )];
    cols.push(Column::new(
        "eta_k_exponent".into(),
        records
            .iter()
            .map(|r| r.params.eta_k_exponent)
            .collect::<Vec<f64>>(),
    ));
    cols.extend(amplitude_columns(&shapes, k_top, ""));
    let total: Vec<f64> = shapes.iter().flatten().map(EndShape::deformation).collect();
    cols.push(Column::new("deformation".into(), total));
    cols
}

/// The points table's columns, empty for a 2-mode map: `modes` (the largest `K` of the
/// point's runs), and per initial condition the settled run's deformation and amplitudes.
pub fn point_columns(map: &PhaseMap) -> Vec<Column> {
    fn shapes(p: &MapEntry) -> impl Iterator<Item = usize> + '_ {
        p.shapes.iter().flatten().map(|e| e.modes)
    }
    let k_top = map.points.iter().flat_map(shapes).max().unwrap_or(2);
    if k_top <= 2 {
        return Vec::new();
    }
    let mut cols = vec![Column::new(
        "modes".into(),
        map.points
            .iter()
            .map(|p| shapes(p).max().map(|k| k as u32))
            .collect::<Vec<Option<u32>>>(),
    )];
    for (i, name) in map.ic_names.iter().enumerate() {
        let own: Vec<Option<EndShape>> = map.points.iter().map(|p| p.shapes[i].clone()).collect();
        cols.push(Column::new(
            format!("deformation_{name}").into(),
            own.iter()
                .map(|e| e.as_ref().map(EndShape::deformation))
                .collect::<Vec<Option<f64>>>(),
        ));
        cols.extend(amplitude_columns(&own, k_top, &format!("_{name}")));
    }
    cols
}
