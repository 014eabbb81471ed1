//! The droplet model of Kitahata, Koyano, Kobayashi & Nagayama, "Energetics-based model for a
//! diffusiophoretic motion of a deformable droplet": a co-moving pseudo-spectral integrator
//! (default), the paper's finite-difference scheme (baseline), the exact steady state, the
//! stop rules and the classification of Sect. 3.
pub mod bessel;
pub mod classify;
pub mod continuation;
pub mod departure_leap;
pub mod dynamics;
pub mod error;
pub mod etd;
pub mod fft2;
pub mod forces;
pub mod grid;
pub mod h0_fit;
pub mod initial;
pub mod landing;
pub mod limits;
pub mod named_state;
pub mod newton;
pub mod newton_finish;
pub mod outcome;
pub mod params;
pub mod reduced;
pub mod run;
pub mod scheme;
pub mod settings;
pub mod shape;
pub mod shape_transform;
pub mod stability;
pub mod state;
pub mod steady;
pub mod steady_method;
pub mod step_control;
pub mod stop_rule;
pub mod verdict;

pub use classify::StateClass;
pub use error::SolverError;
pub use initial::InitialCondition;
pub use outcome::{RunOutcome, RunStatus, SeriesRow, Unsettled, STEP_ERROR_LIMIT};
pub use params::ModelParams;
pub use run::{simulate, Run};
pub use scheme::{Scheme, SchemeKind};
pub use settings::{ModelKind, SolverSettings};
pub use state::DropletState;
pub use steady::{SteadySolver, SteadyState};

/// Version of the solver's numerics (the PDE model's runs); part of every run's cache key.
/// 2: the Newton finish compares a run's orientation with its root's like with like, so a run
/// slowing down onto a resting ID ends there instead of creeping on (some to `t_max`).
/// 3: an unfinished run's diagnosis calls its speed and deformation settled (it only turns)
/// only if they are within the class threshold of its root's, with its class.
/// 4: only a run that ends on a stable root has a class (`unsettled`, `heading` for the
/// rest); slow runs end where their one-dimensional quasi-steady flow lands
/// ([`landing`]); the rotation mode is only looked for at states away from the disk
/// (`verdict::ROTATION_MIN_NORM`) and among near-neutral eigenvalues.
/// 5: no landing on a root unstable in its rotation mode (the run's turn decides between
/// competing orientations); a turn may end on a root of another class within the box's
/// anisotropy (MD on one mirror line, MC on the other).
pub const SOLVER_VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "+numerics-5");

/// Version of the reduced ODE model's numerics (2: unstable states no longer end a run;
/// 3: a run that does not end steady has no class).
pub const ODE_SOLVER_VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "+numerics-1+ode-3");

/// The numerics version of a model's runs, part of their cache key: a change to one model's
/// results invalidates its stored runs only.
pub fn solver_version(model: ModelKind) -> &'static str {
    match model {
        ModelKind::Pde => SOLVER_VERSION,
        ModelKind::Ode => ODE_SOLVER_VERSION,
    }
}
