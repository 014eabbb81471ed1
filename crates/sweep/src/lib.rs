//! Sweeps of the droplet model over `(eta_t, kappa2)`: YAML specs, content-keyed run store
//! with resume, parallel execution, point classification, Parquet tables and pictures.
//! Data flows one way: spec -> plan -> runs (store) -> tables -> pictures.
pub mod atomic;
pub mod audit;
pub mod axes;
pub mod bench;
pub mod bench_run;
pub mod bench_table;
pub mod bifurcation_table;
pub mod boundary_table;
pub mod branch_lines;
pub mod continuation_table;
pub mod error;
pub mod execute;
pub mod h0_table;
pub mod level_walk;
pub mod line_compare;
pub mod merge;
pub mod merge_report;
pub mod phase;
pub mod phase_map;
pub mod pictures;
pub mod plan;
pub mod plot;
pub mod precision_plot;
pub mod progress;
pub mod refine;
pub mod render;
pub mod series_table;
pub mod shard;
pub mod slurm;
pub mod spec;
pub mod status;
pub mod store;
pub mod tables;
pub mod tally;

pub use error::{SpecError, SweepError};
pub use execute::{run_sweep, SweepOptions, SweepSummary};
pub use merge::merge;
pub use merge_report::MergeReport;
pub use spec::SweepSpec;
