//! End-to-end tests through the `droplet` binary, one file per group of commands: `sweep`
//! (sweep, merge, resume, specs), `shards` (sharded sweeps merged), `axes` (sweeps in any
//! parameter), `plane_boundaries` (boundaries over them), `three_axes` (three-axis maps),
//! `simulate`, `ode`, `commands` (bench, help), `truncation` (the K-mode model),
//! `k_mode_states` (its boundaries, runs and branches), `modes` (K-mode sweeps), `shape_modes`
//! (K-mode single runs), `pictures` (what a map's picture shows beside its labels).
mod axes;
mod commands;
mod k_mode_states;
mod modes;
mod ode;
mod pictures;
mod plane_boundaries;
mod shape_modes;
mod shards;
mod simulate;
mod sweep;
mod three_axes;
mod truncation;

/// A tiny sweep (coarse grid, N = 32, fixed steps so that it lasts long enough to be
/// interrupted): seconds, enough for resume and locking tests.
pub(crate) const TINY: &str = "name: tiny
grid:
  eta_t: [0.07, 0.09, 0.11]
  kappa2: {start: 0.10, stop: 0.14, step: 0.02}
initial_conditions: [i, iii]
solver:
  n: 32
  dt: 0.05
  tol: 0
  t_max: 150
";
