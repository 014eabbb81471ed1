//! The plan of a sweep and where its runs are kept: the tasks (every point and initial
//! condition, each keyed by a hash of everything that decides its result), the run store of an
//! output directory (one JSON file per finished run, written atomically, and the directory's
//! lock; each record sealed with its outcome's digest, `record_file`), the shards of a sweep split over processes, and atomic file writes.
//!
//! May use: `spec`, the crate's `error` and `merge_report`. Used by every folder above it.
pub mod atomic;
pub mod plan;
mod record_file;
pub mod run_store;
pub mod shard;
