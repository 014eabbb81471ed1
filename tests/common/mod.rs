//! Helpers shared by the end-to-end test binaries.
use polars::prelude::*;
use std::path::Path;
use std::process::Command;

/// The `droplet` binary under test.
pub fn droplet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_droplet"))
}

/// A Parquet table.
pub fn read(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap())
        .finish()
        .unwrap()
}

/// A table without its wall-clock column (the one value that differs between two runs).
pub fn table_without_wall(path: &Path) -> DataFrame {
    let df = read(path);
    if df.schema().contains("wall_s") {
        df.drop("wall_s").unwrap()
    } else {
        df
    }
}
