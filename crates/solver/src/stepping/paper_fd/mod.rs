//! The paper's own scheme (Sect. 3), the baseline for speed and error comparisons: forward
//! Euler on the lab grid, the 5-point Laplacian, central differences for `grad u`
//! ([`finite_differences`]) and `Theta` at the droplet's position (minimum image); the paper's
//! settings are dx = 0.025, dt = 1e-4. One scheme, two implementations, chosen once per run
//! by [`crate::runs::driver`]:
//!
//! - [`general`]: [`PaperFd`], every shape with modes `2..K`;
//! - [`two_mode`]: [`TwoModeFd`], `K = 2` with the mode-2 shape's own sampler.
//!
//! At `K = 2` they agree to round-off (tested in [`general`]).
pub mod finite_differences;
pub mod general;
pub mod two_mode;

pub use general::PaperFd;
pub use two_mode::TwoModeFd;
