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
//!   forces by Parseval, and the solves constrained to a mirror line that the landing uses).
//!
//! At `K = 2` the two give the same forces to round-off (tested in [`general`]).
pub mod general;
pub mod two_mode;

pub use general::{on_x_axis, MirrorState, SteadySolver};
pub use two_mode::{SteadyState, TwoModeSolver};

use crate::error::SolverError;
use crate::model::grid::Grid;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::model::shape::ShapeParams;

/// A steady solver's parameters moved to the value `x` of `param`, checked, and, for a
/// parameter that changes the droplet or the box (`radius`, `sigma`, `box_len`), the grid of
/// `n` points and the droplet it must sample again: `Ok(None)` when `x` is the value already
/// held. Refused where the parameters would be invalid or the grid would not resolve the
/// droplet ([`crate::contract::limits::check_resolved`]).
#[allow(clippy::type_complexity)]
pub(crate) fn moved(
    params: &ModelParams,
    n: usize,
    param: ModelParam,
    x: f64,
) -> Result<Option<(ModelParams, Option<(Grid, ShapeParams)>)>, SolverError> {
    if param.get(params) == x {
        return Ok(None);
    }
    let params = param.with(params, x);
    params.validate()?;
    if !param.is_geometric() {
        return Ok(Some((params, None)));
    }
    let grid = Grid::new(n, params.box_len)?;
    crate::contract::limits::check_resolved(&params, n)?;
    let shape = params.shape();
    Ok(Some((params, Some((grid, shape)))))
}
