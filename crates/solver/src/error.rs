//! Typed errors of the solver crate.
use thiserror::Error;

/// Everything that can go wrong when setting up or running a simulation.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolverError {
    /// A model or solver parameter is outside its allowed range.
    #[error("invalid parameter `{name}` = {}: {allowed}", show_number(*.value))]
    InvalidParameter {
        name: &'static str,
        value: f64,
        allowed: String,
    },
    /// A named option with a value that is not allowed here.
    #[error("invalid `{name}` = {value}: {allowed}")]
    InvalidChoice {
        name: &'static str,
        value: String,
        allowed: String,
    },
    /// A named initial condition that does not exist.
    #[error("unknown initial condition `{0}`: allowed are i, ii, iii, iv, i', ii' or custom:vx,vy,a2,b2 (then a3,b3,a4,b4,... for K-mode runs)")]
    UnknownInitialCondition(String),
    /// A custom initial condition whose values are outside the model.
    #[error("invalid initial condition `{text}`: {reason}")]
    InvalidInitialCondition { text: String, reason: String },
    /// A scheme name that does not exist.
    #[error("unknown scheme `{0}`: allowed are spectral, paper-fd")]
    UnknownScheme(String),
    /// The Newton iteration of the exact steady-state solver did not converge.
    #[error("steady-state Newton solve did not converge (residual {residual:e} after {iterations} iterations)")]
    NewtonFailed { residual: f64, iterations: usize },
    /// The Newton solve for a moving state converged, but to a droplet at rest.
    #[error("the steady-state Newton solve converged (residual {residual:.1e} after {iterations} iterations) to a resting droplet (v = {v:.1e}), not to a moving one")]
    RestingRoot {
        residual: f64,
        iterations: usize,
        v: f64,
    },
    /// Continuation found no state of the family anywhere on its line.
    #[error("no {family} state found on the line (Newton from the reduced model's states failed at 9 points); try another range or --axis")]
    NoBranch { family: &'static str },
}

/// A number as a person reads it: plain for ordinary magnitudes, in exponent form when tiny
/// or huge (`1e-300`, not three hundred zeros).
pub fn show_number(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-4..1e7).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// Shorthand for a finite-and-in-range check.
pub(crate) fn require(
    ok: bool,
    name: &'static str,
    value: f64,
    allowed: impl Into<String>,
) -> Result<(), SolverError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(SolverError::InvalidParameter {
            name,
            value,
            allowed: allowed.into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_well_in_messages() {
        assert_eq!(show_number(1e-300), "1e-300");
        assert_eq!(show_number(0.02), "0.02");
        assert_eq!(show_number(-0.1), "-0.1");
        assert_eq!(show_number(0.0), "0");
        assert_eq!(show_number(2e9), "2e9");
        assert_eq!(show_number(f64::NAN), "NaN");
    }
}
