//! The droplet model of the paper (Sect. 2-3): its parameters, the mechanical state
//! `(r_c, v, a2, b2)`, the initial conditions, the grid of the co-moving frame, the smoothed
//! indicator and its transforms, the driving forces (eqs. 35-37), the equations of motion
//! (eqs. 36-39 with the inertia `m`) and the classes IC / ID / MD / MC of a steady state; the
//! general shape with modes `k = 2..K` and its fields `w_k` (`modes`), and their friction
//! `eta_k` (`friction`).
//!
//! May use: `numerics`. Used by every folder above it.
pub mod classify;
pub mod dynamics;
pub mod forces;
pub mod friction;
pub mod grid;
pub mod initial;
pub mod mirror;
pub mod modes;
pub mod param;
pub mod params;
pub mod shape;
pub mod shape_transform;
pub mod state;
