//! The `solver` section: the types are read here (a scheme name, an integer `n`, finite
//! numbers); every range and consistency check is `SolverSettings::validate` and
//! `droplet_solver::contract::limits::check_run`, the same checks `droplet simulate` makes, run
//! at the grid's points ([`super::grid::check_points`]) with the offending field mapped back to
//! its key.
use super::context::{show, Ctx, NumberField};
use crate::error::SpecError;
use droplet_solver::{
    contract::settings::ModelKind, contract::settings::SolverSettings, stepping::SchemeKind,
};
use serde_yaml::Mapping;

/// The keys of the section read by name (a scheme, an integer, a choice).
const NAMED: [&str; 3] = ["scheme", "n", "steady"];

/// The numeric settings of the section, each the key of its field's name.
const NUMBERS: [NumberField<SolverSettings>; 7] = [
    ("dt", |s| &mut s.dt),
    ("tol", |s| &mut s.tol),
    ("dt_max", |s| &mut s.dt_max),
    ("t_max", |s| &mut s.t_max),
    ("steady_tol", |s| &mut s.steady_tol),
    ("steady_window", |s| &mut s.steady_window),
    ("h0", |s| &mut s.h0),
];

/// Every key of the section.
pub(super) fn keys() -> Vec<&'static str> {
    NAMED
        .into_iter()
        .chain(FLAGS.iter().map(|(k, ..)| *k))
        .chain(NUMBERS.iter().map(|(k, _)| *k))
        .collect()
}

/// The on/off settings: each key, what `true` means, and its field.
type Flag = (
    &'static str,
    &'static str,
    fn(&mut SolverSettings) -> &mut bool,
);

const FLAGS: [Flag; 6] = [
    (
        "stop_beside_saddle",
        "stop a run beside a saddle it cannot leave before t_max",
        |s| &mut s.stop_beside_saddle,
    ),
    (
        "leap_departures",
        "leap along the linear stretch of a departure from a saddle",
        |s| &mut s.leap_departures,
    ),
    (
        "landing",
        "end a slow run where its one-dimensional quasi-steady flow lands; the default",
        |s| &mut s.landing,
    ),
    (
        "orientation_flow",
        "end a leaning run where the orientation's slow flow takes it (2-mode runs); the default",
        |s| &mut s.orientation_flow,
    ),
    (
        "run_on",
        "run a run not yet on a stable state on to 64 t_max (4 t_max with fixed steps); the default",
        |s| &mut s.run_on,
    ),
    (
        "projective_steps",
        "move on along slow phases by projective steps (adaptive spectral runs); the default",
        |s| &mut s.projective_steps,
    ),
];

/// Reads the on/off settings of the `solver` section `m` into `solver`.
fn flags(ctx: &Ctx, m: &Mapping, solver: &mut SolverSettings) -> Result<(), SpecError> {
    for (key, meaning, field) in FLAGS {
        if let Some(x) = m.get(key) {
            *field(solver) = x.as_bool().ok_or_else(|| {
                ctx.err(
                    &["solver", key],
                    show(x),
                    format!("true ({meaning}) or false"),
                )
            })?;
        }
    }
    Ok(())
}

/// The `solver` section for `model` (its types; the ranges are checked at the grid's points).
pub(super) fn parse(
    ctx: &Ctx,
    top: &Mapping,
    model: ModelKind,
) -> Result<SolverSettings, SpecError> {
    let mut solver = match model {
        ModelKind::Pde => SolverSettings::default(),
        ModelKind::Ode => SolverSettings::ode(),
    };
    if let Some(v) = top.get("solver") {
        // The model's shape modes are model parameters, not settings.
        if let Some((key, x)) = v.as_mapping().and_then(|m| {
            droplet_solver::model::params::ModelParams::SHAPE_MODE_FIELDS
                .into_iter()
                .find_map(|k| m.get(k).map(|x| (k, x)))
        }) {
            return Err(ctx.err(
                &["solver", key],
                show(x),
                format!("a model parameter: give it as params.{key}"),
            ));
        }
        let m = ctx.mapping(v, &["solver"], &keys())?;
        if let Some(x) = m.get("scheme") {
            solver.scheme = x
                .as_str()
                .and_then(|s| s.parse::<SchemeKind>().ok())
                .ok_or_else(|| ctx.err(&["solver", "scheme"], show(x), "spectral or paper-fd"))?;
            if solver.scheme == SchemeKind::PaperFd {
                let fd = SolverSettings::paper_fd();
                (solver.n, solver.dt, solver.tol, solver.steady) = (fd.n, fd.dt, fd.tol, fd.steady);
            }
        }
        if let Some(x) = m.get("n") {
            solver.n = x
                .as_u64()
                .and_then(|n| usize::try_from(n).ok())
                .ok_or_else(|| ctx.err(&["solver", "n"], show(x), "an even integer"))?;
        }
        if let Some(x) = m.get("steady") {
            solver.steady = x.as_str().and_then(|s| s.parse().ok()).ok_or_else(|| {
                ctx.err(
                    &["solver", "steady"],
                    show(x),
                    "newton (default for the spectral scheme) or test (the paper's test alone)",
                )
            })?;
        }
        flags(ctx, m, &mut solver)?;
        ctx.numbers(m, "solver", &NUMBERS, &mut solver)?;
    }
    Ok(solver)
}

#[cfg(test)]
mod tests {
    use super::*;
    use droplet_solver::model::params::ModelParams;
    use serde_json::Value as Json;

    /// The fields of `after` that differ from `before` (as serialised).
    fn changed<T: serde::Serialize>(before: &T, after: &T) -> Vec<String> {
        let (Json::Object(b), Json::Object(a)) = (
            serde_json::to_value(before).unwrap(),
            serde_json::to_value(after).unwrap(),
        ) else {
            panic!("not objects")
        };
        let mut keys: Vec<String> = b.keys().chain(a.keys()).cloned().collect();
        keys.sort();
        keys.dedup();
        keys.into_iter().filter(|k| b.get(k) != a.get(k)).collect()
    }

    /// A value for `key` other than its default for `model`, of the key's type.
    fn other_value(key: &str, model: ModelKind) -> &'static str {
        match key {
            "scheme" => "paper-fd",
            "n" => "128",
            "steady" if model == ModelKind::Ode => "newton",
            "steady" => "test",
            "stop_beside_saddle" | "leap_departures" => "true",
            "landing" | "orientation_flow" | "run_on" | "projective_steps" => "false",
            _ => "0.0123",
        }
    }

    #[test]
    fn the_shape_modes_in_the_solver_section_are_sent_to_params() {
        for key in ModelParams::SHAPE_MODE_FIELDS {
            let text = format!("solver:\n  n: 96\n  {key}: 3\n");
            let top: serde_yaml::Value = serde_yaml::from_str(&text).unwrap();
            let ctx = Ctx {
                file: "t.yaml",
                text: &text,
            };
            let e = parse(&ctx, top.as_mapping().unwrap(), ModelKind::Pde).unwrap_err();
            let message = e.to_string();
            assert!(
                message.contains(&format!("solver.{key}"))
                    && message.contains(&format!("params.{key}")),
                "{message}"
            );
        }
    }

    #[test]
    fn every_solver_key_sets_the_field_of_its_own_name_and_no_other() {
        let keys = keys();
        assert_eq!(keys.len(), 16, "{keys:?}");
        for key in keys {
            let for_model = |model| {
                let text = format!("solver:\n  {key}: {}\n", other_value(key, model));
                let top: serde_yaml::Value = serde_yaml::from_str(&text).unwrap();
                let ctx = Ctx {
                    file: "t.yaml",
                    text: &text,
                };
                let got = parse(&ctx, top.as_mapping().unwrap(), model).unwrap();
                let base = match model {
                    ModelKind::Pde => SolverSettings::default(),
                    ModelKind::Ode => SolverSettings::ode(),
                };
                changed(&base, &got)
            };
            for model in [ModelKind::Pde, ModelKind::Ode] {
                let fields = for_model(model);
                if key == "scheme" {
                    // The paper's scheme brings its own grid, step and ending (documented).
                    assert!(fields.contains(&"scheme".to_string()), "{key}: {fields:?}");
                    assert!(fields
                        .iter()
                        .all(|f| ["scheme", "n", "dt", "tol", "steady"].contains(&f.as_str())));
                } else {
                    assert_eq!(fields, [key], "solver.{key} with model {model:?}");
                }
            }
        }
    }

    #[test]
    fn every_params_key_sets_the_field_of_its_own_name_and_no_other() {
        for key in [
            "eta_t", "kappa2", "eta2", "radius", "sigma", "box_len", "mass",
        ] {
            let text = format!("params:\n  {key}: 0.0123\n");
            let top: serde_yaml::Value = serde_yaml::from_str(&text).unwrap();
            let ctx = Ctx {
                file: "t.yaml",
                text: &text,
            };
            let got = super::super::params::parse(&ctx, top.as_mapping().unwrap()).unwrap();
            assert_eq!(changed(&ModelParams::default(), &got), [key]);
            assert_eq!((got.modes, got.eta_k_exponent), (2, 0.0));
        }
    }
}
