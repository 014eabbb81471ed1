//! Two finished maps of the same plane compared (`droplet plot DIR --beside OTHER`): both
//! drawn side by side in `DIR/beside.png` / `.svg` with the full model's boundaries of both on
//! each (`DIR`'s solid black, `OTHER`'s dashed purple, on both panels), how much of the window each label
//! covers in each map, and the points both maps hold whose label changes.
use crate::error::SweepError;
use crate::map::tally::tally;
use crate::pictures::map_figure::{spacing, Curve, MapPoint};
use crate::pictures::slice_figure::{slice_maps, Panel};
use crate::pictures::sweep_pictures::{map_points, model_title, MapDrawing};
use crate::spec::SweepSpec;
use crate::tables::read;
use droplet_solver::contract::settings::ModelKind;
use plotters::style::RGBColor;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The stem of the picture written into the compared map's directory.
pub const STEM: &str = "beside";

/// The colours of the boundaries: the compared map's, the other map's.
const THIS: RGBColor = RGBColor(0, 0, 0);
const OTHER: RGBColor = RGBColor(160, 0, 160);

/// How much of the window a label covers in each map (in units of the plane's two
/// parameters: the sum of its points' cells, a refined map's tiles or an unrefined map's grid
/// cells cut at the window's edge).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LabelArea {
    pub label: String,
    pub other: f64,
    pub this: f64,
}

/// The points both maps hold (the same coordinates) whose label goes from `from` (the other
/// map) to `to` (this one).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LabelChange {
    pub from: String,
    pub to: String,
    pub points: usize,
}

/// What [`compare`] drew and counted.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Comparison {
    pub files: Vec<PathBuf>,
    /// Each map's model, as its pictures name it.
    pub this_model: String,
    pub other_model: String,
    /// Every label of either map, in the legend's order.
    pub areas: Vec<LabelArea>,
    /// The points both maps hold.
    pub common_points: usize,
    pub changes: Vec<LabelChange>,
}

/// One finished map: its spec, points as drawn and full-model boundaries.
struct Map {
    spec: SweepSpec,
    points: Vec<MapPoint>,
    boundaries: Vec<crate::tables::boundaries::NamedCurve>,
}

impl Map {
    /// The map whose tables are in `dir`: refused unless it has two axes and no third.
    fn load(dir: &Path) -> Result<Self, SweepError> {
        if !dir.join(read::POINTS).is_file() {
            return Err(SweepError::Invalid(format!(
                "{}: no finished map here (no {}): compare maps whose sweep has ended",
                dir.display(),
                read::POINTS
            )));
        }
        let spec = read::stored_spec(&dir.join(read::POINTS))?;
        let (grid, y) = (&spec.grid, spec.grid.y.as_ref());
        let Some(y) =
            y.filter(|y| y.values.len() > 1 && grid.z.is_none() && grid.x.values.len() > 1)
        else {
            return Err(SweepError::Invalid(format!(
                "{}: a map of two axes is needed to compare maps (this sweep is not one)",
                dir.display()
            )));
        };
        let names = (grid.x.param.name(), y.param.name());
        let boundaries = crate::tables::boundaries::read_in(
            &dir.join(crate::tables::boundaries::FILE),
            names,
            ModelKind::Pde,
        )?;
        let drawing = MapDrawing::from_tables(dir)?;
        let points: Vec<MapPoint> = map_points(&spec, &drawing)
            .into_iter()
            .map(|(_, p)| p)
            .collect();
        if points.is_empty() {
            return Err(SweepError::Invalid(format!(
                "{}: the map has no points to compare",
                dir.display()
            )));
        }
        Ok(Self {
            spec,
            points,
            boundaries,
        })
    }

    /// The plane's axis names.
    fn names(&self) -> (&'static str, &'static str) {
        let y = self.spec.grid.y.as_ref().expect("checked at load");
        (self.spec.grid.x.param.name(), y.param.name())
    }

    /// The area each label covers.
    fn areas(&self) -> BTreeMap<String, f64> {
        let mut xs: Vec<f64> = self.points.iter().map(|p| p.x).collect();
        let mut ys: Vec<f64> = self.points.iter().map(|p| p.y).collect();
        let (dx, dy) = (spacing(&mut xs), spacing(&mut ys));
        let (x0, x1, y0, y1) = (xs[0], xs[xs.len() - 1], ys[0], ys[ys.len() - 1]);
        let mut out = BTreeMap::new();
        for p in &self.points {
            let area = if p.tiles.is_empty() {
                let w = (p.x + dx / 2.0).min(x1) - (p.x - dx / 2.0).max(x0);
                let h = (p.y + dy / 2.0).min(y1) - (p.y - dy / 2.0).max(y0);
                w * h
            } else {
                p.tiles.iter().map(|r| (r[2] - r[0]) * (r[3] - r[1])).sum()
            };
            *out.entry(p.label.clone()).or_insert(0.0) += area;
        }
        out
    }

    /// Its boundaries as drawn on both panels: the compared map's solid in [`THIS`], the
    /// other's dashed in [`OTHER`], each set under one legend entry naming its panel and
    /// sweep (two maps of one model stay apart; the panels' titles name the models).
    fn curves(&self, this: bool) -> Vec<Curve> {
        let side = if this { "right" } else { "left" };
        let label = format!("{side}: {} boundaries", self.spec.name);
        self.boundaries
            .iter()
            .map(|c| Curve {
                label: label.clone(),
                points: c.points.clone(),
                dashed: !this,
                colour: Some(if this { THIS } else { OTHER }),
            })
            .collect()
    }
}

/// Draws the map in `dir` beside the one in `other` (`dir/beside.png`, `.svg`: `other` on
/// the left) and counts what changes from `other` to `dir`. Both must be finished maps
/// (their tables written) in the same plane.
pub fn compare(dir: &Path, other: &Path) -> Result<Comparison, SweepError> {
    let this = Map::load(dir)?;
    let that = Map::load(other)?;
    if this.names() != that.names() {
        return Err(SweepError::Invalid(format!(
            "{} maps ({}, {}) and {} maps ({}, {}): maps of different planes cannot be compared",
            dir.display(),
            this.names().0,
            this.names().1,
            other.display(),
            that.names().0,
            that.names().1
        )));
    }
    let (this_model, other_model) = (model_title(&this.spec), model_title(&that.spec));
    let curves: Vec<Curve> = this
        .curves(true)
        .into_iter()
        .chain(that.curves(false))
        .collect();
    let panels = [
        Panel {
            title: format!("{}: {other_model}", that.spec.name),
            pts: that.points.clone(),
            curves: curves.clone(),
        },
        Panel {
            title: format!("{}: {this_model}", this.spec.name),
            pts: this.points.clone(),
            curves,
        },
    ];
    let title = format!("{other_model} beside {this_model}");
    let files = slice_maps(dir, STEM, &title, this.names(), &panels)?;
    let (mine, theirs) = (this.areas(), that.areas());
    let labels = crate::pictures::legend::legend_order(mine.keys().chain(theirs.keys()).cloned());
    let areas = labels
        .into_iter()
        .map(|label| LabelArea {
            this: mine.get(&label).copied().unwrap_or(0.0),
            other: theirs.get(&label).copied().unwrap_or(0.0),
            label,
        })
        .collect();
    let key = |p: &MapPoint| (p.x.to_bits(), p.y.to_bits());
    let before: BTreeMap<_, &str> = that
        .points
        .iter()
        .map(|p| (key(p), p.label.as_str()))
        .collect();
    let common: Vec<(&str, &str)> = this
        .points
        .iter()
        .filter_map(|p| before.get(&key(p)).map(|&b| (b, p.label.as_str())))
        .collect();
    let changes = tally(
        common
            .iter()
            .filter(|(a, b)| a != b)
            .map(|(a, b)| format!("{a}\t{b}")),
    )
    .into_iter()
    .map(|(pair, points)| {
        let (from, to) = pair.split_once('\t').expect("joined above");
        LabelChange {
            from: from.to_string(),
            to: to.to_string(),
            points,
        }
    })
    .collect();
    Ok(Comparison {
        files,
        this_model,
        other_model,
        areas,
        common_points: common.len(),
        changes,
    })
}
