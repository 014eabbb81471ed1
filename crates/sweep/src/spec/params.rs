//! The `params` section: the fixed model parameters (paper defaults where absent; `eta_t`
//! and `kappa2` default to the Fig. 1(c) point 0.085, 0.112 when no axis sweeps them), and
//! `modes: K`, the shape modes `2..K` of the paper's general model (default 2, the paper's),
//! with `eta_k_exponent: p`, their friction law `eta_k = eta2 (k/2)^p` (default 0).
//! Only the types are read here; the ranges are checked by `ModelParams::validate` and
//! `limits::check_run` (the solver's one source of truth) at the grid's points,
//! [`super::grid::check_points`].
use super::context::{Ctx, NumberField};
use crate::error::SpecError;
use droplet_solver::model::params::ModelParams;
use serde_yaml::Mapping;

/// The model parameters of the section, each the key of its field's name.
const NUMBERS: [NumberField<ModelParams>; 7] = [
    ("eta_t", |p| &mut p.eta_t),
    ("kappa2", |p| &mut p.kappa2),
    ("eta2", |p| &mut p.eta2),
    ("radius", |p| &mut p.radius),
    ("sigma", |p| &mut p.sigma),
    ("box_len", |p| &mut p.box_len),
    ("mass", |p| &mut p.mass),
];

/// The `params` section: the model parameters, the shape modes among them.
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<ModelParams, SpecError> {
    let mut params = ModelParams::default();
    let Some(v) = top.get("params") else {
        return Ok(params);
    };
    let all: Vec<&str> = NUMBERS
        .iter()
        .map(|(k, _)| *k)
        .chain(ModelParams::SHAPE_MODE_FIELDS)
        .collect();
    let m = ctx.mapping(v, &["params"], &all)?;
    if let Some(x) = m.get("modes") {
        params.modes = ctx.number(
            x,
            &["params", "modes"],
            |k| {
                k.fract() == 0.0
                    && (2.0..=droplet_solver::contract::limits::MAX_MODES as f64).contains(&k)
            },
            "an integer K from 2 to 16: shape modes 2..K (2: the paper's)",
        )? as usize;
    }
    if let Some(x) = m.get("eta_k_exponent") {
        // The range is the solver's to check (ModelParams::validate).
        params.eta_k_exponent = ctx.number(
            x,
            &["params", "eta_k_exponent"],
            f64::is_finite,
            "a number p: eta_k = eta2 (k/2)^p for the shape modes k >= 3 (0: the default)",
        )?;
    }
    ctx.numbers(m, "params", &NUMBERS, &mut params)?;
    Ok(params)
}
