//! Pictures: the phase map (paper Fig. 2a) and the single-run panels (Fig. 1), as PNG and SVG.
use crate::error::SweepError;
use droplet_solver::scheme::Field;
use droplet_solver::{DropletState, ModelParams, SeriesRow};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

static FONT: Once = Once::new();

/// Registers the bundled DejaVu Sans for every family plotters may ask for.
pub(crate) fn register_fonts() {
    FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../../assets/DejaVuSans.ttf");
        for family in ["sans-serif", "serif", "monospace"] {
            for style in [
                FontStyle::Normal,
                FontStyle::Bold,
                FontStyle::Italic,
                FontStyle::Oblique,
            ] {
                let _ = plotters::style::register_font(family, style, bytes);
            }
        }
    });
}

pub(crate) fn perr<E: std::fmt::Display>(e: E) -> SweepError {
    SweepError::Plot(e.to_string())
}

/// The paper's colour for a point label (Fig. 2a), and colours for the labels it does not use.
pub fn class_colour(label: &str) -> RGBColor {
    match label {
        "IC" => RGBColor(220, 30, 30),
        "ID" => RGBColor(20, 150, 40),
        "MD" => RGBColor(0, 0, 139),
        "IC/MD" => RGBColor(0, 200, 220),
        "ID/MD" => RGBColor(235, 205, 0),
        "IC/MC" => RGBColor(150, 150, 150),
        "not classified" => RGBColor(140, 80, 20),
        "MC" => RGBColor(255, 140, 0),
        "IC/ID" => RGBColor(240, 120, 200),
        "MD/MC" => RGBColor(130, 60, 180),
        "ID/MC" => RGBColor(120, 130, 40),
        "diverged" => RGBColor(0, 0, 0),
        "MD minor-axis" => RGBColor(0, 0, 139),
        "MD major-axis" => RGBColor(140, 80, 20),
        _ => RGBColor(255, 255, 255),
    }
}

/// Legend order: the paper's classes first.
const ORDER: [&str; 13] = [
    "IC",
    "ID",
    "MD",
    "IC/MD",
    "ID/MD",
    "IC/MC",
    "not classified",
    "MC",
    "IC/ID",
    "MD/MC",
    "ID/MC",
    "diverged",
    "missing",
];

/// One point of a phase map.
#[derive(Debug, Clone)]
pub struct MapPoint {
    pub eta_t: f64,
    pub kappa2: f64,
    pub label: String,
}

/// A curve drawn over a phase map (e.g. an analytic boundary).
#[derive(Debug, Clone)]
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

fn spacing(v: &mut Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v.windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min)
}

fn draw_map<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    pts: &[MapPoint],
    curves: &[Curve],
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(perr)?;
    let mut xs: Vec<f64> = pts.iter().map(|p| p.eta_t).collect();
    let mut ys: Vec<f64> = pts.iter().map(|p| p.kappa2).collect();
    let dx = spacing(&mut xs);
    let dy = spacing(&mut ys);
    let dx = if dx.is_finite() { dx } else { 0.01 };
    let dy = if dy.is_finite() { dy } else { 0.01 };
    let (x0, x1) = (xs[0] - dx / 2.0, xs[xs.len() - 1] + dx / 2.0);
    let (y0, y1) = (ys[0] - dy / 2.0, ys[ys.len() - 1] + dy / 2.0);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(perr)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("eta_t")
        .y_desc("kappa2")
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 18))
        .x_label_formatter(&|v| format!("{v:.3}"))
        .y_label_formatter(&|v| format!("{v:.3}"))
        .draw()
        .map_err(perr)?;
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
            .map_err(perr)?
            .label(format!("{label} ({})", mine.len()))
            .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 12, y + 6)], colour.filled()));
    }
    let styles = [
        BLACK,
        RGBColor(90, 90, 90),
        RGBColor(160, 0, 160),
        RGBColor(0, 110, 110),
    ];
    for (i, c) in curves.iter().enumerate() {
        let style = styles[i % styles.len()];
        let inside: Vec<(f64, f64)> = c
            .points
            .iter()
            .copied()
            .filter(|(x, y)| (x0..=x1).contains(x) && (y0..=y1).contains(y))
            .collect();
        if inside.len() < 2 {
            continue;
        }
        chart
            .draw_series(LineSeries::new(inside, style.stroke_width(2)))
            .map_err(perr)?
            .label(c.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 14, y)], style.stroke_width(2))
            });
    }
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
    register_fonts();
    let png = dir.join(format!("{stem}.png"));
    let svg = dir.join(format!("{stem}.svg"));
    draw_map(
        BitMapBackend::new(&png, (900, 760)).into_drawing_area(),
        title,
        pts,
        curves,
    )?;
    draw_map(
        SVGBackend::new(&svg, (900, 760)).into_drawing_area(),
        title,
        pts,
        curves,
    )?;
    Ok(vec![png, svg])
}

fn draw_run<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    params: &ModelParams,
    field: &Field,
    state: &DropletState,
    series: &[SeriesRow],
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(perr)?;
    let root = root.titled(title, ("sans-serif", 20)).map_err(perr)?;
    let (left, right) = root.split_horizontally(560);
    let half = field.len / 2.0;
    let mut chart = ChartBuilder::on(&left)
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(44)
        .caption("concentration u (white = high)", ("sans-serif", 16))
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
    let n = field.n;
    let stride = n.div_ceil(140).max(1);
    let (lo, hi) = field
        .values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let span = (hi - lo).max(1e-300);
    let dx = field.len / n as f64;
    let cell = dx * stride as f64;
    chart
        .draw_series((0..n).step_by(stride).flat_map(|iy| {
            (0..n).step_by(stride).map(move |ix| {
                let v = field.values[iy * n + ix];
                let g = (255.0 * (v - lo) / span).clamp(0.0, 255.0) as u8;
                let (x, y) = (
                    (ix as f64 - (n / 2) as f64) * dx,
                    (iy as f64 - (n / 2) as f64) * dx,
                );
                Rectangle::new(
                    [
                        (x - cell / 2.0, y - cell / 2.0),
                        (x + cell / 2.0, y + cell / 2.0),
                    ],
                    RGBColor(g, g, g).filled(),
                )
            })
        }))
        .map_err(perr)?;
    // Outline r = R (1 + a2 cos 2t + b2 sin 2t) around the centre wrapped into the box.
    let wrap = |c: f64| c - field.len * (c / field.len).round();
    let (xc, yc) = (wrap(state.x), wrap(state.y));
    let outline: Vec<(f64, f64)> = (0..=180)
        .map(|i| {
            let t = i as f64 / 180.0 * std::f64::consts::TAU;
            let r = params.radius * (1.0 + state.a2 * (2.0 * t).cos() + state.b2 * (2.0 * t).sin());
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

/// The Fig. 1 panels of one run: final field with outline and velocity arrow, and `v(t)`,
/// `s(t)`. Writes `path` (PNG) and the same name with `.svg`.
pub fn run_picture(
    path: &Path,
    title: &str,
    params: &ModelParams,
    field: &Field,
    state: &DropletState,
    series: &[SeriesRow],
) -> Result<Vec<PathBuf>, SweepError> {
    register_fonts();
    let png = path.with_extension("png");
    let svg = path.with_extension("svg");
    draw_run(
        BitMapBackend::new(&png, (1100, 560)).into_drawing_area(),
        title,
        params,
        field,
        state,
        series,
    )?;
    draw_run(
        SVGBackend::new(&svg, (1100, 560)).into_drawing_area(),
        title,
        params,
        field,
        state,
        series,
    )?;
    Ok(vec![png, svg])
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

fn draw_vs<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    x_label: &str,
    markers: &[Marker],
    vlines: &[(f64, String)],
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(perr)?;
    let root = root.titled(title, ("sans-serif", 20)).map_err(perr)?;
    let (x0, x1) = markers
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), m| {
            (a.min(m.x), b.max(m.x))
        });
    let pad = ((x1 - x0) * 0.03).max(1e-6);
    let panels = root.split_evenly((1, 2));
    for (i, panel) in panels.iter().enumerate() {
        let val = |m: &Marker| if i == 0 { m.v } else { m.s };
        let ymax = markers.iter().map(val).fold(0.0, f64::max).max(1e-3) * 1.08;
        let mut chart = ChartBuilder::on(panel)
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(52)
            .build_cartesian_2d(x0 - pad..x1 + pad, 0.0..ymax)
            .map_err(perr)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_label)
            .y_desc(if i == 0 { "speed v" } else { "deformation s" })
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .x_label_formatter(&|v| format!("{v:.3}"))
            .draw()
            .map_err(perr)?;
        for (x, label) in vlines {
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
        let mut keys: Vec<&str> = markers.iter().map(|m| m.key.as_str()).collect();
        keys.sort();
        keys.dedup();
        for key in keys {
            let colour = class_colour(key);
            let mine = markers.iter().filter(|m| m.key == key);
            chart
                .draw_series(mine.map(|m| {
                    let style = if m.bold {
                        colour.filled()
                    } else {
                        colour.stroke_width(1)
                    };
                    Circle::new((m.x, val(m)), if m.bold { 3 } else { 2 }, style)
                }))
                .map_err(perr)?
                .label(key.to_string())
                .legend(move |(x, y)| Circle::new((x + 6, y), 4, colour.filled()));
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

/// `v` and `s` against a parameter (Fig. 2b / Fig. 3b style): `<stem>.png` and `.svg` in `dir`.
/// Bold filled markers are stable (or steady) states, thin rings unstable ones; `vlines`
/// mark bifurcation points.
pub fn vs_parameter(
    dir: &Path,
    stem: &str,
    title: &str,
    x_label: &str,
    markers: &[Marker],
    vlines: &[(f64, String)],
) -> Result<Vec<PathBuf>, SweepError> {
    if markers.is_empty() {
        return Err(SweepError::Invalid("nothing to draw".into()));
    }
    register_fonts();
    let png = dir.join(format!("{stem}.png"));
    let svg = dir.join(format!("{stem}.svg"));
    draw_vs(
        BitMapBackend::new(&png, (1200, 520)).into_drawing_area(),
        title,
        x_label,
        markers,
        vlines,
    )?;
    draw_vs(
        SVGBackend::new(&svg, (1200, 520)).into_drawing_area(),
        title,
        x_label,
        markers,
        vlines,
    )?;
    Ok(vec![png, svg])
}

fn draw_h0<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    fit: &H0Picture,
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
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
        .x_desc("kappa2")
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
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 14, y)], green.stroke_width(2)));
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
    register_fonts();
    let png = dir.join(format!("{stem}.png"));
    let svg = dir.join(format!("{stem}.svg"));
    draw_h0(
        BitMapBackend::new(&png, (900, 640)).into_drawing_area(),
        fit,
    )?;
    draw_h0(SVGBackend::new(&svg, (900, 640)).into_drawing_area(), fit)?;
    Ok(vec![png, svg])
}
