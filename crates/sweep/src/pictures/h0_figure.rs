//! The Appendix E fit of `h0`: the deformation-only steady states `(kappa2, s)` and the
//! fitted parabola.
use crate::error::SweepError;
use crate::pictures::render::perr;
use crate::pictures::render::{render, Figure};
use crate::spec::axes::KAPPA2;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

impl H0Picture {
    /// `s = sqrt((p0 - kappa2) / p2)` sampled over `(k0, k1)` (padded by 0.001), below `smax`.
    fn parabola(&self, p0: f64, (k0, k1): (f64, f64), smax: f64) -> Vec<(f64, f64)> {
        (0..=300)
            .map(|i| k0 - 0.001 + (k1 - k0 + 0.002) * i as f64 / 300.0)
            .filter(|k| *k < p0)
            .map(|k| (k, ((p0 - k) / self.p2).sqrt()))
            .filter(|(_, s)| *s <= smax)
            .collect()
    }
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
        let curve = |p0: f64| fit.parabola(p0, (k0, k1), smax);
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
