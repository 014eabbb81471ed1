//! What every section parser of a spec needs: the file and text (for the line of a key),
//! typed accessors that fail with the key path, the value and what is allowed, and the spec
//! key of a solver error's field.
use crate::error::SpecError;
use crate::spec::axes::{Param, Plane};
use droplet_solver::error::show_number;
use droplet_solver::error::SolverError;
use serde_yaml::Value;

/// Where a spec came from, for error messages.
pub(super) struct Ctx<'a> {
    pub file: &'a str,
    pub text: &'a str,
}

impl Ctx<'_> {
    pub fn err(
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

    pub fn mapping<'v>(
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

    /// Reads each key of `fields` present in `m` (the mapping at `section`) as a finite
    /// number into its field of `target`; the ranges are the solver crate's to check
    /// ([`Self::checked`]).
    pub fn numbers<T>(
        &self,
        m: &serde_yaml::Mapping,
        section: &str,
        fields: &[NumberField<T>],
        target: &mut T,
    ) -> Result<(), SpecError> {
        for (key, field) in fields {
            if let Some(x) = m.get(*key) {
                *field(target) = self.number(x, &[section, key], |_| true, "a finite number")?;
            }
        }
        Ok(())
    }

    /// A solver-crate check, its failure reported at the spec key of the field it names.
    pub fn checked(&self, check: Result<(), SolverError>) -> Result<(), SpecError> {
        check.map_err(|e| match e {
            SolverError::InvalidParameter {
                name,
                value,
                allowed,
            } => self.err(&key_of(name), show_number(value), allowed),
            SolverError::InvalidChoice {
                name,
                value,
                allowed,
            } => self.err(&key_of(name), value, allowed),
            other => self.err(&["(spec)"], "", other.to_string()),
        })
    }

    /// As [`Self::checked`], on a point of the grid: a failure of a swept field is reported
    /// at its axis, `grid.<name>`.
    pub fn checked_swept(
        &self,
        check: Result<(), SolverError>,
        plane: &Plane,
    ) -> Result<(), SpecError> {
        let swept = |name: &str| plane.params().iter().any(|p| p.name() == name);
        match check {
            Err(SolverError::InvalidParameter {
                name,
                value,
                allowed,
            }) if swept(name) => Err(self.err(&["grid", name], show_number(value), allowed)),
            other => self.checked(other),
        }
    }

    pub fn number(
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

/// Longest rendering of a value in a message.
const MAX_SHOWN: usize = 200;

/// Renders a YAML value compactly for messages, cut to [`MAX_SHOWN`] characters (a long
/// list or name is not copied whole into an error).
pub(super) fn show(v: &Value) -> String {
    let text = match v {
        Value::String(s) if s.len() > MAX_SHOWN => format!("a string of {} characters", s.len()),
        Value::String(s) => format!("{s:?}"),
        Value::Null => "null (empty)".into(),
        Value::Sequence(seq) if seq.len() > 20 => format!("a list of {} values", seq.len()),
        // A short list of plain values as it would be written in flow style.
        Value::Sequence(seq) if seq.iter().all(|x| !x.is_sequence() && !x.is_mapping()) => {
            format!("[{}]", seq.iter().map(show).collect::<Vec<_>>().join(", "))
        }
        other => serde_yaml::to_string(other)
            .map(|s| s.trim().replace('\n', " "))
            .unwrap_or_else(|_| "?".into()),
    };
    if text.chars().count() > MAX_SHOWN {
        let cut: String = text.chars().take(MAX_SHOWN).collect();
        format!("{cut} ...")
    } else {
        text
    }
}

/// The lines of block-style YAML that hold content: `(0-based number, indentation, text
/// after the indentation)`, blank and comment lines left out.
fn content_lines(text: &str) -> impl Iterator<Item = (usize, usize, &str)> + Clone {
    text.lines().enumerate().filter_map(|(no, line)| {
        let trimmed = line.trim_start();
        let content = !trimmed.is_empty() && !trimmed.starts_with('#');
        content.then(|| (no, line.len() - trimmed.len(), trimmed))
    })
}

/// Whether `trimmed` (a line after its indentation) starts with the key `key:`.
fn is_key(trimmed: &str, key: &str) -> bool {
    trimmed
        .strip_prefix(key)
        .is_some_and(|rest| rest.trim_start().starts_with(':'))
}

/// 1-based line of the key at `path` in block-style YAML (the deepest key found).
pub fn locate(text: &str, path: &[&str]) -> Option<usize> {
    let mut depth = 0;
    let mut indent_at_depth: Vec<usize> = Vec::new();
    let mut best = None;
    for (no, indent, trimmed) in content_lines(text) {
        while let Some(&i) = indent_at_depth.last() {
            if indent <= i {
                indent_at_depth.pop();
                depth = indent_at_depth.len();
            } else {
                break;
            }
        }
        if depth < path.len() && is_key(trimmed, path[depth]) {
            best = Some(no + 1);
            indent_at_depth.push(indent);
            depth += 1;
            if depth == path.len() {
                return best;
            }
        }
    }
    best
}

/// The line of the second `key:` of the block mapping whose first key is on line `start`
/// (1-based; a parser reports a duplicate at the mapping's start): the lines at that
/// mapping's indentation are its keys, and a shallower line ends it.
pub fn second_key_line(text: &str, start: usize, key: &str) -> Option<usize> {
    let lines = content_lines(text).skip_while(|&(no, _, _)| no + 1 < start);
    let (_, indent, _) = lines.clone().next()?;
    lines
        .take_while(|&(_, here, _)| here >= indent)
        .filter(|&(_, here, trimmed)| here == indent && is_key(trimmed, key))
        .nth(1)
        .map(|(no, _, _)| no + 1)
}

/// The spec key of a field named in a [`droplet_solver::error::SolverError::InvalidParameter`]:
/// `params.<name>` for a model parameter, `solver.<name>` for a setting.
/// A numeric key of a section and the field of its own name that it sets.
pub(super) type NumberField<T> = (&'static str, fn(&mut T) -> &mut f64);

fn key_of(name: &str) -> [&str; 2] {
    match Param::parse(name) {
        Some(p) if p.is_model() => ["params", name],
        _ if droplet_solver::model::params::ModelParams::SHAPE_MODE_FIELDS.contains(&name) => {
            ["params", name]
        }
        _ => ["solver", name],
    }
}
