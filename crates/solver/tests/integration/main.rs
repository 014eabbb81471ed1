//! The solver's integration tests: one test binary with a module per concern, so that the
//! crate is linked once for all of them and their tests share the machine's threads.
//! `cargo test --release -p droplet-solver --test integration MODULE::` runs one module.
//!
//! - `adaptive`: adaptive ETD2RK stepping against fixed steps and its tolerance;
//! - `continuation`: continuation against the time stepper, the fold curve against the
//!   one-parameter folds, the branches' meeting points against the exact thresholds;
//! - `modes`: the model with shape modes 2..K, its runs against its own MD fold;
//! - `newton_finish`: the Newton finish against time stepping alone;
//! - `physics`: analytic solutions, conservation, symmetry, convergence, exact fixed points;
//! - `slow_endings`: how K-mode runs end their slow stretches (a turn, the disk, a departure
//!   leapt, a saddle stop) against pure time stepping;
//! - `stress`: random parameters in and beyond the paper's window end with a status.
mod adaptive;
mod continuation;
mod modes;
mod newton_finish;
mod physics;
mod slow_endings;
mod stress;
