//! Phase maps side by side, with one legend counting every panel's points: the slices of a
//! 3-axis sweep (one panel per value of the third axis), or two maps compared
//! ([`crate::pictures::map_comparison`], each panel with its boundary curves).
use crate::error::SweepError;
use crate::pictures::legend::{draw_legend, LegendKey, ORDER};
use crate::pictures::map_figure::{draw_panel, Curve, MapPoint, LEGEND_W};
use crate::pictures::render::{perr, render, Figure};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// One phase map of several side by side: its title, points and the curves drawn over it.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    pub title: String,
    pub pts: Vec<MapPoint>,
    pub curves: Vec<Curve>,
}

/// Several phase maps side by side, one legend for all.
struct SliceMaps<'a> {
    title: &'a str,
    names: (&'a str, &'a str),
    slices: &'a [Panel],
}

/// Width of one slice's panel.
const SLICE_W: u32 = 560;

impl Figure for SliceMaps<'_> {
    fn size(&self) -> (u32, u32) {
        (SLICE_W * self.slices.len() as u32 + LEGEND_W, 560)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(perr)?;
        let root = root.titled(self.title, ("sans-serif", 22)).map_err(perr)?;
        let (plots, legend_area) = root.split_horizontally(SLICE_W * self.slices.len() as u32);
        let panels = plots.split_evenly((1, self.slices.len()));
        // One entry per class, counted over every panel, in the order first met; one per
        // curve label.
        let mut classes: Vec<(String, usize, LegendKey)> = Vec::new();
        let mut curves: Vec<(String, LegendKey)> = Vec::new();
        for (area, p) in panels.iter().zip(self.slices) {
            let (drawn, lines) = draw_panel(area, &p.title, self.names, &p.pts, &p.curves)?;
            for (class, count, key) in drawn {
                match classes.iter_mut().find(|(c, _, _)| *c == class) {
                    Some((_, n, _)) => *n += count,
                    None => classes.push((class, count, key)),
                }
            }
            for (label, key) in lines {
                if !curves.iter().any(|(l, _)| *l == label) {
                    curves.push((label, key));
                }
            }
        }
        classes.sort_by_key(|(c, _, _)| ORDER.iter().position(|o| o == c).unwrap_or(usize::MAX));
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

/// Renders the panels side by side as `<stem>.png` and `<stem>.svg` in `dir`; returns both
/// paths.
pub fn slice_maps(
    dir: &Path,
    stem: &str,
    title: &str,
    names: (&str, &str),
    slices: &[Panel],
) -> Result<Vec<PathBuf>, SweepError> {
    if slices.iter().all(|p| p.pts.is_empty()) {
        return Err(SweepError::Invalid("no points to draw".into()));
    }
    render(
        &dir.join(format!("{stem}.png")),
        &SliceMaps {
            title,
            names,
            slices,
        },
    )
}
