//! The `grid` section: one to three swept axes, each any [`Param`] (a model parameter or a
//! solver setting), as an inclusive `{start, stop, step}` range or an explicit list. Two
//! axes are a plane (a phase map); a third is a slice axis (one map per value).
//!
//! ```yaml
//! grid:
//!   mass: [0.01, 0.03, 0.1, 0.3, 1]                # a list ...
//!   eta_t: {start: 0.07, stop: 0.10, step: 0.005}  # ... or a range
//! ```
//!
//! The first axis is the picture's horizontal one; `eta_t` and `kappa2` together are always
//! in the paper's order `(eta_t, kappa2)`, however the file lists them. A swept parameter
//! may not also be fixed in `params` or `solver`.
use super::context::{show, Ctx};
use crate::error::SpecError;
use crate::spec::axes::{round12, Param, Plane, Point};
use droplet_solver::{contract::settings::SolverSettings, model::params::ModelParams};
use serde::Serialize;
use serde_yaml::{Mapping, Value};

/// Most points one axis may have.
pub const MAX_AXIS_POINTS: usize = 100_000;

/// Most axes a grid may have.
pub const MAX_AXES: usize = 3;

/// One swept parameter of the grid (an axis of the map): its values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Swept {
    pub param: Param,
    /// The values, in the spec's order (a range: increasing).
    pub values: Vec<f64>,
    /// The step of a `{start, stop, step}` range (`None`: a list), which refinement halves.
    pub step: Option<f64>,
}

impl Swept {
    /// Smallest and largest value.
    pub fn span(&self) -> (f64, f64) {
        self.values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            })
    }
}

/// The swept axes: `x`, in a 2- or 3-axis grid `y`, in a 3-axis grid `z` (the slices).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Grid {
    pub x: Swept,
    pub y: Option<Swept>,
    pub z: Option<Swept>,
}

impl Grid {
    /// The plane of the grid's points.
    pub fn plane(&self) -> Plane {
        Plane {
            x: self.x.param,
            y: self.y.as_ref().map(|a| a.param),
            z: self.z.as_ref().map(|a| a.param),
        }
    }

    /// The axes, in order.
    pub fn axes(&self) -> impl Iterator<Item = &Swept> {
        std::iter::once(&self.x)
            .chain(self.y.as_ref())
            .chain(self.z.as_ref())
    }

    /// The axis that sweeps `p`, if any.
    pub fn axis(&self, p: Param) -> Option<&Swept> {
        self.axes().find(|a| a.param == p)
    }

    /// The first point.
    pub fn first(&self) -> Point {
        let at = |a: &Option<Swept>| a.as_ref().map_or(0.0, |a| a.values[0]);
        [self.x.values[0], at(&self.y), at(&self.z)]
    }

    /// The values along `y` (one value 0 without that axis, see [`Plane`]).
    pub fn y_values(&self) -> Vec<f64> {
        self.y.as_ref().map_or(vec![0.0], |a| a.values.clone())
    }

    /// The values along `z` (one value 0 without that axis).
    pub fn z_values(&self) -> Vec<f64> {
        self.z.as_ref().map_or(vec![0.0], |a| a.values.clone())
    }

    /// Every point, z-major, then x, then y (a 2-axis grid: x-major, as always).
    pub fn points(&self) -> Vec<Point> {
        let (ys, zs) = (self.y_values(), self.z_values());
        zs.iter()
            .flat_map(|&z| {
                let ys = &ys;
                self.x
                    .values
                    .iter()
                    .flat_map(move |&x| ys.iter().map(move |&y| [x, y, z]))
            })
            .collect()
    }
}

/// The `grid` section.
pub(super) fn parse(ctx: &Ctx, top: &Mapping) -> Result<Grid, SpecError> {
    let grid_v = top.get("grid").ok_or_else(|| {
        ctx.err(
            &["grid"],
            "missing",
            format!(
                "a mapping of one to three axes, each one of: {}",
                Param::names()
            ),
        )
    })?;
    if let Some((key, v)) = grid_v.as_mapping().and_then(|m| {
        ModelParams::SHAPE_MODE_FIELDS
            .iter()
            .find_map(|key| m.get(*key).map(|v| (*key, v)))
    }) {
        // The shape modes set the state's length: one value per sweep.
        return Err(ctx.err(
            &["grid", key],
            show(v),
            format!(
                "not an axis: one value per sweep, params.{key} (one sweep per value; \
                 `droplet truncation` compares K = 2..K at a point)"
            ),
        ));
    }
    let names: Vec<&str> = Param::ALL.iter().map(|p| p.name()).collect();
    let grid = ctx.mapping(grid_v, &["grid"], &names)?;
    if grid.is_empty() || grid.len() > MAX_AXES {
        return Err(ctx.err(
            &["grid"],
            format!("{} axes", grid.len()),
            format!(
                "one to three axes (a line, a plane, or planes in slices of the third), each one of: {}",
                Param::names()
            ),
        ));
    }
    let mut axes = Vec::with_capacity(grid.len());
    for (k, v) in grid {
        let name = k.as_str().unwrap_or("");
        let param = Param::parse(name).expect("keys were checked against Param::ALL");
        let (values, step) = parse_axis(ctx, v, param)?;
        axes.push(Swept {
            param,
            values,
            step,
        });
    }
    if axes.len() >= 2 && axes[0].param == Param::KAPPA2 && axes[1].param == Param::ETA_T {
        axes.swap(0, 1);
    }
    let mut axes = axes.into_iter();
    Ok(Grid {
        x: axes.next().expect("one axis at least"),
        y: axes.next(),
        z: axes.next(),
    })
}

/// One axis: a list of distinct values or a `{start, stop, step}` range (and its step), every
/// value in the parameter's domain ([`Param::admits`]).
fn parse_axis(ctx: &Ctx, v: &Value, param: Param) -> Result<(Vec<f64>, Option<f64>), SpecError> {
    let key = param.name();
    let path = ["grid", key];
    let lower_ok = |x: f64| param.admits(x).0;
    let lower = param.admits(0.0).1;
    if let Some(seq) = v.as_sequence() {
        if seq.is_empty() {
            return Err(ctx.err(&path, "[]", "a non-empty list"));
        }
        if seq.len() > MAX_AXIS_POINTS {
            return Err(ctx.err(&path, show(v), format!("at most {MAX_AXIS_POINTS} values")));
        }
        let mut out = Vec::with_capacity(seq.len());
        // Seen values by their bits (every value is finite, and -0.0 is read as 0.0): one
        // look-up per value, so a long list is checked in linear time.
        let mut seen = std::collections::HashSet::with_capacity(seq.len());
        for item in seq {
            let x = ctx.number(item, &path, lower_ok, lower)? + 0.0;
            if !seen.insert(x.to_bits()) {
                return Err(ctx.err(&path, x, "distinct values"));
            }
            out.push(x);
        }
        return Ok((out, None));
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
    let start = get("start", &lower_ok, &format!("one of the {lower}"))?;
    let stop = get(
        "stop",
        &|x| x >= start && lower_ok(x),
        &format!("one of the {lower}, >= start ({start})"),
    )?;
    let step = get(
        "step",
        &|x| x > 0.0 && (param != Param::N || x.fract() == 0.0),
        if param == Param::N {
            "an integer > 0"
        } else {
            "a finite number > 0"
        },
    )?;
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
    let values = (0..count as usize)
        .map(|i| round12(start + i as f64 * step))
        .collect();
    Ok((values, Some(step)))
}

/// Refuses a swept parameter that the spec also fixes in `params` or `solver`.
pub(super) fn check_not_fixed(ctx: &Ctx, top: &Mapping, grid: &Grid) -> Result<(), SpecError> {
    for axis in grid.axes() {
        let section = if axis.param.is_model() {
            "params"
        } else {
            "solver"
        };
        let fixed = top
            .get(section)
            .and_then(Value::as_mapping)
            .is_some_and(|m| m.contains_key(axis.param.name()));
        if fixed {
            return Err(ctx.err(
                &["grid", axis.param.name()],
                format!("swept here and fixed in {section}.{}", axis.param),
                format!("a parameter either swept in grid or fixed in {section}, not both"),
            ));
        }
    }
    Ok(())
}

/// Checks the solver's own rules (`ModelParams::validate`, `SolverSettings::validate`,
/// `limits::check_run`) on the grid's points: every value of each axis with the other axes at
/// their smallest and largest values (each rule is monotone in each parameter, so these
/// points bound the grid). This is the one range check of the `params` and `solver`
/// sections too: a failure is reported at the axis that sweeps the named field, else at its key
/// in `params` or `solver`.
pub(super) fn check_points(
    ctx: &Ctx,
    grid: &Grid,
    params: &ModelParams,
    settings: &SolverSettings,
) -> Result<(), SpecError> {
    let plane = grid.plane();
    let axes: Vec<&Swept> = grid.axes().collect();
    let ends: Vec<[f64; 2]> = axes
        .iter()
        .map(|a| {
            let (lo, hi) = a.span();
            [lo, hi]
        })
        .collect();
    for (i, axis) in axes.iter().enumerate() {
        for &value in &axis.values {
            // Every combination of the other axes' ends.
            for corner in (0..(1usize << axes.len())).filter(|c| (c >> i) & 1 == 0) {
                let mut point = [0.0; 3];
                for (j, end) in ends.iter().enumerate() {
                    point[j] = if j == i {
                        value
                    } else {
                        end[(corner >> j) & 1]
                    };
                }
                let (mut p, mut s) = (*params, *settings);
                plane.apply(point, &mut p, &mut s);
                let check = p
                    .validate()
                    .and_then(|()| s.validate())
                    .and_then(|()| droplet_solver::contract::limits::check_run(&p, &s));
                ctx.checked_swept(check, &plane)?;
            }
        }
    }
    Ok(())
}
