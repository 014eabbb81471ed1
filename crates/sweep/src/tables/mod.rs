//! Parquet tables, each with key-value metadata (spec, versions, commit): a sweep's
//! `runs.parquet` and `points.parquet` (`sweep_tables`), a run's time series (`series`), the
//! reduced model's bifurcation diagrams (`bifurcation`), phase boundaries (`boundaries`),
//! continuation branches (`continuation`) and the Appendix E fit (`h0`).
//!
//! May use: `spec`, `store`, `map`. Used by: `pictures`, `execution`, `bench`, the CLI.
pub mod bifurcation;
pub mod boundaries;
pub mod continuation;
pub mod h0;
pub mod series;
pub mod sweep_tables;
