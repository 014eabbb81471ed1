//! Sweep specs (YAML): strict parsing with the file, key path, line, bad value and what is
//! allowed in every error.
//!
//! ```yaml
//! name: smoke                 # [A-Za-z0-9_.-]+ ; default: the file's stem
//! output: out/smoke           # default: out/<name>
//! model: pde                  # pde (Sect. 3) or ode (reduced model, eqs. 58-59)
//! params: {eta2: 0.1, radius: 1, sigma: 0.03, box_len: 7, mass: 0.1}   # paper defaults
//! grid:
//!   eta_t: {start: 0.07, stop: 0.10, step: 0.01}    # inclusive range ...
//!   kappa2: [0.11, 0.12]                            # ... or an explicit list
//! initial_conditions: [i, ii, iii, iv]              # default: the paper's four
//! solver: {scheme: spectral, n: 192, dt: 0.02, tol: 1.0e-4, dt_max: 0.25, t_max: 2000,
//!          steady_tol: 1.0e-6, steady_window: 0.1}
//!                             # tol: adaptive stepping (0 = fixed step dt; spectral only)
//!                             # ode: dt default 0.05, and h0 (default 0.1436)
//! ```
use crate::error::SpecError;
use droplet_solver::{InitialCondition, ModelKind, ModelParams, SchemeKind, SolverSettings};
use serde::Serialize;
use serde_yaml::Value;
use std::path::{Path, PathBuf};

/// Most points one axis may have.
pub const MAX_AXIS_POINTS: usize = 100_000;

/// A validated sweep spec.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepSpec {
    pub name: String,
    pub output: PathBuf,
    /// Fixed parameters; `eta_t` and `kappa2` are overwritten per point.
    pub params: ModelParams,
    pub eta_t: Vec<f64>,
    pub kappa2: Vec<f64>,
    pub initial_conditions: Vec<InitialCondition>,
    pub solver: SolverSettings,
    /// The spec's text, stored in the output metadata.
    #[serde(skip)]
    pub source: String,
}

struct Ctx<'a> {
    file: &'a str,
    text: &'a str,
}

impl Ctx<'_> {
    fn err(
        &self,
        path: &[&str],
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> SpecError {
        SpecError {
            file: self.file.to_string(),
            path: path.join("."),
            line: locate(self.text, path),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    fn mapping<'v>(
        &self,
        v: &'v Value,
        path: &[&str],
        keys: &[&str],
    ) -> Result<&'v serde_yaml::Mapping, SpecError> {
        let map = v
            .as_mapping()
            .ok_or_else(|| self.err(path, show(v), "a mapping (key: value)"))?;
        for k in map.keys() {
            let name = k.as_str().unwrap_or("");
            if !keys.contains(&name) {
                let mut p = path.to_vec();
                p.push(name);
                return Err(self.err(
                    &p,
                    format!("unknown key `{}`", show(k)),
                    format!("one of: {}", keys.join(", ")),
                ));
            }
        }
        Ok(map)
    }

    fn number(
        &self,
        v: &Value,
        path: &[&str],
        ok: impl Fn(f64) -> bool,
        allowed: &str,
    ) -> Result<f64, SpecError> {
        match v.as_f64() {
            Some(x) if x.is_finite() && ok(x) => Ok(x),
            _ => Err(self.err(path, show(v), allowed)),
        }
    }
}

/// Renders a YAML value compactly for messages.
fn show(v: &Value) -> String {
    match v {
        Value::String(s) => format!("{s:?}"),
        Value::Null => "null (empty)".into(),
        other => serde_yaml::to_string(other)
            .map(|s| s.trim().replace('\n', " "))
            .unwrap_or_else(|_| "?".into()),
    }
}

/// 1-based line of the key at `path` in block-style YAML (the deepest key found).
pub fn locate(text: &str, path: &[&str]) -> Option<usize> {
    let mut depth = 0;
    let mut indent_at_depth: Vec<usize> = Vec::new();
    let mut best = None;
    for (no, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let indent = line.len() - trimmed.len();
        while let Some(&i) = indent_at_depth.last() {
            if indent <= i {
                indent_at_depth.pop();
                depth = indent_at_depth.len();
            } else {
                break;
            }
        }
        if depth < path.len() {
            let key = path[depth];
            let matches = trimmed
                .strip_prefix(key)
                .is_some_and(|rest| rest.trim_start().starts_with(':'));
            if matches {
                best = Some(no + 1);
                indent_at_depth.push(indent);
                depth += 1;
                if depth == path.len() {
                    return best;
                }
            }
        }
    }
    best
}

/// Reads and validates a spec file. A file that cannot be read (missing, a directory, not
/// UTF-8) is a spec error too (exit code 2), naming the file and why.
pub fn load(path: &Path) -> Result<SweepSpec, crate::SweepError> {
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
pub fn load_stored(dir: &Path) -> Result<SweepSpec, crate::SweepError> {
    let path = dir.join("spec.yaml");
    let text = std::fs::read_to_string(&path).map_err(|e| crate::SweepError::io(&path, e))?;
    Ok(parse(&text, &path.display().to_string(), "sweep")?)
}

/// The spec key of a field named in a [`droplet_solver::SolverError::InvalidParameter`].
fn key_of(name: &str) -> [&str; 2] {
    match name {
        "eta2" | "radius" | "sigma" | "box_len" | "mass" => ["params", name],
        "eta_t" | "kappa2" => ["grid", name],
        _ => ["solver", name],
    }
}

/// Parses and validates a spec's text; `file` names it in errors, `stem` is the default name.
pub fn parse(text: &str, file: &str, stem: &str) -> Result<SweepSpec, SpecError> {
    let ctx = Ctx { file, text };
    let doc: Value = serde_yaml::from_str(text).map_err(|e| SpecError {
        file: file.to_string(),
        path: "(document)".into(),
        line: e.location().map(|l| l.line()),
        value: "not valid YAML".into(),
        allowed: e.to_string(),
    })?;
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
        ],
    )?;

    let name = match top.get("name") {
        None => stem.to_string(),
        Some(v) => {
            let s = v.as_str().unwrap_or("");
            let ok = !s.is_empty()
                && s.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_.-".contains(c));
            if !ok {
                return Err(ctx.err(
                    &["name"],
                    show(v),
                    "a non-empty name of letters, digits, _ . -",
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

    let mut params = ModelParams::default();
    if let Some(v) = top.get("params") {
        let keys = ["eta2", "radius", "sigma", "box_len", "mass"];
        let m = ctx.mapping(v, &["params"], &keys)?;
        for key in keys {
            if let Some(x) = m.get(key) {
                let nonneg = key == "mass";
                let allowed = if nonneg {
                    "a finite number >= 0 (0 = overdamped)"
                } else {
                    "a finite number > 0"
                };
                let val = ctx.number(
                    x,
                    &["params", key],
                    |x| if nonneg { x >= 0.0 } else { x > 0.0 },
                    allowed,
                )?;
                match key {
                    "eta2" => params.eta2 = val,
                    "radius" => params.radius = val,
                    "sigma" => params.sigma = val,
                    "box_len" => params.box_len = val,
                    _ => params.mass = val,
                }
            }
        }
        if let Err(droplet_solver::SolverError::InvalidParameter {
            name,
            value,
            allowed,
        }) = params.validate()
        {
            return Err(ctx.err(
                &["params", name],
                droplet_solver::error::show_number(value),
                allowed,
            ));
        }
    }

    let grid_v = top
        .get("grid")
        .ok_or_else(|| ctx.err(&["grid"], "missing", "a mapping with eta_t and kappa2 axes"))?;
    let grid = ctx.mapping(grid_v, &["grid"], &["eta_t", "kappa2"])?;
    let axis = |key: &'static str,
                lower_ok: fn(f64) -> bool,
                lower: &str|
     -> Result<Vec<f64>, SpecError> {
        let v = grid.get(key).ok_or_else(|| {
            ctx.err(
                &["grid", key],
                "missing",
                "{start, stop, step} or a list of numbers",
            )
        })?;
        parse_axis(&ctx, v, key, lower_ok, lower)
    };
    let eta_t = axis("eta_t", |x| x > 0.0, "> 0")?;
    let kappa2 = axis("kappa2", |x| x >= 0.0, ">= 0")?;

    let initial_conditions = match top.get("initial_conditions") {
        None => droplet_solver::initial::PAPER_FOUR
            .iter()
            .map(|n| InitialCondition::parse(n).expect("named"))
            .collect(),
        Some(v) => {
            let seq = v.as_sequence().filter(|s| !s.is_empty()).ok_or_else(|| {
                ctx.err(
                    &["initial_conditions"],
                    show(v),
                    "a non-empty list of i, ii, iii, iv, i', ii', custom:vx,vy,a2,b2",
                )
            })?;
            let mut out: Vec<InitialCondition> = Vec::new();
            for item in seq {
                let s = item.as_str().ok_or_else(|| {
                    ctx.err(
                        &["initial_conditions"],
                        show(item),
                        "a name such as i or ii' (quote names with ')",
                    )
                })?;
                let ic = InitialCondition::parse(s).map_err(|e| {
                    ctx.err(
                        &["initial_conditions"],
                        show(item),
                        match e {
                            droplet_solver::SolverError::InvalidInitialCondition {
                                reason, ..
                            } => reason,
                            _ => "i, ii, iii, iv, i', ii' or custom:vx,vy,a2,b2 with s < 1".into(),
                        },
                    )
                })?;
                if out.iter().any(|o| o.name == ic.name) {
                    return Err(ctx.err(
                        &["initial_conditions"],
                        show(item),
                        "each initial condition once",
                    ));
                }
                out.push(ic);
            }
            out
        }
    };

    let mut solver = match model {
        ModelKind::Pde => SolverSettings::default(),
        ModelKind::Ode => SolverSettings::ode(),
    };
    if let Some(v) = top.get("solver") {
        let keys = [
            "scheme",
            "n",
            "dt",
            "tol",
            "dt_max",
            "t_max",
            "steady_tol",
            "steady_window",
            "h0",
        ];
        let m = ctx.mapping(v, &["solver"], &keys)?;
        if let Some(x) = m.get("scheme") {
            solver.scheme = x
                .as_str()
                .and_then(|s| s.parse::<SchemeKind>().ok())
                .ok_or_else(|| ctx.err(&["solver", "scheme"], show(x), "spectral or paper-fd"))?;
            if solver.scheme == SchemeKind::PaperFd {
                let fd = SolverSettings::paper_fd();
                (solver.n, solver.dt, solver.tol) = (fd.n, fd.dt, fd.tol);
            }
        }
        if let Some(x) = m.get("n") {
            solver.n = match x.as_u64() {
                Some(n) if (16..=4096).contains(&n) && n % 2 == 0 => n as usize,
                _ => {
                    return Err(ctx.err(
                        &["solver", "n"],
                        show(x),
                        "an even integer from 16 to 4096",
                    ))
                }
            };
        }
        let pos = |k: &'static str| -> Result<Option<f64>, SpecError> {
            m.get(k)
                .map(|x| ctx.number(x, &["solver", k], |x| x > 0.0, "a finite number > 0"))
                .transpose()
        };
        if let Some(x) = pos("dt")? {
            solver.dt = x;
        }
        if let Some(x) = m.get("tol") {
            solver.tol = ctx.number(
                x,
                &["solver", "tol"],
                |x| x >= 0.0,
                "a finite number >= 0 (0 = fixed step dt)",
            )?;
            if solver.tol > 0.0
                && (model != ModelKind::Pde || solver.scheme != SchemeKind::Spectral)
            {
                return Err(ctx.err(
                    &["solver", "tol"],
                    solver.tol,
                    "0: adaptive stepping needs model pde with scheme spectral",
                ));
            }
        }
        if let Some(x) = pos("dt_max")? {
            solver.dt_max = x;
        }
        if solver.adaptive() && solver.dt_max < solver.dt {
            return Err(ctx.err(
                &["solver", "dt_max"],
                solver.dt_max,
                format!("at least dt = {}", solver.dt),
            ));
        }
        if let Some(x) = pos("t_max")? {
            solver.t_max = x;
        }
        if let Some(x) = pos("steady_tol")? {
            solver.steady_tol = x;
        }
        if let Some(x) = pos("steady_window")? {
            solver.steady_window = x;
        }
        if let Some(x) = pos("h0")? {
            solver.h0 = x;
        }
        if solver.steady_window < solver.dt {
            return Err(ctx.err(
                &["solver", "steady_window"],
                solver.steady_window,
                format!("at least dt = {}", solver.dt),
            ));
        }
        if solver.t_max < solver.dt {
            return Err(ctx.err(
                &["solver", "t_max"],
                solver.t_max,
                format!("at least dt = {}", solver.dt),
            ));
        }
    }

    // The solver's own checks, last: step counts, the droplet resolved by the grid, the
    // explicit scheme's stability limit (one source of truth with `droplet simulate`).
    if let Err(droplet_solver::SolverError::InvalidParameter {
        name,
        value,
        allowed,
    }) = solver
        .validate()
        .and_then(|()| droplet_solver::limits::check_run(&params, &solver))
    {
        return Err(ctx.err(
            &key_of(name),
            droplet_solver::error::show_number(value),
            allowed,
        ));
    }

    Ok(SweepSpec {
        name,
        output,
        params,
        eta_t,
        kappa2,
        initial_conditions,
        solver,
        source: text.to_string(),
    })
}

fn parse_axis(
    ctx: &Ctx,
    v: &Value,
    key: &'static str,
    lower_ok: fn(f64) -> bool,
    lower: &str,
) -> Result<Vec<f64>, SpecError> {
    let path = ["grid", key];
    if let Some(seq) = v.as_sequence() {
        if seq.is_empty() {
            return Err(ctx.err(&path, "[]", "a non-empty list"));
        }
        let mut out = Vec::with_capacity(seq.len());
        for item in seq {
            let x = ctx.number(item, &path, lower_ok, &format!("finite numbers {lower}"))?;
            if out.contains(&x) {
                return Err(ctx.err(&path, x, "distinct values"));
            }
            out.push(x);
        }
        return Ok(out);
    }
    let m = ctx.mapping(v, &path, &["start", "stop", "step"])?;
    let get =
        |k: &'static str, ok: &dyn Fn(f64) -> bool, allowed: &str| -> Result<f64, SpecError> {
            let x = m.get(k).ok_or_else(|| {
                ctx.err(
                    &["grid", key, k],
                    "missing",
                    "start, stop and step are all required",
                )
            })?;
            ctx.number(x, &["grid", key, k], ok, allowed)
        };
    let start = get(
        "start",
        &|x| lower_ok(x),
        &format!("a finite number {lower}"),
    )?;
    let stop = get(
        "stop",
        &|x| x >= start,
        &format!("a finite number >= start ({start})"),
    )?;
    let step = get("step", &|x| x > 0.0, "a finite number > 0")?;
    let count = ((stop - start) / step + 1e-9).floor() + 1.0;
    if count > MAX_AXIS_POINTS as f64 {
        return Err(ctx.err(
            &["grid", key, "step"],
            step,
            format!("a step giving at most {MAX_AXIS_POINTS} points (this gives {count})"),
        ));
    }
    // Values on a decimal grid: start + i step, rounded to 12 digits so that 0.07 + 3 * 0.01
    // is 0.1 and equal points in two specs get equal run keys.
    Ok((0..count as usize)
        .map(|i| round12(start + i as f64 * step))
        .collect())
}

/// Rounds to 12 significant decimal places after the point.
pub fn round12(x: f64) -> f64 {
    (x * 1e12).round() / 1e12
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "name: t\ngrid:\n  eta_t: {start: 0.07, stop: 0.1, step: 0.01}\n  kappa2: [0.11, 0.12]\nsolver:\n  n: 64\n  dt: 0.02\n";

    #[test]
    fn parses_a_good_spec() {
        let s = parse(GOOD, "t.yaml", "t").unwrap();
        assert_eq!(s.eta_t, vec![0.07, 0.08, 0.09, 0.1]);
        assert_eq!(s.kappa2, vec![0.11, 0.12]);
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
    fn ode_model_has_its_own_defaults() {
        let s = parse(
            &format!("model: ode\n{GOOD}").replace("  dt: 0.02\n", ""),
            "t.yaml",
            "t",
        )
        .unwrap();
        assert_eq!(s.solver.model, ModelKind::Ode);
        assert_eq!(s.solver.dt, 0.05);
        let e = parse(&format!("model: fem\n{GOOD}"), "t.yaml", "t").unwrap_err();
        assert_eq!((e.path.as_str(), e.line), ("model", Some(1)));
    }
}
