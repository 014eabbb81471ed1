//! `v` and `s` against a parameter (paper Fig. 2b, 3b): markers per class, branches as lines
//! (solid stable, dashed unstable), bifurcation points.
use crate::error::SweepError;
use crate::pictures::branch_lines::BranchLine;
use crate::pictures::legend::class_colour;
use crate::pictures::render::perr;
use crate::pictures::render::{render, Figure};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

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

/// The quantity a panel draws against the parameter.
#[derive(Debug, Clone, Copy)]
enum Quantity {
    Speed,
    Deformation,
}

impl Quantity {
    fn of_marker(self, m: &Marker) -> f64 {
        match self {
            Self::Speed => m.v,
            Self::Deformation => m.s,
        }
    }

    /// Of a line's point `(x, v, s)`.
    fn of_point(self, p: &(f64, f64, f64)) -> f64 {
        match self {
            Self::Speed => p.1,
            Self::Deformation => p.2,
        }
    }

    fn label(self) -> &'static str {
        match self {
            Self::Speed => "speed v",
            Self::Deformation => "deformation s",
        }
    }
}

impl VsFigure<'_> {
    /// One panel: `q` (`v` or `s`) against the parameter over `x`, with the lines, the
    /// markers, the vertical lines and the legend.
    fn draw_panel<DB: DrawingBackend>(
        &self,
        panel: &DrawingArea<DB, Shift>,
        q: Quantity,
        x: (f64, f64),
    ) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let (markers, lines) = (self.markers, self.lines);
        let ymax = markers
            .iter()
            .map(|m| q.of_marker(m))
            .chain(
                lines
                    .iter()
                    .flat_map(|l| l.points.iter().map(|p| q.of_point(p))),
            )
            .fold(0.0, f64::max)
            .max(1e-3)
            * 1.08;
        let mut chart = ChartBuilder::on(panel)
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(52)
            .build_cartesian_2d(x.0..x.1, 0.0..ymax)
            .map_err(perr)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.x_label)
            .y_desc(q.label())
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
            self.draw_key(&mut chart, key, q)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .draw()
            .map_err(perr)?;
        Ok(())
    }

    /// The lines and markers of one class (or branch) `key` on a panel, with its legend entry.
    fn draw_key<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        key: &str,
        q: Quantity,
    ) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        let (markers, lines) = (self.markers, self.lines);
        let colour = class_colour(key);
        let mut legend_done = false;
        for l in lines.iter().filter(|l| l.key == key) {
            let pts = l.points.iter().map(|p| (p.0, q.of_point(p)));
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
                Circle::new((m.x, q.of_marker(m)), if m.bold { 3 } else { 2 }, style)
            }))
            .map_err(perr)?;
        if !legend_done {
            anno.label(key.to_string())
                .legend(move |(x, y)| Circle::new((x + 6, y), 4, colour.filled()));
        }
        Ok(())
    }
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
            let q = if i == 0 {
                Quantity::Speed
            } else {
                Quantity::Deformation
            };
            self.draw_panel(panel, q, (x0 - pad, x1 + pad))?;
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
