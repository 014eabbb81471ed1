//! The phase map (paper Fig. 2a): one tile per point in its label's colour, boundary curves
//! over it, the legend beside it; and the boundaries alone.
use crate::error::SweepError;
use crate::pictures::legend::{class_colour, draw_legend, legend_order, LegendKey};
use crate::pictures::render::perr;
use crate::pictures::render::{render, Figure};
use crate::spec::axes::{ETA_T, KAPPA2};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// One point of a phase map.
#[derive(Debug, Clone)]
pub struct MapPoint {
    /// Its coordinates in the map's plane.
    pub x: f64,
    pub y: f64,
    pub label: String,
    /// How many of its runs left the model (`diverged`): the label counts only the others,
    /// so the picture marks such a point with a cross (unless all of them did: `diverged`).
    pub left_model: usize,
    /// The rectangles `[x0, y0, x1, y1]` the point stands for on a
    /// refined map ([`crate::spec::lattice::Lattice::tiles`]); empty: a square of the grid spacing.
    pub tiles: Vec<[f64; 4]>,
}

/// A curve drawn over a phase map (e.g. an analytic boundary).
#[derive(Debug, Clone)]
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Drawn dashed (the reduced model's boundaries) or solid (the full model's).
    pub dashed: bool,
    /// Its colour; `None`: the next of [`CURVE_COLOURS`] (solid) or of the lighter ones
    /// (dashed).
    pub colour: Option<RGBColor>,
}

/// The colours of solid curves over a map, in order.
pub const CURVE_COLOURS: [RGBColor; 7] = [
    BLACK,
    RGBColor(90, 90, 90),
    RGBColor(160, 0, 160),
    RGBColor(0, 110, 110),
    RGBColor(200, 90, 0),
    RGBColor(0, 150, 60),
    RGBColor(255, 140, 0),
];

impl Curve {
    /// A boundary curve as drawn: labelled with its model, the reduced model's dashed.
    pub fn of(c: &crate::tables::boundaries::NamedCurve) -> Self {
        Self {
            label: format!("{}: {}", c.model.as_str().to_uppercase(), c.name),
            dashed: c.model == droplet_solver::contract::settings::ModelKind::Ode,
            points: c.points.clone(),
            colour: None,
        }
    }
}

pub(crate) fn spacing(v: &mut Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v.windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min)
}

/// The phase map: one square per point in its class colour, curves drawn over it, the legend
/// in a panel on the right.
struct PhaseMap<'a> {
    title: &'a str,
    /// The names of the axes `(x, y)`.
    names: (&'a str, &'a str),
    pts: &'a [MapPoint],
    curves: &'a [Curve],
}

/// Width of the legend panel beside a phase map.
pub(crate) const LEGEND_W: u32 = 340;

impl Figure for PhaseMap<'_> {
    fn size(&self) -> (u32, u32) {
        (900 + LEGEND_W, 760)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(perr)?;
        let (plot_area, legend_area) = root.split_horizontally(900);
        let (classes, curves) =
            draw_panel(&plot_area, self.title, self.names, self.pts, self.curves)?;
        let legend: Vec<(String, LegendKey)> = classes
            .into_iter()
            .map(|(class, count, key)| (format!("{class} ({count})"), key))
            .chain(curves)
            .collect();
        draw_legend(&legend_area, &legend)?;
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// The legend entries of one panel: each class with its count and colour, then each curve.
pub(crate) type PanelLegend = (Vec<(String, usize, LegendKey)>, Vec<(String, LegendKey)>);

/// Draws one phase map (tiles, curves) into `area`; returns its legend entries.
pub(crate) fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    names: (&str, &str),
    pts: &[MapPoint],
    curves: &[Curve],
) -> Result<PanelLegend, SweepError>
where
    DB::ErrorType: 'static,
{
    let mut xs: Vec<f64> = pts.iter().map(|p| p.x).collect();
    let mut ys: Vec<f64> = pts.iter().map(|p| p.y).collect();
    let dx = spacing(&mut xs);
    let dy = spacing(&mut ys);
    let dx = if dx.is_finite() { dx } else { 0.01 };
    let dy = if dy.is_finite() { dy } else { 0.01 };
    let (mut x0, mut x1) = (xs[0] - dx / 2.0, xs[xs.len() - 1] + dx / 2.0);
    let (mut y0, mut y1) = (ys[0] - dy / 2.0, ys[ys.len() - 1] + dy / 2.0);
    let tiled = pts.iter().any(|p| !p.tiles.is_empty());
    if tiled {
        // A refined map is drawn edge to edge: its extent is the tiles'.
        let rects = pts.iter().flat_map(|p| &p.tiles);
        (x0, y0, x1, y1) = rects.fold(
            (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, c, d), r| (a.min(r[0]), b.min(r[1]), c.max(r[2]), d.max(r[3])),
        );
    }
    let mut chart = plane_chart(area, title, names, (x0, x1), (y0, y1), false)?;
    let mut classes = Vec::new();
    for label in legend_order(pts.iter().map(|p| p.label.as_str())) {
        let mine: Vec<&MapPoint> = pts.iter().filter(|p| p.label == label).collect();
        if mine.is_empty() {
            continue;
        }
        let colour = class_colour(label);
        if tiled {
            chart
                .draw_series(
                    mine.iter()
                        .flat_map(|p| &p.tiles)
                        .map(|r| Rectangle::new([(r[0], r[1]), (r[2], r[3])], colour.filled())),
                )
                .map_err(perr)?;
        } else {
            chart
                .draw_series(mine.iter().map(|p| {
                    Rectangle::new(
                        [
                            (p.x - 0.42 * dx, p.y - 0.42 * dy),
                            (p.x + 0.42 * dx, p.y + 0.42 * dy),
                        ],
                        colour.filled(),
                    )
                }))
                .map_err(perr)?;
        }
        classes.push((label.to_string(), mine.len(), LegendKey::Box(colour)));
    }
    let size = marker_size(area, (x1 - x0, y1 - y0), (dx, dy));
    classes.extend(mark_left_model(&mut chart, pts, size)?);
    let mut drawn = Vec::new();
    draw_curves(&mut chart, curves, (x0, x1), (y0, y1), &mut drawn)?;
    Ok((classes, drawn))
}

/// The legend's name for the points marked with a cross (some of their runs `diverged`).
pub const LEFT_MODEL: &str = "runs left the model";

/// Crosses out the points some of whose runs left the model (a point all of whose runs did
/// says so in its label), `size` pixels wide; their legend entry, if any.
fn mark_left_model<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    pts: &[MapPoint],
    size: i32,
) -> Result<Option<(String, usize, LegendKey)>, SweepError>
where
    DB::ErrorType: 'static,
{
    let left: Vec<&MapPoint> = pts
        .iter()
        .filter(|p| p.left_model > 0 && p.label != crate::map::point_class::DIVERGED)
        .collect();
    if left.is_empty() {
        return Ok(None);
    }
    // Black on a white halo: seen on every class's colour.
    for style in [WHITE.stroke_width(3), BLACK.stroke_width(1)] {
        chart
            .draw_series(left.iter().map(|p| Cross::new((p.x, p.y), size, style)))
            .map_err(perr)?;
    }
    Ok(Some((LEFT_MODEL.to_string(), left.len(), LegendKey::Cross)))
}

/// A cross's half size in pixels: a third of the point's spacing on the chart, 2 to 6 pixels.
fn marker_size<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (width, height): (f64, f64),
    (dx, dy): (f64, f64),
) -> i32 {
    let (w, h) = area.dim_in_pixel();
    let px = (f64::from(w) * dx / width).min(f64::from(h) * dy / height);
    ((px / 3.0) as i32).clamp(2, 6)
}

/// A parameter plane over `x` and `y` with its axes drawn, named `names` (and a mesh if
/// `mesh`).
pub(crate) fn plane_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    names: (&str, &str),
    x: (f64, f64),
    y: (f64, f64),
    mesh: bool,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    SweepError,
>
where
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(perr)?;
    let mut m = chart.configure_mesh();
    if !mesh {
        m.disable_mesh();
    }
    let (x_tick, y_tick) = (tick_format(x), tick_format(y));
    m.x_desc(names.0)
        .y_desc(names.1)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 18))
        .x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .draw()
        .map_err(perr)?;
    Ok(chart)
}

/// Tick labels for an axis over `(lo, hi)`: three decimals on the paper's windows, fewer on
/// wide ones (none for a grid size), more on very narrow ones.
fn tick_format((lo, hi): (f64, f64)) -> impl Fn(&f64) -> String {
    let span = (hi - lo).abs();
    let decimals = match span {
        s if s >= 100.0 => 0,
        s if s >= 10.0 => 1,
        s if s >= 1.0 => 2,
        s if s >= 1e-3 => 3,
        _ => 5,
    };
    move |v: &f64| format!("{v:.decimals$}")
}

/// Draws `curves` (the part inside the window) on a phase-plane chart, adding each to the
/// legend: the full model's solid, the reduced model's dashed, each in its own colour.
pub(crate) fn draw_curves<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    curves: &[Curve],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    legend: &mut Vec<(String, LegendKey)>,
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    let styles = CURVE_COLOURS;
    // The reduced model's curves in lighter colours of their own.
    let light = [
        RGBColor(120, 120, 120),
        RGBColor(200, 120, 200),
        RGBColor(90, 170, 220),
        RGBColor(220, 170, 60),
    ];
    let (mut solid, mut dashed) = (0, 0);
    for c in curves {
        let next = if c.dashed {
            dashed += 1;
            light[(dashed - 1) % light.len()]
        } else {
            solid += 1;
            styles[(solid - 1) % styles.len()]
        };
        let colour = c.colour.unwrap_or(next);
        let style = colour.stroke_width(if c.dashed { 2 } else { 3 });
        let inside: Vec<(f64, f64)> = c
            .points
            .iter()
            .copied()
            .filter(|(x, y)| (x0..=x1).contains(x) && (y0..=y1).contains(y))
            .collect();
        if inside.len() < 2 {
            continue;
        }
        if c.dashed {
            chart
                .draw_series(DashedLineSeries::new(inside, 8, 6, style))
                .map_err(perr)?;
        } else {
            chart
                .draw_series(LineSeries::new(inside, style))
                .map_err(perr)?;
        }
        legend.push((c.label.clone(), LegendKey::Line(style)));
    }
    Ok(())
}

/// Phase boundaries alone in the `(eta_t, kappa2)` window (`droplet boundaries`).
struct BoundaryFigure<'a> {
    title: &'a str,
    /// The axes' names.
    names: (&'a str, &'a str),
    curves: &'a [Curve],
    eta_t: (f64, f64),
    kappa2: (f64, f64),
}

impl Figure for BoundaryFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (900 + LEGEND_W + 80, 760)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(perr)?;
        let (plot_area, legend_area) = root.split_horizontally(900);
        let (x, y) = (self.eta_t, self.kappa2);
        let mut chart = plane_chart(&plot_area, self.title, self.names, x, y, true)?;
        let mut legend = Vec::new();
        draw_curves(&mut chart, self.curves, x, y, &mut legend)?;
        draw_legend(&legend_area, &legend)?;
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// Renders `<stem>.png` and `.svg` in `dir`: `curves` in the window; returns both paths.
pub fn boundary_picture(
    dir: &Path,
    stem: &str,
    title: &str,
    curves: &[Curve],
    eta_t: (f64, f64),
    kappa2: (f64, f64),
) -> Result<Vec<PathBuf>, SweepError> {
    render(
        &dir.join(format!("{stem}.png")),
        &BoundaryFigure {
            title,
            names: (ETA_T, KAPPA2),
            curves,
            eta_t,
            kappa2,
        },
    )
}

/// Renders `<stem>.png` and `.svg` in `dir`: droplet outlines `curves` in the droplet's frame
/// `(x, y)` (centre at 0, radius about 1), at about equal scales; returns both paths.
pub fn outline_picture(
    dir: &Path,
    stem: &str,
    title: &str,
    curves: &[Curve],
) -> Result<Vec<PathBuf>, SweepError> {
    render(
        &dir.join(format!("{stem}.png")),
        &BoundaryFigure {
            title,
            names: ("x", "y"),
            curves,
            // The plot area is about 900 x 760 pixels.
            eta_t: (-1.78, 1.78),
            kappa2: (-1.5, 1.5),
        },
    )
}

/// Renders `<stem>.png` and `<stem>.svg` in `dir`; returns both paths.
pub fn phase_map(
    dir: &Path,
    stem: &str,
    title: &str,
    names: (&str, &str),
    pts: &[MapPoint],
    curves: &[Curve],
) -> Result<Vec<PathBuf>, SweepError> {
    if pts.is_empty() {
        return Err(SweepError::Invalid("no points to draw".into()));
    }
    render(
        &dir.join(format!("{stem}.png")),
        &PhaseMap {
            title,
            names,
            pts,
            curves,
        },
    )
}
