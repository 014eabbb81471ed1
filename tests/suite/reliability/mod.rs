//! Reliability through the `droplet` binary: nothing lost, nothing hung.
//!
//! - a catalogue of malformed and extreme inputs: each exits with its documented code
//!   (2 for bad input), names what is wrong, never panics, and returns within seconds (the
//!   tiny-step cases within one);
//! - corrupt stored runs are reported, moved aside and recomputed; `merge` refuses to build
//!   tables while a run is missing or unreadable;
//! - an oversized spec is refused before anything is written;
//! - SIGKILL at many moments, then resume: tables identical to an uninterrupted sweep;
//! - stale temporaries of interrupted table and picture writes are removed by the next run;
//! - a whole sweep and a shard never work on one directory at the same time;
//! - `droplet audit` fails a map with a run missing, duplicated, foreign or mislabelled.
//!
//! With `DROPLET_RELIABILITY_DIR` set, the catalogue and kill tests write their counts there
//! (`inputs.md`, `kills.md`): the README's reliability section quotes them.
//!
//! One file per concern: `catalogue` (bad input; its cases for files and windows in
//! `refusals`, for specs and round 4's settings in `spec_refusals`), `store` (corrupt runs, resume
//! after kills, temporaries, locks), `output` (a full disk, a closed pipe, pictures and
//! messages), `audit` (complete maps only), `round4` (edited and re-keyed stored runs, a full
//! stderr, directories in use, continuation files of their own).
mod audit;
mod catalogue;
mod output;
mod refusals;
mod round4;
mod spec_refusals;
mod store;

use crate::common::table_without_wall;
use std::path::{Path, PathBuf};

/// Writes a report section when `DROPLET_RELIABILITY_DIR` is set.
pub(crate) fn report(name: &str, text: &str) {
    if let Ok(dir) = std::env::var("DROPLET_RELIABILITY_DIR") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(Path::new(&dir).join(name), text).unwrap();
    }
}

/// A tiny sweep: 12 runs at N = 32, fixed steps; a fraction of a second per run.
pub(crate) const TINY: &str = "name: tiny
grid:
  eta_t: [0.07, 0.09, 0.11]
  kappa2: [0.10, 0.12]
initial_conditions: [i, iii]
solver:
  n: 32
  dt: 0.05
  tol: 0
  t_max: 150
";

pub(crate) fn tables_equal(a: &Path, b: &Path) {
    for t in ["runs.parquet", "points.parquet"] {
        let x = table_without_wall(&a.join(t));
        let y = table_without_wall(&b.join(t));
        assert!(x.equals_missing(&y), "{t} differs:\n{x}\n{y}");
    }
}

pub(crate) fn run_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir.join("runs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    v.sort();
    v
}
