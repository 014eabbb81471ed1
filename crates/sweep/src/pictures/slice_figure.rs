//! The slices of a 3-axis sweep: one phase map per value of the third axis, side by side,
//! with one legend counting every slice's points.
use crate::error::SweepError;
use crate::pictures::legend::{draw_legend, LegendKey, ORDER};
use crate::pictures::map_figure::{draw_panel, MapPoint, LEGEND_W};
use crate::pictures::render::{perr, render, Figure};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Several phase maps side by side (the slices of a 3-axis sweep), one legend for all.
struct SliceMaps<'a> {
    title: &'a str,
    names: (&'a str, &'a str),
    /// Each slice's title and points.
    slices: &'a [(String, Vec<MapPoint>)],
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
        // One entry per class, counted over every slice, in the order first met.
        let mut classes: Vec<(String, usize, LegendKey)> = Vec::new();
        for (area, (title, pts)) in panels.iter().zip(self.slices) {
            for (class, count, key) in draw_panel(area, title, self.names, pts, &[])?.0 {
                match classes.iter_mut().find(|(c, _, _)| *c == class) {
                    Some((_, n, _)) => *n += count,
                    None => classes.push((class, count, key)),
                }
            }
        }
        classes.sort_by_key(|(c, _, _)| ORDER.iter().position(|o| o == c).unwrap_or(usize::MAX));
        let legend: Vec<(String, LegendKey)> = classes
            .into_iter()
            .map(|(class, count, key)| (format!("{class} ({count})"), key))
            .collect();
        draw_legend(&legend_area, &legend)?;
        root.present().map_err(perr)?;
        Ok(())
    }
}

/// Renders the slices of a 3-axis sweep side by side as `<stem>.png` and `<stem>.svg` in
/// `dir`: each slice's title and points; returns both paths.
pub fn slice_maps(
    dir: &Path,
    stem: &str,
    title: &str,
    names: (&str, &str),
    slices: &[(String, Vec<MapPoint>)],
) -> Result<Vec<PathBuf>, SweepError> {
    if slices.iter().all(|(_, p)| p.is_empty()) {
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
