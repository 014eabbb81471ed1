//! The single-run panels of paper Fig. 1: the final field with the droplet's outline and
//! velocity, and `v(t)`, `s(t)`.
use crate::error::SweepError;
use crate::pictures::render::perr;
use crate::pictures::render::{render, Figure};
use droplet_solver::stepping::Field;
use droplet_solver::{
    contract::outcome::SeriesRow, model::params::ModelParams, model::state::DropletState,
};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use std::path::{Path, PathBuf};

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
    /// The amplitudes of modes `3..K` (`a_3..a_K`, then `b_3..b_K`); empty for 2 modes.
    higher: &'a [f64],
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
        draw_droplet(&mut chart, field.len, state, self.higher, params)?;
        colour_bar(&bar_area, lo, hi)
    }
}

/// The droplet's outline `r = R (1 + sum_k a_k cos kt + b_k sin kt)` (`k = 2..K`; `higher`
/// holds `a_3..a_K`, then `b_3..b_K`) around its centre wrapped into the box of side `len`,
/// and an arrow along its velocity.
fn draw_droplet<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    len: f64,
    state: &DropletState,
    higher: &[f64],
    params: &ModelParams,
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    let wrap = |c: f64| c - len * (c / len).round();
    let (xc, yc) = (wrap(state.x), wrap(state.y));
    let (a, b) = higher.split_at(higher.len() / 2);
    let outline: Vec<(f64, f64)> = (0..=360)
        .map(|i| {
            let t = i as f64 / 360.0 * std::f64::consts::TAU;
            let modes = (3..).zip(a.iter().zip(b));
            let relative = state.a2 * (2.0 * t).cos()
                + state.b2 * (2.0 * t).sin()
                + modes
                    .map(|(k, (ak, bk))| ak * (k as f64 * t).cos() + bk * (k as f64 * t).sin())
                    .sum::<f64>();
            let r = params.radius * (1.0 + relative);
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
    Ok(())
}

/// The colour bar beside the field: the field's colour map over `[lo, hi]`, labelled in `u`.
fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lo: f64,
    hi: f64,
) -> Result<(), SweepError>
where
    DB::ErrorType: 'static,
{
    let colour = |v: f64| ViridisRGB::get_color_normalized(v, lo, hi);
    let mut bar = ChartBuilder::on(area)
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

/// The Fig. 1 panels of one run: final field (interpolated, with a colour bar), outline (with
/// the amplitudes `higher` of modes `3..K`, `a_3..a_K` then `b_3..b_K`; empty for 2 modes)
/// and velocity arrow, and `v(t)`, `s(t)`. Writes `path` (PNG) and the same name with `.svg`.
pub fn run_picture(
    path: &Path,
    title: &str,
    params: &ModelParams,
    field: &Field,
    state: &DropletState,
    higher: &[f64],
    series: &[SeriesRow],
) -> Result<Vec<PathBuf>, SweepError> {
    render(
        path,
        &RunFigure {
            title,
            params,
            field,
            state,
            higher,
            series,
        },
    )
}
