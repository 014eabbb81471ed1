//! Sweep specs (YAML): strict parsing with the file, key path, line, bad value and what is
//! allowed in every error.
//!
//! ```yaml
//! name: smoke                 # [A-Za-z0-9_.-]+ ; default: the file's stem
//! output: out/smoke           # default: out/<name>
//! model: pde                  # pde (Sect. 3) or ode (reduced model, eqs. 58-59)
//! params: {eta2: 0.1, radius: 1, sigma: 0.03, box_len: 7, mass: 0.1}   # paper defaults
//! grid:                       # 1-3 axes: any model parameter, or n, tol, dt_max, t_max
//!   eta_t: {start: 0.07, stop: 0.10, step: 0.01}    # inclusive range ...
//!   kappa2: [0.11, 0.12]                            # ... or an explicit list
//! initial_conditions: [i, ii, iii, iv]              # default: the paper's four
//! solver: {scheme: spectral, n: 192, dt: 0.02, tol: 1.0e-4, dt_max: 0.25, t_max: 2000,
//!          steady_tol: 1.0e-6, steady_window: 0.1}
//! refine: {levels: 4, min_step: {eta_t: 1.5e-4, kappa2: 3e-4}}   # optional (two range axes)
//!                             # tol: adaptive stepping (0 = fixed step dt; spectral only)
//!                             # ode: dt default 0.05, and h0 (default 0.1436)
//! ```
//!
//! One file per section: [`context`] (locating keys, typed accessors, error paths),
//! [`grid`], [`params`], [`initial`], [`solver`], [`refine`], [`classify`]. Range checks are the
//! solver crate's own (`ModelParams::validate`, `SolverSettings::validate`, `limits::check_run`), the same as for
//! `droplet simulate`. `axes` names the swept parameters; `lattice` is the integer point lattice of
//! a refined sweep.
//!
//! May use: the crate's `error` (and the solver crate). Used by every other folder.
pub mod axes;
mod classify;
mod context;
mod grid;
mod initial;
pub mod lattice;
mod params;
mod refine;
mod solver;

use crate::error::SpecError;
use context::{show, Ctx};
use droplet_solver::{
    contract::settings::ModelKind, contract::settings::SolverSettings,
    model::initial::InitialCondition, model::params::ModelParams,
};
use serde::Serialize;
use serde_yaml::Value;
use std::path::{Path, PathBuf};

pub use context::locate;
pub use grid::{Grid, Swept, MAX_AXES, MAX_AXIS_POINTS};
pub use refine::MAX_LEVELS;

/// A validated sweep spec.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepSpec {
    pub name: String,
    pub output: PathBuf,
    /// Fixed parameters; the swept ones are overwritten per point.
    pub params: ModelParams,
    /// The swept axes.
    pub grid: Grid,
    pub initial_conditions: Vec<InitialCondition>,
    pub solver: SolverSettings,
    /// Adaptive refinement of the grid (`refine:`), if asked for.
    pub refine: Option<crate::spec::lattice::Lattice>,
    /// How point classes count runs stopped beside an unstable state (`classify:`).
    /// The spec's text, stored in the output metadata.
    #[serde(skip)]
    pub source: String,
}

/// Largest spec file accepted (a list of [`MAX_AXIS_POINTS`] values on each axis fits).
pub const MAX_SPEC_BYTES: usize = 4 << 20;

/// Longest `name` (it is copied into every table's metadata and every picture's title).
pub const MAX_NAME_CHARS: usize = 100;

/// The error for a spec text over [`MAX_SPEC_BYTES`].
fn too_large(file: &str, bytes: u64) -> SpecError {
    SpecError {
        file: file.to_string(),
        path: "(file)".into(),
        line: None,
        value: format!("{bytes} bytes"),
        allowed: format!(
            "at most {MAX_SPEC_BYTES} bytes (4 MiB): ranges {{start, stop, step}} describe \
             large grids"
        ),
    }
}

/// Reads and validates a spec file. A file that cannot be read (missing, a directory, not
/// UTF-8) is a spec error too (exit code 2), naming the file and why.
pub fn load(path: &Path) -> Result<SweepSpec, crate::error::SweepError> {
    if let Ok(meta) = std::fs::metadata(path) {
        if meta.is_file() && meta.len() > MAX_SPEC_BYTES as u64 {
            return Err(too_large(&path.display().to_string(), meta.len()).into());
        }
    }
    let text = std::fs::read_to_string(path).map_err(|e| SpecError {
        file: path.display().to_string(),
        path: "(file)".into(),
        line: None,
        value: format!("cannot be read ({e})"),
        allowed: "a readable UTF-8 YAML file".into(),
    })?;
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("sweep")
        .to_string();
    Ok(parse(&text, &path.display().to_string(), &stem)?)
}

/// The spec stored in a sweep directory.
pub fn load_stored(dir: &Path) -> Result<SweepSpec, crate::error::SweepError> {
    let path = dir.join("spec.yaml");
    let text =
        std::fs::read_to_string(&path).map_err(|e| crate::error::SweepError::io(&path, e))?;
    Ok(parse(&text, &path.display().to_string(), "sweep")?)
}

/// A YAML error as a spec error: a duplicated key on the line of its second occurrence,
/// anything else as invalid YAML.
fn yaml_error(e: &serde_yaml::Error, file: &str, text: &str) -> SpecError {
    let line = e.location().map(|l| l.line());
    match duplicate_key(&e.to_string()) {
        Some(path) => {
            let key = path.rsplit('.').next().unwrap_or(&path).to_string();
            SpecError {
                file: file.to_string(),
                line: line.map(|l| context::second_key_line(text, l, &key).unwrap_or(l)),
                value: format!("a second `{key}`"),
                path,
                allowed: "each key once in its section".into(),
            }
        }
        None => SpecError {
            file: file.to_string(),
            path: "(document)".into(),
            line,
            value: "not valid YAML".into(),
            allowed: e.to_string(),
        },
    }
}

/// The spec's `name` (default: the file's stem), `output` (default: `out/<name>`) and `model`.
fn header(
    ctx: &Ctx,
    top: &serde_yaml::Mapping,
    stem: &str,
) -> Result<(String, PathBuf, ModelKind), SpecError> {
    let name = match top.get("name") {
        None => stem.to_string(),
        Some(v) => {
            let s = v.as_str().unwrap_or("");
            let ok = !s.is_empty()
                && s.len() <= MAX_NAME_CHARS
                && s.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_.-".contains(c));
            if !ok {
                let shown = if s.len() > MAX_NAME_CHARS {
                    format!("a name of {} characters", s.len())
                } else {
                    show(v)
                };
                return Err(ctx.err(
                    &["name"],
                    shown,
                    format!("a non-empty name of at most {MAX_NAME_CHARS} letters, digits, _ . -"),
                ));
            }
            s.to_string()
        }
    };
    let output = match top.get("output") {
        None => PathBuf::from("out").join(&name),
        Some(v) => match v.as_str() {
            Some(s) if !s.trim().is_empty() => PathBuf::from(s),
            _ => return Err(ctx.err(&["output"], show(v), "a directory path (string)")),
        },
    };
    let model = match top.get("model") {
        None => ModelKind::Pde,
        Some(v) => match v.as_str() {
            Some("pde") => ModelKind::Pde,
            Some("ode") => ModelKind::Ode,
            _ => return Err(ctx.err(&["model"], show(v), "pde or ode")),
        },
    };
    Ok((name, output, model))
}

/// Parses and validates a spec's text; `file` names it in errors, `stem` is the default name.
pub fn parse(text: &str, file: &str, stem: &str) -> Result<SweepSpec, SpecError> {
    if text.len() > MAX_SPEC_BYTES {
        return Err(too_large(file, text.len() as u64));
    }
    let ctx = Ctx { file, text };
    let doc: Value = serde_yaml::from_str(text).map_err(|e| yaml_error(&e, file, text))?;
    let top = ctx.mapping(
        &doc,
        &[],
        &[
            "name",
            "output",
            "model",
            "params",
            "grid",
            "initial_conditions",
            "solver",
            "refine",
            "classify",
        ],
    )?;

    let (name, output, model) = header(&ctx, top, stem)?;

    let grid = grid::parse(&ctx, top)?;
    grid::check_not_fixed(&ctx, top, &grid)?;
    let params = params::parse(&ctx, top)?;
    let initial_conditions = initial::parse(&ctx, top)?;
    initial::check_modes(&ctx, &initial_conditions, params.modes)?;
    let solver = solver::parse(&ctx, top, model)?;
    check_read(&ctx, top, &grid, params.modes, &solver)?;
    grid::check_points(&ctx, &grid, &params, &solver)?;
    let refine = refine::parse(&ctx, top, &grid, &solver)?;
    classify::parse(&ctx, top)?;
    Ok(SweepSpec {
        name,
        output,
        params,
        grid,
        initial_conditions,
        solver,
        refine,
        source: text.to_string(),
    })
}

/// Refuses a setting given in the `solver` section, or swept by a grid axis, that the spec's
/// runs do not read (`SolverSettings::first_unread`): it would be accepted and ignored.
fn check_read(
    ctx: &Ctx,
    top: &serde_yaml::Mapping,
    grid: &Grid,
    modes: usize,
    solver: &SolverSettings,
) -> Result<(), SpecError> {
    let refuse = |path: &[&str], value: String, why: &str| {
        ctx.err(
            path,
            value,
            format!("refused: these runs do not read it ({why})"),
        )
    };
    if let Some(m) = top.get("solver").and_then(|v| v.as_mapping()) {
        let given: Vec<&str> = solver::keys()
            .into_iter()
            .filter(|k| m.contains_key(*k))
            .collect();
        if let Some((key, why)) = solver.first_unread(modes, &given) {
            return Err(refuse(
                &["solver", key],
                m.get(key).map(show).unwrap_or_default(),
                why,
            ));
        }
    }
    // An axis of a setting the runs do not read gives the same run at each of its values.
    let swept = grid.plane().params().into_iter().filter(|p| !p.is_model());
    for key in swept.map(|p| p.name()) {
        if let Some(why) = solver.unread_reason(modes, key) {
            return Err(refuse(&["grid", key], "an axis".into(), why));
        }
    }
    Ok(())
}

/// The key path of a YAML parser's "[section: ]duplicate entry with key \"K\"" error.
fn duplicate_key(message: &str) -> Option<String> {
    let (before, rest) = message.split_once("duplicate entry with key ")?;
    let key = rest.split(" at line ").next()?.trim_matches('"');
    let section = before.trim_end().trim_end_matches(':');
    Some(if section.is_empty() {
        key.to_string()
    } else {
        format!("{section}.{key}")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_duplicated_key_is_named_on_its_second_line() {
        let text = "name: a\ngrid:\n  eta_t: [0.08]\n  kappa2: [0.11]\nsolver:\n  n: 32\n  dt: 0.05\n  t_max: 10\nname: b\n";
        let e = parse(text, "t.yaml", "t").unwrap_err();
        assert_eq!((e.path.as_str(), e.line), ("name", Some(9)), "{e}");
        let text = "name: a\ngrid:\n  eta_t: [0.08]\n  kappa2: [0.11]\n  eta_t: [0.09]\n";
        let e = parse(text, "t.yaml", "t").unwrap_err();
        assert_eq!((e.path.as_str(), e.line), ("grid.eta_t", Some(5)), "{e}");
        assert!(e.to_string().contains("each key once"), "{e}");
    }

    #[test]
    fn long_lists_and_names_are_refused_quickly_and_shown_short() {
        let list: Vec<String> = (0..150_000)
            .map(|i| format!("{:.7}", 0.1 + i as f64 * 1e-7))
            .collect();
        let text = format!("grid:\n  eta_t: [{}]\n  kappa2: [0.1]\n", list.join(", "));
        let started = std::time::Instant::now();
        let e = parse(&text, "t.yaml", "t").unwrap_err();
        assert!(started.elapsed().as_secs_f64() < 2.0);
        assert_eq!(e.path, "grid.eta_t");
        assert!(e.to_string().contains("at most 100000 values"), "{e}");
        assert!(e.to_string().len() < 400, "{e}");
        let name = "n".repeat(MAX_NAME_CHARS + 1);
        let e = parse(&format!("name: {name}\n{GOOD}"), "t.yaml", "t").unwrap_err();
        assert_eq!(e.path, "name");
        assert!(e.to_string().len() < 400, "{e}");
        let e = parse(&" ".repeat(MAX_SPEC_BYTES + 1), "t.yaml", "t").unwrap_err();
        assert_eq!(e.path, "(file)");
        // Duplicates are still found, in linear time.
        let e = parse(
            &GOOD.replace("[0.11, 0.12]", "[0.11, 0.12, 0.11]"),
            "t.yaml",
            "t",
        );
        assert!(e.unwrap_err().to_string().contains("distinct"));
    }

    const GOOD: &str = "name: t\ngrid:\n  eta_t: {start: 0.07, stop: 0.1, step: 0.01}\n  kappa2: [0.11, 0.12]\nsolver:\n  n: 64\n  dt: 0.02\n";

    #[test]
    fn parses_a_good_spec() {
        let s = parse(GOOD, "t.yaml", "t").unwrap();
        assert_eq!(s.grid.x.values, vec![0.07, 0.08, 0.09, 0.1]);
        assert_eq!(s.grid.y.as_ref().unwrap().values, vec![0.11, 0.12]);
        assert_eq!(s.initial_conditions.len(), 4);
        assert_eq!(s.solver.n, 64);
        assert_eq!(s.output, PathBuf::from("out/t"));
    }

    #[test]
    fn errors_name_the_key_and_line() {
        let bad = GOOD.replace("step: 0.01", "step: -0.01");
        let e = parse(&bad, "t.yaml", "t").unwrap_err();
        assert_eq!(e.path, "grid.eta_t.step");
        assert_eq!(e.line, Some(3));
        let bad = GOOD.replace("  n: 64", "  nn: 64");
        let e = parse(&bad, "t.yaml", "t").unwrap_err();
        assert_eq!(e.path, "solver.nn");
        assert_eq!(e.line, Some(6));
    }

    #[test]
    fn the_removed_classify_section_is_refused() {
        let with = |extra: &str| parse(&format!("{GOOD}{extra}"), "t.yaml", "t");
        assert!(with("").is_ok());
        let e = with("classify: {beside_unstable: exclude}\n").unwrap_err();
        assert_eq!(e.path, "classify");
        assert_eq!(e.line, Some(8));
        assert!(e.allowed.contains("removed"), "{}", e.allowed);
    }

    #[test]
    fn ode_model_has_its_own_defaults() {
        let s = parse(
            &format!("model: ode\n{GOOD}").replace("  n: 64\n  dt: 0.02\n", "  t_max: 100\n"),
            "t.yaml",
            "t",
        )
        .unwrap();
        assert_eq!(s.solver.model, ModelKind::Ode);
        assert_eq!(s.solver.dt, 0.05);
        // The ODE model has no grid: a grid size is refused, not ignored.
        let e = parse(&format!("model: ode\n{GOOD}"), "t.yaml", "t").unwrap_err();
        assert_eq!((e.path.as_str(), e.line), ("solver.n", Some(7)));
        assert!(e.allowed.contains("no grid"), "{}", e.allowed);
        let e = parse(&format!("model: fem\n{GOOD}"), "t.yaml", "t").unwrap_err();
        assert_eq!((e.path.as_str(), e.line), ("model", Some(1)));
    }
}
