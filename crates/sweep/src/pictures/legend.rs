//! The colours of the point labels (the paper's Fig. 2a palette) and the legend drawn beside
//! a chart.
use crate::error::SweepError;
use crate::map::point_class::{DIVERGED, MISSING, NOT_CLASSIFIED, UNSETTLED};
use crate::pictures::render::perr;
use plotters::coord::Shift;
use plotters::prelude::*;

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
pub(crate) const ORDER: [&str; 14] = [
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

/// The distinct `labels` in legend order: those of [`ORDER`] in its order, then any other
/// alphabetically.
pub(crate) fn legend_order<S: AsRef<str> + Ord>(labels: impl IntoIterator<Item = S>) -> Vec<S> {
    let mut distinct: Vec<S> = labels
        .into_iter()
        .collect::<std::collections::BTreeSet<S>>()
        .into_iter()
        .collect();
    // Stable: the labels outside ORDER keep their alphabetical order.
    distinct.sort_by_key(|l| {
        ORDER
            .iter()
            .position(|o| *o == l.as_ref())
            .unwrap_or(usize::MAX)
    });
    distinct
}

/// One entry of a legend drawn beside a chart.
pub(crate) enum LegendKey {
    Box(RGBColor),
    Line(ShapeStyle),
    /// A black cross: the points whose runs left the model.
    Cross,
}

/// Draws `entries` top-down in `area` (a panel beside the chart, so the legend never covers
/// data).
pub(crate) fn draw_legend<DB: DrawingBackend>(
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
            LegendKey::Cross => area
                .draw(&Cross::new((13, y), 5, BLACK.stroke_width(1)))
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
