//! The reduced ODE model (paper Sect. 4-5, Appendices D-F): coefficients from modified Bessel
//! functions, the ODE dynamics (eqs. 58-59), its analytic phase boundaries, and its steady
//! states with their stability (bifurcation diagrams, Fig. 3).
//!
//! May use: `numerics`, `model`, `contract` (its runs end like the full model's). Used by:
//! `roots` (starting guesses), `runs` (the ODE model's runs), `continuation`.
pub mod bifurcation;
pub mod boundaries;
pub mod coefficients;
pub mod ode;
