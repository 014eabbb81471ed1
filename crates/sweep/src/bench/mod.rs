//! The work-precision benchmark (`droplet bench`): the cases and methods (`plan`, each method
//! of a typed `family`), their fine references computed once (`references`), the timed rows
//! and their scores (`scoring`), a whole benchmark run from references to files (`run`), its
//! Parquet table (`table`) and its picture (`precision_plot`); and a map's run time part by
//! part, on the map's own runs computed again (`map_profile`, `droplet bench --map`), and
//! what `refine.certify_midpoints` would make of a finished map (`certify_check`, `droplet
//! bench --map DIR --certify`).
//!
//! May use: every folder but `audit` and `studies`. Used by: the CLI.
pub mod certify_check;
pub mod family;
pub mod map_profile;
pub mod plan;
pub mod precision_plot;
pub mod references;
pub mod run;
pub mod scoring;
pub mod table;
