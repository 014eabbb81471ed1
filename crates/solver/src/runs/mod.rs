//! One run of the full model, from an initial condition to its ending: the driver (`driver`:
//! the time loop and its stop rules), the Newton finish and the diagnosis of a run that is not
//! settled (`finish`; the early tries of K-mode runs, `early_try`, and their record,
//! `early_tries`), the leap along a departure from a saddle (`leap`), projective steps along a
//! slow phase (`projection`) and the landing of a
//! slow run where its one-dimensional quasi-steady flow ends (`landing`, and the walks along its
//! families, `walks`; docs/classification.md).
//!
//! May use: every folder below it (`numerics`, `model`, `stepping`, `contract`, `reduced`,
//! `roots`). Used by: the sweep crate and the CLI.
pub mod clock;
pub mod driver;
pub mod early_tries;
pub mod early_try;
pub mod finding;
pub mod finish;
pub mod landing;
pub mod leap;
pub mod orientation;
pub mod projection;
pub mod root_search;
pub mod rotation_flow;
pub mod turning;
pub mod walks;
