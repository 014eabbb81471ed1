//! The `params` section: the fixed model parameters (paper defaults where absent; `eta_t`
//! and `kappa2` default to the Fig. 1(c) point 0.085, 0.112 when no axis sweeps them). Only the
//! types are read here; the ranges are checked by `ModelParams::validate` (the solver's one
//! source of truth) at the grid's points, [`super::grid::check_points`].
use super::context::Ctx;
use crate::error::SpecError;
use droplet_solver::model::params::ModelParams;
use serde_yaml::Mapping;

/// The `params` section.
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<ModelParams, SpecError> {
    let mut params = ModelParams::default();
    let Some(v) = top.get("params") else {
        return Ok(params);
    };
    let keys = [
        "eta_t", "kappa2", "eta2", "radius", "sigma", "box_len", "mass",
    ];
    let m = ctx.mapping(v, &["params"], &keys)?;
    ctx.numbers(m, "params", &keys, |key, val| match key {
        "eta_t" => params.eta_t = val,
        "kappa2" => params.kappa2 = val,
        "eta2" => params.eta2 = val,
        "radius" => params.radius = val,
        "sigma" => params.sigma = val,
        "box_len" => params.box_len = val,
        _ => params.mass = val,
    })?;
    Ok(params)
}
