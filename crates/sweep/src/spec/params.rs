//! The `params` section: the fixed model parameters (paper defaults where absent), checked by
//! `ModelParams::validate` (the solver's one source of truth) after the types are read.
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
    let keys = ["eta2", "radius", "sigma", "box_len", "mass"];
    let m = ctx.mapping(v, &["params"], &keys)?;
    ctx.numbers(m, "params", &keys, |key, val| match key {
        "eta2" => params.eta2 = val,
        "radius" => params.radius = val,
        "sigma" => params.sigma = val,
        "box_len" => params.box_len = val,
        _ => params.mass = val,
    })?;
    ctx.checked(params.validate())?;
    Ok(params)
}
