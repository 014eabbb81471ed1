//! Sweeps of the droplet model: YAML specs, a content-keyed run store with resume, parallel and
//! sharded execution, point classification and refinement, the audit of a map against the
//! stable states, Parquet tables and pictures.
//!
//! # Map of the crate
//!
//! Each folder holds one concern and uses only the folders listed before it (checked by
//! `tests/suite/module_graph.rs`):
//!
//! | folder | what it holds |
//! |---|---|
//! | [`spec`] | the YAML spec: strict parsing, the swept axes, the point lattice |
//! | [`store`] | the plan (tasks and run keys), the run store and its lock, shards, atomic writes |
//! | [`map`] | point classes, the phase map of a sweep, refinement, label counts, 1-D comparisons |
//! | [`tables`] | the Parquet tables (runs, points, series, branches, boundaries, `h0` fit), and read back as typed rows |
//! | [`audit`] | `droplet audit`: every label checked against the stable states at its point |
//! | [`pictures`] | the figures as PNG and SVG |
//! | [`execution`] | running, merging and watching a sweep; Slurm scripts; progress bars |
//! | [`studies`] | whole studies behind one command: exact phase boundaries, continuation |
//! | [`bench`] | the work-precision benchmark |
//!
//! [`error`] holds the crate's errors; [`merge_report`] what a merge found (errors carry it).
//!
//! # The path of one run
//!
//! A YAML line is parsed by [`spec::load`]; [`store::plan::plan`] turns the spec into
//! tasks, each keyed by a hash of its parameters, settings and initial condition;
//! [`execution::execute::run_sweep`] runs the tasks not yet in the [`store::run_store::Store`]
//! through `droplet_solver::runs::driver::simulate` and stores each outcome as it finishes;
//! [`map::phase_map::PhaseMap`] classes every point from its runs
//! ([`map::point_class`]); [`sweep_tables::sweep_tables`] writes one row per run to `runs.parquet`
//! and one per point to `points.parquet`; [`pictures::sweep_pictures`] draws the map.
pub mod audit;
pub mod bench;
pub mod error;
pub mod execution;
pub mod map;
pub mod merge_report;
pub mod pictures;
pub mod spec;
pub mod store;
pub mod studies;
pub mod tables;
