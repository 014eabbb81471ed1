//! The end-to-end tests of the `droplet` binary and of the committed results: one test binary
//! with a module per concern (as ripgrep's tests are), so that polars and the two library
//! crates are linked once, not once per file. `cargo test --release --test suite MODULE::`
//! runs one module.
//!
//! - `cli`: the commands, one file per group (sweep, axes, simulate, ode, commands,
//!   truncation, modes);
//! - `reliability`: bad input, corrupt and edited stored runs, kills and resume, full disks
//!   and closed streams, incomplete maps;
//! - `attractors`: every label an attractor (slow runs settled, the audit);
//! - `continuation`, `boundaries`, `stability`, `newton_finish`, `refine`: the commands of
//!   the same names end to end; `certify`: refinement's certified midpoints;
//! - `committed_results`: samples of the committed tables, recomputed;
//! - `slurm`: a sharded sweep under a real Slurm cluster (`.ci/run` brings one up);
//! - `module_graph`: the library crates' folders depend one way, without cycles.
//!
//! `common` holds the helpers they share.
mod attractors;
mod boundaries;
mod certify;
mod cli;
mod committed_results;
mod common;
mod continuation;
mod module_graph;
mod newton_finish;
mod refine;
mod reliability;
mod slurm;
mod stability;
