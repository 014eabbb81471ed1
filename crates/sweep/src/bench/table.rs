//! The benchmark's Parquet table: one row per timed run, written and read back (re-scoring).
use crate::bench::family::Family;
use crate::bench::scoring::BenchRow;
use crate::error::SweepError;
use crate::tables::sweep_tables::{f64_col, str_col};
use polars::prelude::*;
use std::fs::File;
use std::path::Path;

/// The work-precision benchmark's rows ([`crate::bench`]).
pub fn bench_frame(rows: &[BenchRow]) -> Result<DataFrame, SweepError> {
    use BenchRow;
    let f = |g: fn(&BenchRow) -> f64| rows.iter().map(g).collect::<Vec<f64>>();
    let st = |g: fn(&BenchRow) -> String| rows.iter().map(g).collect::<Vec<String>>();
    let opt = |g: fn(&BenchRow) -> Option<f64>| rows.iter().map(g).collect::<Vec<Option<f64>>>();
    let cols = vec![
        str_col("case", st(|r| r.case.clone())),
        str_col("family", st(|r| r.family.to_string())),
        str_col("scheme", st(|r| r.scheme.clone())),
        Column::new(
            "n".into(),
            rows.iter().map(|r| r.n as u32).collect::<Vec<u32>>(),
        ),
        f64_col("dt", f(|r| r.dt)),
        f64_col("tol", f(|r| r.tol)),
        f64_col("dt_max", f(|r| r.dt_max)),
        str_col("steady", st(|r| r.steady.clone())),
        str_col("status", st(|r| r.status.clone())),
        Column::new(
            "class".into(),
            rows.iter()
                .map(|r| r.class.clone())
                .collect::<Vec<Option<String>>>(),
        ),
        Column::new(
            "class_ok".into(),
            rows.iter().map(|r| r.class_ok).collect::<Vec<bool>>(),
        ),
        f64_col("v", f(|r| r.v)),
        f64_col("s", f(|r| r.s)),
        f64_col("err_v", f(|r| r.err_v)),
        f64_col("err_s", f(|r| r.err_s)),
        Column::new("err_series".into(), opt(|r| r.err_series)),
        f64_col("t_end", f(|r| r.t_end)),
        Column::new(
            "steps".into(),
            rows.iter().map(|r| r.steps).collect::<Vec<u64>>(),
        ),
        Column::new(
            "rejected".into(),
            rows.iter().map(|r| r.rejected).collect::<Vec<u64>>(),
        ),
        Column::new("max_step_error".into(), opt(|r| r.max_step_error)),
        f64_col("wall_s", f(|r| r.wall_s)),
    ];
    Ok(DataFrame::new(rows.len(), cols)?)
}

/// Reads the rows of a `bench.parquet` written by [`bench_frame`].
pub fn read_bench(path: &Path) -> Result<Vec<BenchRow>, SweepError> {
    let file = File::open(path).map_err(|e| SweepError::io(path, e))?;
    let df = ParquetReader::new(file).finish()?;
    let h = df.height();
    let s = |c: &str| -> Result<Vec<Option<String>>, SweepError> {
        let col = df.column(c)?.str()?.clone();
        Ok((0..h).map(|i| col.get(i).map(str::to_string)).collect())
    };
    let f = |c: &str| -> Result<Vec<Option<f64>>, SweepError> {
        let col = df.column(c)?.f64()?.clone();
        Ok((0..h).map(|i| col.get(i)).collect())
    };
    let u = |c: &str| -> Result<Vec<Option<u64>>, SweepError> {
        let col = df.column(c)?.cast(&DataType::UInt64)?;
        let col = col.u64()?;
        Ok((0..h).map(|i| col.get(i)).collect())
    };
    let (case, family, scheme, status, class) = (
        s("case")?,
        s("family")?,
        s("scheme")?,
        s("status")?,
        s("class")?,
    );
    let family = family
        .iter()
        .map(|f| {
            f.as_deref()
                .unwrap_or_default()
                .parse::<Family>()
                .map_err(|e| SweepError::Invalid(format!("{}: {e}", path.display())))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let (n, steps, rejected) = (u("n")?, u("steps")?, u("rejected")?);
    // Tables written before the Newton finish have no `steady` column: all ran the test.
    let steady = if df.get_column_names().iter().any(|c| c.as_str() == "steady") {
        s("steady")?
    } else {
        vec![Some("test".to_string()); h]
    };
    let (dt, tol, dt_max, v, sv) = (f("dt")?, f("tol")?, f("dt_max")?, f("v")?, f("s")?);
    let (err_v, err_s, err_series) = (f("err_v")?, f("err_s")?, f("err_series")?);
    let (t_end, mse, wall) = (f("t_end")?, f("max_step_error")?, f("wall_s")?);
    let ok_col = df.column("class_ok")?.bool()?.clone();
    let ok: Vec<Option<bool>> = (0..h).map(|i| ok_col.get(i)).collect();
    let nan = |x: Option<f64>| x.unwrap_or(f64::NAN);
    Ok((0..df.height())
        .map(|i| BenchRow {
            case: case[i].clone().unwrap_or_default(),
            family: family[i],
            scheme: scheme[i].clone().unwrap_or_default(),
            n: n[i].unwrap_or(0) as usize,
            dt: nan(dt[i]),
            tol: nan(tol[i]),
            dt_max: nan(dt_max[i]),
            steady: steady[i].clone().unwrap_or_else(|| "test".into()),
            status: status[i].clone().unwrap_or_default(),
            class: class[i].clone(),
            class_ok: ok[i].unwrap_or(false),
            v: nan(v[i]),
            s: nan(sv[i]),
            err_v: nan(err_v[i]),
            err_s: nan(err_s[i]),
            err_series: err_series[i],
            t_end: nan(t_end[i]),
            steps: steps[i].unwrap_or(0),
            rejected: rejected[i].unwrap_or(0),
            max_step_error: mse[i],
            wall_s: nan(wall[i]),
        })
        .collect())
}
