//! The default scheme: pseudo-spectral ETD2RK in the droplet's co-moving frame, fixed or
//! adaptive steps with its embedded error estimate (docs/model.md, "Solving it in the
//! droplet's frame"). Every ETD-RK step keeps the ODE's fixed points, so a steadily moving
//! droplet is an exact fixed point of the scheme whatever the step. One scheme, two
//! implementations, chosen once per run by [`crate::runs::driver`]:
//!
//! - [`general`]: [`ComovingEtd`], every shape with modes `2..K` (forces by quadrature, the
//!   predictor from the last two states, [`predictor`]);
//! - [`two_mode`]: [`TwoModeEtd`], the fast path of `K = 2` (the droplet's point symmetry,
//!   forces by Parseval fused into two passes over the spectrum, [`spectral_pass`]; one step
//!   in four parts, [`two_mode_step`]).
//!
//! At `K = 2` they differ by `O(h^2)` at a fixed time (the general step extrapolates its
//! predictor's field gradient, [`predictor`]), not by a discretisation of their own (tested
//! in [`general`]).
pub mod general;
pub mod predictor;
pub mod spectral_pass;
pub mod two_mode;
pub mod two_mode_step;

pub use general::ComovingEtd;
pub use two_mode::TwoModeEtd;
