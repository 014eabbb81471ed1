//! Sweeps of the droplet model over `(eta_t, kappa2)`: YAML specs, content-keyed run store
//! with resume, parallel execution, point classification, Parquet tables and pictures.
//! Data flows one way: spec -> plan -> runs (store) -> tables -> pictures.
pub mod bench;
pub mod branch_lines;
pub mod error;
pub mod execute;
pub mod phase;
pub mod plan;
pub mod plot;
pub mod precision_plot;
pub mod render;
pub mod shard;
pub mod spec;
pub mod status;
pub mod store;
pub mod tables;

pub use error::{SpecError, SweepError};
pub use execute::{merge, run_sweep, MergeReport, SweepOptions, SweepSummary};
pub use spec::SweepSpec;
