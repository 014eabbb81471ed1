//! The work-precision benchmark (`droplet bench`): the cases and methods with their fine
//! references (`cases`), a whole benchmark run from references to files (`run`), its Parquet
//! table (`table`) and its picture (`precision_plot`).
//!
//! May use: every folder but `audit`. Used by: the CLI.
pub mod cases;
pub mod family;
pub mod precision_plot;
pub mod run;
pub mod table;
