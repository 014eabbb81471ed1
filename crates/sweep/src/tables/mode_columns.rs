//! The columns a sweep of the `K`-mode model (spec `params.modes` > 2) adds to
//! `runs.parquet`: `modes`, the higher amplitudes at each run's end `a3 .. aK`, `b3 .. bK`
//! (null beyond a run's own `K`) and the total deformation `sqrt(sum_k a_k^2 + b_k^2)`. The
//! class stays the paper's, from `v` and `s = sqrt(a2^2 + b2^2)` (mode 2). A 2-mode sweep's
//! table has none of them, and is unchanged.
use crate::store::run_store::RunRecord;
use polars::prelude::*;

/// `(a_k, b_k)` of a run at its end, for `k >= 3` (`None` beyond its `K`).
fn amplitude(r: &RunRecord, k: usize) -> (Option<f64>, Option<f64>) {
    let own = r.settings.modes;
    if k > own {
        return (None, None);
    }
    let h = &r.outcome.higher_modes;
    (h.get(k - 3).copied(), h.get(own - 2 + k - 3).copied())
}

/// The columns, empty when every run is a 2-mode run.
pub fn mode_columns(records: &[&RunRecord]) -> Vec<Column> {
    let k_top = records.iter().map(|r| r.settings.modes).max().unwrap_or(2);
    if k_top <= 2 {
        return Vec::new();
    }
    let mut cols = vec![Column::new(
        "modes".into(),
        records
            .iter()
            .map(|r| r.settings.modes as u32)
            .collect::<Vec<u32>>(),
    )];
    for (name, pick) in [("a", 0), ("b", 1)] {
        for k in 3..=k_top {
            let v: Vec<Option<f64>> = records
                .iter()
                .map(|r| {
                    let (a, b) = amplitude(r, k);
                    if pick == 0 {
                        a
                    } else {
                        b
                    }
                })
                .collect();
            cols.push(Column::new(format!("{name}{k}").into(), v));
        }
    }
    let total: Vec<f64> = records
        .iter()
        .map(|r| {
            let s = r.outcome.s;
            let higher: f64 = r.outcome.higher_modes.iter().map(|x| x * x).sum();
            (s * s + higher).sqrt()
        })
        .collect();
    cols.push(Column::new("deformation".into(), total));
    cols
}
