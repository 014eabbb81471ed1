//! What a run is asked and what it answers: its settings (model, scheme, grid, steps, stop
//! rules) and their limits, how it may end steady (`ending`), the paper's stop rules, and its
//! outcome (status, final state, class or the reason it is unsettled, time series) with its
//! profile (where its time went). Shared by
//! the PDE run driver (`runs`), the reduced model and the sweep crate.
//!
//! May use: `model`, `stepping` (the scheme setting). Used by: `reduced`, `roots`, `runs`,
//! `continuation`.
pub mod ending;
pub mod honoured;
pub mod limits;
pub mod outcome;
pub mod profile;
pub mod settings;
pub mod stop_rule;
