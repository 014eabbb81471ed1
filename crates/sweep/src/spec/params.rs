//! The `params` section: the fixed model parameters (paper defaults where absent; `eta_t`
//! and `kappa2` default to the Fig. 1(c) point 0.085, 0.112 when no axis sweeps them), and
//! `modes: K`, the shape modes `2..K` of the paper's general model (default 2, the paper's).
//! Only the types are read here; the ranges are checked by `ModelParams::validate` and
//! `limits::check_run` (the solver's one source of truth) at the grid's points,
//! [`super::grid::check_points`].
use super::context::Ctx;
use crate::error::SpecError;
use droplet_solver::model::params::ModelParams;
use serde_yaml::Mapping;

/// The `params` section: the model parameters and the number of shape modes `K`.
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<(ModelParams, usize), SpecError> {
    let mut params = ModelParams::default();
    let Some(v) = top.get("params") else {
        return Ok((params, 2));
    };
    let keys = [
        "eta_t", "kappa2", "eta2", "radius", "sigma", "box_len", "mass",
    ];
    let all = [&keys[..], &["modes"]].concat();
    let m = ctx.mapping(v, &["params"], &all)?;
    let modes = match m.get("modes") {
        None => 2,
        Some(x) => ctx.number(
            x,
            &["params", "modes"],
            |k| k.fract() == 0.0 && (0.0..=1e6).contains(&k),
            "an integer K from 2 to 16: shape modes 2..K (2: the paper's)",
        )? as usize,
    };
    ctx.numbers(m, "params", &keys, |key, val| match key {
        "eta_t" => params.eta_t = val,
        "kappa2" => params.kappa2 = val,
        "eta2" => params.eta2 = val,
        "radius" => params.radius = val,
        "sigma" => params.sigma = val,
        "box_len" => params.box_len = val,
        _ => params.mass = val,
    })?;
    Ok((params, modes))
}
