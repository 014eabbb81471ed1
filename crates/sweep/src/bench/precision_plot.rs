//! The work-precision picture of [`crate::bench`]: error against wall time, log-log, one
//! panel per case and one curve per method family.
use crate::bench::family::Family;
use crate::bench::scoring::BenchRow;
use crate::error::SweepError;
use crate::pictures::render::{perr, render, Figure};
use droplet_solver::contract::outcome::RunStatus;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Errors below this are drawn at it (exact agreement, e.g. a resting disk's `v`).
const FLOOR: f64 = 1e-10;

/// Colour of a family: paper-fd black, fixed-step spectral in blues, adaptive in
/// reds/oranges/greens by `dt_max`, the Newton finish in purples; `index` picks the shade.
fn colour(family: &Family, index: usize) -> RGBColor {
    let is = |dt_max: f64, x: f64| (dt_max - x).abs() < 1e-12;
    let shades: [RGBColor; 4] = match *family {
        Family::PaperFd => return BLACK,
        Family::Spectral { .. } => [
            RGBColor(150, 190, 230),
            RGBColor(80, 140, 210),
            RGBColor(20, 80, 180),
            RGBColor(10, 30, 110),
        ],
        Family::Newton { .. } => [
            RGBColor(200, 160, 230),
            RGBColor(140, 80, 200),
            RGBColor(90, 30, 150),
            RGBColor(50, 0, 90),
        ],
        Family::Adaptive { dt_max, .. } if is(dt_max, 0.1) => [
            RGBColor(150, 220, 150),
            RGBColor(40, 160, 60),
            RGBColor(10, 90, 30),
            RGBColor(0, 60, 0),
        ],
        Family::Adaptive { dt_max, .. } if is(dt_max, 0.25) => [
            RGBColor(250, 190, 120),
            RGBColor(240, 130, 30),
            RGBColor(170, 80, 0),
            RGBColor(110, 50, 0),
        ],
        Family::Adaptive { .. } => [
            RGBColor(240, 150, 150),
            RGBColor(220, 50, 50),
            RGBColor(150, 0, 0),
            RGBColor(90, 0, 0),
        ],
    };
    shades[index.min(3)]
}

/// The legend panel: one line per family in its colour, and what the markers mean.
fn draw_family_legend<DB: DrawingBackend>(
    legend: &DrawingArea<DB, Shift>,
    families: &[Family],
    shade: &dyn Fn(&Family) -> usize,
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    let (w, _) = legend.dim_in_pixel();
    let columns = if families.len() > 8 { 2 } else { 1 };
    let per = families.len().div_ceil(columns);
    for (i, f) in families.iter().enumerate() {
        let (col, row) = (i / per, i % per);
        let x = 20 + col as i32 * (w as i32 / 2);
        let y = 20 + row as i32 * 22;
        let c = colour(f, shade(f));
        legend
            .draw(&PathElement::new(
                vec![(x, y + 7), (x + 24, y + 7)],
                c.stroke_width(3),
            ))
            .map_err(perr)?;
        legend
            .draw(&Text::new(f.to_string(), (x + 30, y), ("sans-serif", 13)))
            .map_err(perr)?;
    }
    let y = 30 + per as i32 * 22;
    legend
        .draw(&Text::new(
            "dot: class agrees with the reference; cross: it does not",
            (20, y),
            ("sans-serif", 13),
        ))
        .map_err(perr)?;
    Ok(())
}

/// One curve per family over a case's panel: error against wall time, a dot where the run's
/// class agrees with the reference, a cross where it does not.
fn draw_families<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>,
    mine: &[&BenchRow],
    families: &[Family],
    shade: &dyn Fn(&Family) -> usize,
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    for f in families {
        let mut pts: Vec<(f64, f64, bool)> = mine
            .iter()
            .filter(|r| r.family == *f)
            .map(|r| (r.wall_s.max(1e-4), r.error().max(FLOOR), r.class_ok))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        if pts.is_empty() {
            continue;
        }
        let c = colour(f, shade(f));
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|p| (p.0, p.1)),
                c.stroke_width(2),
            ))
            .map_err(perr)?;
        // Filled: class agrees with the reference; cross: it does not.
        chart
            .draw_series(pts.iter().map(|p| {
                if p.2 {
                    Circle::new((p.0, p.1), 3, c.filled()).into_dyn()
                } else {
                    Cross::new((p.0, p.1), 5, c.stroke_width(2)).into_dyn()
                }
            }))
            .map_err(perr)?;
    }
    Ok(())
}

/// The distinct values of `items`, in order of first appearance.
fn in_order<T: PartialEq>(items: impl Iterator<Item = T>) -> Vec<T> {
    let mut out: Vec<T> = Vec::new();
    for x in items {
        if !out.contains(&x) {
            out.push(x);
        }
    }
    out
}

/// The work-precision picture.
struct WorkPrecision<'a> {
    title: &'a str,
    rows: &'a [BenchRow],
}

impl Figure for WorkPrecision<'_> {
    fn size(&self) -> (u32, u32) {
        (1500, 960)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let (title, rows) = (self.title, self.rows);
        root.fill(&WHITE).map_err(perr)?;
        let root = root.titled(title, ("sans-serif", 20)).map_err(perr)?;
        let cases = in_order(rows.iter().map(|r| r.case.as_str()));
        let families = in_order(rows.iter().map(|r| r.family));
        // Shade index within a colour group: by N, in order of appearance.
        let shade = |f: &Family| {
            families
                .iter()
                .filter(|g| g.colour_group() == f.colour_group())
                .position(|g| g == f)
                .unwrap_or(0)
        };
        let panels = root.split_evenly((2, 3));
        for (panel, case) in panels.iter().zip(&cases) {
            let mine: Vec<&BenchRow> = rows
                .iter()
                .filter(|r| {
                    r.case == *case
                        && r.status != RunStatus::Diverged.as_str()
                        && r.error().is_finite()
                })
                .collect();
            if mine.is_empty() {
                continue;
            }
            let (w0, w1) = mine.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
                (a.min(r.wall_s.max(1e-4)), b.max(r.wall_s))
            });
            let (e0, e1) = mine.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
                (a.min(r.error().max(FLOOR)), b.max(r.error().max(FLOOR)))
            });
            let what = if mine.iter().any(|r| r.err_series.is_some()) {
                "max series error (v, s)"
            } else {
                "steady error max(|dv|, |ds|)"
            };
            let mut chart = ChartBuilder::on(panel)
                .margin(10)
                .caption(*case, ("sans-serif", 16))
                .x_label_area_size(38)
                .y_label_area_size(58)
                .build_cartesian_2d(
                    (w0 / 1.5..w1 * 1.5).log_scale(),
                    (e0 / 2.0..e1 * 2.0).log_scale(),
                )
                .map_err(perr)?;
            chart
                .configure_mesh()
                .x_desc("wall time per run [s]")
                .y_desc(what)
                .label_style(("sans-serif", 12))
                .axis_desc_style(("sans-serif", 13))
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .light_line_style(WHITE)
                .draw()
                .map_err(perr)?;
            draw_families(&mut chart, &mine, &families, &shade)?;
        }
        // Legend panel: the sixth cell.
        if let Some(legend) = panels.get(cases.len()) {
            draw_family_legend(legend, &families, &shade)?;
        }
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// Draws `<stem>.png` and `.svg` in `dir`.
pub fn work_precision(
    dir: &Path,
    stem: &str,
    title: &str,
    rows: &[BenchRow],
) -> Result<Vec<PathBuf>, SweepError> {
    if rows.is_empty() {
        return Err(SweepError::Invalid("no benchmark rows to draw".into()));
    }
    render(
        &dir.join(format!("{stem}.png")),
        &WorkPrecision { title, rows },
    )
}
