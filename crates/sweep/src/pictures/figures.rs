//! Pictures: the phase map (paper Fig. 2a), the single-run panels (Fig. 1), `v` and `s`
//! against a parameter (Fig. 2b, 3b) and the Appendix E fit, each a [`Figure`] drawn as PNG
//! and SVG by [`render`].
use crate::error::SweepError;
use crate::map::point_class::{DIVERGED, MISSING, NOT_CLASSIFIED, UNSETTLED};
use crate::pictures::branch_lines::BranchLine;
pub(crate) use crate::pictures::render::perr;
use crate::pictures::render::{render, Figure};
use crate::spec::axes::{ETA_T, KAPPA2};
use droplet_solver::stepping::Field;
use droplet_solver::{
    contract::outcome::SeriesRow, model::params::ModelParams, model::state::DropletState,
};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use std::path::{Path, PathBuf};

/// The paper's colour for a point label (Fig. 2a), and colours for the labels it does not use.
pub fn class_colour(label: &str) -> RGBColor {
    match label {
        "IC" => RGBColor(220, 30, 30),
        "ID" => RGBColor(20, 150, 40),
        "MD" => RGBColor(0, 0, 139),
        "IC/MD" => RGBColor(0, 200, 220),
        "ID/MD" => RGBColor(235, 205, 0),
        "IC/MC" => RGBColor(150, 150, 150),
        NOT_CLASSIFIED => RGBColor(140, 80, 20),
        "MC" => RGBColor(255, 140, 0),
        "IC/ID" => RGBColor(240, 120, 200),
        "MD/MC" => RGBColor(130, 60, 180),
        "ID/MC" => RGBColor(120, 130, 40),
        DIVERGED => RGBColor(0, 0, 0),
        UNSETTLED => RGBColor(200, 200, 200),
        "MD minor-axis" => RGBColor(0, 0, 139),
        "MD major-axis" => RGBColor(140, 80, 20),
        _ => RGBColor(255, 255, 255),
    }
}

/// Legend order: the paper's classes first.
const ORDER: [&str; 14] = [
    "IC",
    "ID",
    "MD",
    "IC/MD",
    "ID/MD",
    "IC/MC",
    NOT_CLASSIFIED,
    "MC",
    "IC/ID",
    "MD/MC",
    "ID/MC",
    DIVERGED,
    UNSETTLED,
    MISSING,
];

/// One point of a phase map.
#[derive(Debug, Clone)]
pub struct MapPoint {
    pub eta_t: f64,
    pub kappa2: f64,
    pub label: String,
    /// The rectangles `[eta_t0, kappa2_0, eta_t1, kappa2_1]` the point stands for on a
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
}

impl Curve {
    /// A boundary curve as drawn: labelled with its model, the reduced model's dashed.
    pub fn of(c: &crate::tables::boundaries::NamedCurve) -> Self {
        Self {
            label: format!("{}: {}", c.model.as_str().to_uppercase(), c.name),
            dashed: c.model == droplet_solver::contract::settings::ModelKind::Ode,
            points: c.points.clone(),
        }
    }
}

fn spacing(v: &mut Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v.windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min)
}

/// One entry of a legend drawn beside a chart.
enum LegendKey {
    Box(RGBColor),
    Line(ShapeStyle),
}

/// Draws `entries` top-down in `area` (a panel beside the chart, so the legend never covers
/// data).
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, LegendKey)],
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    let font = ("sans-serif", 14).into_font();
    for (i, (label, key)) in entries.iter().enumerate() {
        let y = 60 + 24 * i as i32;
        match key {
            LegendKey::Box(c) => area
                .draw(&Rectangle::new([(6, y - 7), (20, y + 7)], c.filled()))
                .map_err(perr)?,
            LegendKey::Line(style) => area
                .draw(&PathElement::new(vec![(4, y), (22, y)], *style))
                .map_err(perr)?,
        }
        area.draw(&Text::new(
            label.clone(),
            (28, y - 8),
            font.clone().color(&BLACK),
        ))
        .map_err(perr)?;
    }
    Ok(())
}

/// The phase map: one square per point in its class colour, curves drawn over it, the legend
/// in a panel on the right.
struct PhaseMap<'a> {
    title: &'a str,
    pts: &'a [MapPoint],
    curves: &'a [Curve],
}

/// Width of the legend panel beside a phase map.
const LEGEND_W: u32 = 340;

impl Figure for PhaseMap<'_> {
    fn size(&self) -> (u32, u32) {
        (900 + LEGEND_W, 760)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let (pts, curves) = (self.pts, self.curves);
        root.fill(&WHITE).map_err(perr)?;
        let (plot_area, legend_area) = root.split_horizontally(900);
        let mut xs: Vec<f64> = pts.iter().map(|p| p.eta_t).collect();
        let mut ys: Vec<f64> = pts.iter().map(|p| p.kappa2).collect();
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
        let mut chart = plane_chart(&plot_area, self.title, (x0, x1), (y0, y1), false)?;
        let mut legend = Vec::new();
        for label in ORDER.iter().copied().chain(
            pts.iter()
                .map(|p| p.label.as_str())
                .filter(|l| !ORDER.contains(l))
                .collect::<std::collections::BTreeSet<_>>(),
        ) {
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
                                (p.eta_t - 0.42 * dx, p.kappa2 - 0.42 * dy),
                                (p.eta_t + 0.42 * dx, p.kappa2 + 0.42 * dy),
                            ],
                            colour.filled(),
                        )
                    }))
                    .map_err(perr)?;
            }
            legend.push((format!("{label} ({})", mine.len()), LegendKey::Box(colour)));
        }
        draw_curves(&mut chart, curves, (x0, x1), (y0, y1), &mut legend)?;
        draw_legend(&legend_area, &legend)?;
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// The `(eta_t, kappa2)` plane over `x` and `y` with its axes drawn (and a mesh if `mesh`).
fn plane_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
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
    m.x_desc(ETA_T)
        .y_desc(KAPPA2)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 18))
        .x_label_formatter(&|v| format!("{v:.3}"))
        .y_label_formatter(&|v| format!("{v:.3}"))
        .draw()
        .map_err(perr)?;
    Ok(chart)
}

/// Draws `curves` (the part inside the window) on a phase-plane chart, adding each to the
/// legend: the full model's solid, the reduced model's dashed, each in its own colour.
fn draw_curves<DB: DrawingBackend>(
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
    let styles = [
        BLACK,
        RGBColor(90, 90, 90),
        RGBColor(160, 0, 160),
        RGBColor(0, 110, 110),
        RGBColor(200, 90, 0),
        RGBColor(0, 150, 60),
        RGBColor(255, 140, 0),
    ];
    // The reduced model's curves in lighter colours of their own.
    let light = [
        RGBColor(120, 120, 120),
        RGBColor(200, 120, 200),
        RGBColor(90, 170, 220),
        RGBColor(220, 170, 60),
    ];
    let (mut solid, mut dashed) = (0, 0);
    for c in curves {
        let colour = if c.dashed {
            dashed += 1;
            light[(dashed - 1) % light.len()]
        } else {
            solid += 1;
            styles[(solid - 1) % styles.len()]
        };
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
        let mut chart = plane_chart(&plot_area, self.title, x, y, true)?;
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
            curves,
            eta_t,
            kappa2,
        },
    )
}

/// Renders `<stem>.png` and `<stem>.svg` in `dir`; returns both paths.
pub fn phase_map(
    dir: &Path,
    stem: &str,
    title: &str,
    pts: &[MapPoint],
    curves: &[Curve],
) -> Result<Vec<PathBuf>, SweepError> {
    if pts.is_empty() {
        return Err(SweepError::Invalid("no points to draw".into()));
    }
    render(
        &dir.join(format!("{stem}.png")),
        &PhaseMap { title, pts, curves },
    )
}

/// The field `u` at `(x, y)` (lab coordinates, sample `(ix, iy)` at `((ix - N/2) dx, ...)`),
/// bilinear between the four nearest samples of the periodic grid.
fn sample_bilinear(field: &Field, x: f64, y: f64) -> f64 {
    let n = field.n;
    let dx = field.len / n as f64;
    let fx = x / dx + (n / 2) as f64;
    let fy = y / dx + (n / 2) as f64;
    let (ix, iy) = (fx.floor(), fy.floor());
    let (tx, ty) = (fx - ix, fy - iy);
    let at = |i: f64, j: f64| {
        let i = (i as i64).rem_euclid(n as i64) as usize;
        let j = (j as i64).rem_euclid(n as i64) as usize;
        field.values[j * n + i]
    };
    (1.0 - ty) * ((1.0 - tx) * at(ix, iy) + tx * at(ix + 1.0, iy))
        + ty * ((1.0 - tx) * at(ix, iy + 1.0) + tx * at(ix + 1.0, iy + 1.0))
}

/// The Fig. 1 panels of one run.
struct RunFigure<'a> {
    title: &'a str,
    params: &'a ModelParams,
    field: &'a Field,
    state: &'a DropletState,
    series: &'a [SeriesRow],
}

impl RunFigure<'_> {
    /// The field panel: `u` interpolated to the panel's pixels (viridis), with a colour bar.
    fn draw_field<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
    ) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let (field, state, params) = (self.field, self.state, self.params);
        let (map_area, bar_area) = area.split_horizontally(560);
        let half = field.len / 2.0;
        let mut chart = ChartBuilder::on(&map_area)
            .margin(10)
            .x_label_area_size(36)
            .y_label_area_size(44)
            .caption("concentration u", ("sans-serif", 16))
            .build_cartesian_2d(-half..half, -half..half)
            .map_err(perr)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x")
            .y_desc("y")
            .label_style(("sans-serif", 13))
            .draw()
            .map_err(perr)?;
        let (lo, hi) = field
            .values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let hi = if hi > lo { hi } else { lo + 1e-12 };
        let colour = |v: f64| ViridisRGB::get_color_normalized(v, lo, hi);
        // One bitmap at the panel's pixel resolution (embedded as PNG in the SVG).
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let (w, h) = ((xr.end - xr.start) as u32, (yr.end - yr.start) as u32);
        let mut rgb = Vec::with_capacity(w as usize * h as usize * 3);
        for py in 0..h {
            let y = half - field.len * (py as f64 + 0.5) / h as f64;
            for px in 0..w {
                let x = -half + field.len * (px as f64 + 0.5) / w as f64;
                let c = colour(sample_bilinear(field, x, y));
                rgb.extend_from_slice(&[c.0, c.1, c.2]);
            }
        }
        let image = BitMapElement::with_owned_buffer((-half, half), (w, h), rgb)
            .ok_or_else(|| SweepError::Plot("field bitmap of the wrong size".into()))?;
        chart.draw_series(std::iter::once(image)).map_err(perr)?;
        // Outline r = R (1 + a2 cos 2t + b2 sin 2t) around the centre wrapped into the box.
        let wrap = |c: f64| c - field.len * (c / field.len).round();
        let (xc, yc) = (wrap(state.x), wrap(state.y));
        let outline: Vec<(f64, f64)> = (0..=180)
            .map(|i| {
                let t = i as f64 / 180.0 * std::f64::consts::TAU;
                let r =
                    params.radius * (1.0 + state.a2 * (2.0 * t).cos() + state.b2 * (2.0 * t).sin());
                (xc + r * t.cos(), yc + r * t.sin())
            })
            .collect();
        chart
            .draw_series(LineSeries::new(
                outline,
                RGBColor(255, 140, 0).stroke_width(2),
            ))
            .map_err(perr)?;
        let v = state.speed();
        if v > 1e-3 {
            let (ux, uy) = (state.vx / v, state.vy / v);
            let tip = (xc + 1.8 * ux, yc + 1.8 * uy);
            let head = |sgn: f64| {
                (
                    tip.0 - 0.35 * ux + sgn * 0.2 * uy,
                    tip.1 - 0.35 * uy - sgn * 0.2 * ux,
                )
            };
            let orange = RGBColor(255, 140, 0).stroke_width(3);
            chart
                .draw_series([
                    PathElement::new(vec![(xc, yc), tip], orange),
                    PathElement::new(vec![head(1.0), tip, head(-1.0)], orange),
                ])
                .map_err(perr)?;
        }
        // Colour bar: the same map over [lo, hi], labelled in u.
        let mut bar = ChartBuilder::on(&bar_area)
            .margin_top(40)
            .margin_bottom(46)
            .margin_right(8)
            .y_label_area_size(62)
            .build_cartesian_2d(0.0..1.0, lo..hi)
            .map_err(perr)?;
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_label_style(("sans-serif", 12))
            .y_label_formatter(&|v| format!("{v:.3}"))
            .draw()
            .map_err(perr)?;
        let steps = 200;
        bar.draw_series((0..steps).map(|i| {
            let (a, b) = (
                lo + (hi - lo) * i as f64 / steps as f64,
                lo + (hi - lo) * (i + 1) as f64 / steps as f64,
            );
            Rectangle::new([(0.0, a), (1.0, b)], colour(0.5 * (a + b)).filled())
        }))
        .map_err(perr)?;
        Ok(())
    }
}

impl Figure for RunFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1180, 560)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let series = self.series;
        root.fill(&WHITE).map_err(perr)?;
        let root = root.titled(self.title, ("sans-serif", 20)).map_err(perr)?;
        let (left, right) = root.split_horizontally(640);
        self.draw_field(&left)?;
        let t_end = series.last().map(|r| r.t).unwrap_or(1.0).max(1e-9);
        let ymax = series
            .iter()
            .map(|r| r.v.max(r.s))
            .fold(0.0, f64::max)
            .max(1e-3)
            * 1.1;
        let mut ts = ChartBuilder::on(&right)
            .margin(10)
            .x_label_area_size(36)
            .y_label_area_size(50)
            .caption("speed v (red), deformation s (blue)", ("sans-serif", 16))
            .build_cartesian_2d(0.0..t_end, 0.0..ymax)
            .map_err(perr)?;
        ts.configure_mesh()
            .x_desc("t")
            .label_style(("sans-serif", 13))
            .draw()
            .map_err(perr)?;
        ts.draw_series(LineSeries::new(
            series.iter().map(|r| (r.t, r.v)),
            RED.stroke_width(2),
        ))
        .map_err(perr)?;
        ts.draw_series(LineSeries::new(
            series.iter().map(|r| (r.t, r.s)),
            BLUE.stroke_width(2),
        ))
        .map_err(perr)?;
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// The Fig. 1 panels of one run: final field (interpolated, with a colour bar), outline and
/// velocity arrow, and `v(t)`, `s(t)`. Writes `path` (PNG) and the same name with `.svg`.
pub fn run_picture(
    path: &Path,
    title: &str,
    params: &ModelParams,
    field: &Field,
    state: &DropletState,
    series: &[SeriesRow],
) -> Result<Vec<PathBuf>, SweepError> {
    render(
        path,
        &RunFigure {
            title,
            params,
            field,
            state,
            series,
        },
    )
}

/// One marker of a `v`, `s` against parameter picture.
#[derive(Debug, Clone)]
pub struct Marker {
    pub x: f64,
    pub v: f64,
    pub s: f64,
    /// Colour key (a class or branch name, see [`class_colour`]).
    pub key: String,
    /// Thick (stable / steady) or thin (unstable / not converged).
    pub bold: bool,
}

/// `v` and `s` against a parameter: lines (solid stable, dashed unstable), markers, labelled
/// vertical lines.
struct VsFigure<'a> {
    title: &'a str,
    x_label: &'a str,
    markers: &'a [Marker],
    lines: &'a [BranchLine],
    vlines: &'a [(f64, String)],
}

impl Figure for VsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 520)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let (markers, lines) = (self.markers, self.lines);
        root.fill(&WHITE).map_err(perr)?;
        let root = root.titled(self.title, ("sans-serif", 20)).map_err(perr)?;
        let xs = markers
            .iter()
            .map(|m| m.x)
            .chain(lines.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
        let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        let pad = ((x1 - x0) * 0.03).max(1e-6);
        let panels = root.split_evenly((1, 2));
        for (i, panel) in panels.iter().enumerate() {
            let val = |m: &Marker| if i == 0 { m.v } else { m.s };
            let lval = |p: &(f64, f64, f64)| if i == 0 { p.1 } else { p.2 };
            let ymax = markers
                .iter()
                .map(val)
                .chain(lines.iter().flat_map(|l| l.points.iter().map(lval)))
                .fold(0.0, f64::max)
                .max(1e-3)
                * 1.08;
            let mut chart = ChartBuilder::on(panel)
                .margin(12)
                .x_label_area_size(42)
                .y_label_area_size(52)
                .build_cartesian_2d(x0 - pad..x1 + pad, 0.0..ymax)
                .map_err(perr)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc(self.x_label)
                .y_desc(if i == 0 { "speed v" } else { "deformation s" })
                .label_style(("sans-serif", 14))
                .axis_desc_style(("sans-serif", 16))
                .x_label_formatter(&|v| format!("{v:.3}"))
                .draw()
                .map_err(perr)?;
            for (x, label) in self.vlines {
                chart
                    .draw_series(LineSeries::new(
                        vec![(*x, 0.0), (*x, ymax)],
                        BLACK.mix(0.4).stroke_width(1),
                    ))
                    .map_err(perr)?;
                chart
                    .draw_series([Text::new(
                        label.clone(),
                        (*x, ymax * 0.97),
                        ("sans-serif", 13),
                    )])
                    .map_err(perr)?;
            }
            let mut keys: Vec<&str> = markers
                .iter()
                .map(|m| m.key.as_str())
                .chain(lines.iter().map(|l| l.key.as_str()))
                .collect();
            keys.sort();
            keys.dedup();
            for key in keys {
                let colour = class_colour(key);
                let mut legend_done = false;
                for l in lines.iter().filter(|l| l.key == key) {
                    let pts = l.points.iter().map(|p| (p.0, lval(p)));
                    let anno = if l.stable {
                        chart
                            .draw_series(LineSeries::new(pts, colour.stroke_width(3)))
                            .map_err(perr)?
                    } else {
                        chart
                            .draw_series(DashedLineSeries::new(pts, 7, 5, colour.stroke_width(2)))
                            .map_err(perr)?
                    };
                    if !legend_done {
                        legend_done = true;
                        anno.label(key.to_string()).legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 14, y)], colour.stroke_width(3))
                        });
                    }
                }
                let mine = markers.iter().filter(|m| m.key == key);
                let anno = chart
                    .draw_series(mine.map(|m| {
                        let style = if m.bold {
                            colour.filled()
                        } else {
                            colour.stroke_width(1)
                        };
                        Circle::new((m.x, val(m)), if m.bold { 3 } else { 2 }, style)
                    }))
                    .map_err(perr)?;
                if !legend_done {
                    anno.label(key.to_string())
                        .legend(move |(x, y)| Circle::new((x + 6, y), 4, colour.filled()));
                }
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 13))
                .draw()
                .map_err(perr)?;
        }
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// `v` and `s` against a parameter (Fig. 2b / Fig. 3b style): `<stem>.png` and `.svg` in `dir`.
/// `lines` are branches (solid: stable, dashed: unstable); bold filled markers are stable or
/// steady states, thin rings unstable or unconverged ones; `vlines` mark bifurcation points.
pub fn vs_parameter(
    dir: &Path,
    stem: &str,
    title: &str,
    x_label: &str,
    markers: &[Marker],
    lines: &[BranchLine],
    vlines: &[(f64, String)],
) -> Result<Vec<PathBuf>, SweepError> {
    if markers.is_empty() && lines.is_empty() {
        return Err(SweepError::Invalid("nothing to draw".into()));
    }
    render(
        &dir.join(format!("{stem}.png")),
        &VsFigure {
            title,
            x_label,
            markers,
            lines,
            vlines,
        },
    )
}

impl Figure for H0Picture {
    fn size(&self) -> (u32, u32) {
        (900, 640)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let fit = self;
        root.fill(&WHITE).map_err(perr)?;
        let (k0, k1) = fit
            .points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.0), b.max(p.0))
            });
        let smax = fit.points.iter().map(|p| p.1).fold(0.0, f64::max) * 1.1;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "Appendix E fit: p0 = {:.4}, p2 = h0 = {:.4} (N = {})",
                    fit.p0, fit.p2, fit.n
                ),
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(56)
            .build_cartesian_2d(k0 - 0.001..k1 + 0.001, 0.0..smax)
            .map_err(perr)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(KAPPA2)
            .y_desc("s")
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .x_label_formatter(&|v| format!("{v:.3}"))
            .draw()
            .map_err(perr)?;
        let curve = |p0: f64| -> Vec<(f64, f64)> {
            (0..=300)
                .map(|i| k0 - 0.001 + (k1 - k0 + 0.002) * i as f64 / 300.0)
                .filter(|k| *k < p0)
                .map(|k| (k, ((p0 - k) / fit.p2).sqrt()))
                .filter(|(_, s)| *s <= smax)
                .collect()
        };
        chart
            .draw_series(LineSeries::new(curve(fit.p0), BLUE.stroke_width(2)))
            .map_err(perr)?
            .label("fit kappa2 = p0 - p2 s^2")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 14, y)], BLUE.stroke_width(2)));
        let green = RGBColor(20, 150, 40);
        chart
            .draw_series(
                curve(fit.g0t)
                    .chunks(2)
                    .filter(|c| c.len() == 2)
                    .enumerate()
                    .filter(|(i, _)| i % 2 == 0)
                    .map(|(_, c)| PathElement::new(c.to_vec(), green.stroke_width(2))),
            )
            .map_err(perr)?
            .label("kappa2 = g0~ - p2 s^2 (theory)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 14, y)], green.stroke_width(2))
            });
        chart
            .draw_series(
                fit.points
                    .iter()
                    .map(|&(k, s)| Circle::new((k, s), 4, RED.filled())),
            )
            .map_err(perr)?
            .label("deformation-only PDE steady states")
            .legend(|(x, y)| Circle::new((x + 6, y), 4, RED.filled()));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(perr)?;
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// What the Fig. A picture shows.
#[derive(Debug, Clone)]
pub struct H0Picture {
    pub points: Vec<(f64, f64)>,
    pub p0: f64,
    pub p2: f64,
    pub g0t: f64,
    pub n: usize,
}

/// The Appendix E picture (Fig. A): `<stem>.png` and `.svg` in `dir`.
pub fn h0_picture(dir: &Path, stem: &str, fit: &H0Picture) -> Result<Vec<PathBuf>, SweepError> {
    render(&dir.join(format!("{stem}.png")), fit)
}
