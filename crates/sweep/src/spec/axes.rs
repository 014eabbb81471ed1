//! The two swept parameters of a phase map, named in one place: spec keys, table columns,
//! picture axes and messages all take their names from here. A point is `(eta_t, kappa2)`
//! in this order.

/// Translational friction `eta_t` (the phase map's horizontal axis, Fig. 2a).
pub const ETA_T: &str = "eta_t";
/// Mode-2 stiffness `kappa2` (the vertical axis).
pub const KAPPA2: &str = "kappa2";
/// Both, in the order of a point's coordinates.
pub const AXES: [&str; 2] = [ETA_T, KAPPA2];

/// Rounds an axis value to 12 decimal places after the point: values on a decimal grid
/// (`0.07 + 3 * 0.01` is `0.1`), so that equal points in two specs, or on two refinement
/// levels, get equal run keys.
pub fn round12(x: f64) -> f64 {
    (x * 1e12).round() / 1e12
}
