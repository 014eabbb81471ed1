//! Parquet tables, each with key-value metadata (spec, versions, commit): a sweep's
//! `runs.parquet` and `points.parquet` (`sweep_tables`), a run's time series (`series`), the
//! reduced model's bifurcation diagrams (`bifurcation`), phase boundaries (`boundaries`),
//! continuation branches at any number of shape modes (`continuation`), the
//! truncation study (`truncation`) and the Appendix E fit (`h0`); a finished map's
//! tables read back as typed rows (`read`).
//!
//! May use: `spec`, `store`, `map`. Used by: `audit`, `pictures`, `execution`, `bench`, the CLI.
pub mod bifurcation;
pub mod boundaries;
pub mod continuation;
pub mod h0;
pub mod read;
pub mod series;
pub mod shape_columns;
pub mod sweep_tables;
pub mod truncation;
