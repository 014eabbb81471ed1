//! Compares two Parquet tables column by column, ignoring `wall_s` (the one column that
//! differs between two runs of the same work), and prints one line per column that differs.
//! Exit code 0: equal; 1: different.
//!
//! ```sh
//! cargo run --release -p droplet-sweep --example table_diff -- a/runs.parquet b/runs.parquet
//! ```
use polars::prelude::*;

fn read(path: &str) -> DataFrame {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    ParquetReader::new(file)
        .finish()
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [a, b] = &args[..] else {
        eprintln!("usage: table_diff A.parquet B.parquet");
        std::process::exit(2);
    };
    let (x, y) = (read(a), read(b));
    let mut differ = 0;
    if x.height() != y.height() {
        println!("rows: {} vs {}", x.height(), y.height());
        differ += 1;
    }
    let names: Vec<String> = x.get_column_names().iter().map(|s| s.to_string()).collect();
    let other: Vec<String> = y.get_column_names().iter().map(|s| s.to_string()).collect();
    if names != other {
        println!("columns: {names:?} vs {other:?}");
        differ += 1;
    }
    for name in names.iter().filter(|n| *n != "wall_s" && other.contains(n)) {
        let (c, d) = (x.column(name).unwrap(), y.column(name).unwrap());
        let (c, d) = (c.as_materialized_series(), d.as_materialized_series());
        if !c.equals_missing(d) {
            let gap = match (c.f64(), d.f64()) {
                (Ok(c), Ok(d)) => {
                    let (mut max, mut n) = (0.0f64, 0);
                    for (p, q) in c.iter().zip(d.iter()) {
                        if let (Some(p), Some(q)) = (p, q) {
                            if p != q {
                                n += 1;
                                max = max.max((p - q).abs());
                            }
                        }
                    }
                    format!(": {n} values, largest difference {max:.3e}")
                }
                _ => String::new(),
            };
            println!("column {name} differs{gap}");
            differ += 1;
        }
    }
    println!(
        "{}: {} rows, {} columns compared (wall_s ignored), {differ} differences",
        if differ == 0 { "equal" } else { "DIFFERENT" },
        x.height(),
        names.len()
    );
    std::process::exit(i32::from(differ > 0));
}
