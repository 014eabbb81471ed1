//! Steady states of the model in the droplet's co-moving frame (docs/model.md, "Steady states
//! as roots"): for a droplet of shape `{a_k, b_k}` moving at `v` the field
//! `u_hat = Theta_hat / (A (1 + k^2 - i k.v))` solves `0 = Lap u - u + v.grad u + Theta / A`
//! (paper eq. S13), and Newton solves the force balances `-eta_t v + F = 0`,
//! `G_k - kappa_k (a_k, b_k) = 0`. One concept, two implementations of the same
//! discretisation, chosen once per model by [`crate::roots::balances::Balances`]:
//!
//! - [`general`]: [`SteadySolver`], every shape with modes `2..K` (forces by quadrature,
//!   [`crate::model::forces::quadrature`]);
//! - [`two_mode`]: [`TwoModeSolver`], the fast path of `K = 2` (the droplet's point symmetry,
//!   forces by Parseval, the chord method with kept Jacobians, and the solves constrained to a
//!   mirror line that the landing uses).
//!
//! At `K = 2` the two give the same forces to round-off (tested in [`general`]).
pub mod general;
pub mod two_mode;

pub use general::{on_x_axis, AxisState, SteadySolver};
pub use two_mode::{KeptJacobians, SteadyState, TwoModeSolver};
