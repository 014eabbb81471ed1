//! The reduced ODE model (paper Sect. 4-5, Appendices D-F): coefficients from modified Bessel
//! functions, the ODE dynamics (eqs. 58-59), its analytic phase boundaries, and its steady
//! states with their stability (bifurcation diagrams, Fig. 3).
pub mod bifurcation;
pub mod boundaries;
pub mod coefficients;
pub mod ode;

pub use coefficients::Coefficients;
