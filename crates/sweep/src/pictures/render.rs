//! The one drawing scaffold behind every picture: a [`Figure`] draws itself on any plotters
//! backend; [`render`] draws it into an in-memory RGB buffer (encoded as PNG) and an SVG
//! string, and writes each file atomically (temporary file, fsync, rename). A full disk or a
//! kill therefore never leaves a partial or empty picture, and every error names its file.
use crate::error::SweepError;
use crate::store::atomic::write_atomic;
use image::ImageEncoder;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

static FONT: Once = Once::new();

/// Registers the bundled DejaVu Sans for every family plotters may ask for.
pub(crate) fn register_fonts() {
    FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../../../assets/DejaVuSans.ttf");
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

/// A drawing error as a [`SweepError`].
pub(crate) fn perr<E: std::fmt::Display>(e: E) -> SweepError {
    SweepError::Plot(e.to_string())
}

/// A picture that can draw itself on any backend.
pub trait Figure {
    /// Width and height in pixels.
    fn size(&self) -> (u32, u32);

    /// Draws onto `root` (filled, drawn and presented).
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
    where
        DB::ErrorType: 'static;
}

/// Draws `fig` to `path` with the extensions `.png` and `.svg`; returns both paths.
pub fn render(path: &Path, fig: &impl Figure) -> Result<Vec<PathBuf>, SweepError> {
    register_fonts();
    let (w, h) = fig.size();
    let png = path.with_extension("png");
    let svg = path.with_extension("svg");
    let named = |p: &Path, e: SweepError| SweepError::Plot(format!("{}: {e}", p.display()));
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    fig.draw(BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area())
        .map_err(|e| named(&png, e))?;
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(&rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| named(&png, perr(e)))?;
    write_atomic(&png, &bytes)?;
    let mut text = String::new();
    fig.draw(SVGBackend::with_string(&mut text, (w, h)).into_drawing_area())
        .map_err(|e| named(&svg, e))?;
    // plotters embeds a bitmap as `data:png;base64,...`; browsers want a MIME type.
    let text = text.replace("href=\"data:png;base64,", "href=\"data:image/png;base64,");
    write_atomic(&svg, text.as_bytes())?;
    Ok(vec![png, svg])
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Square;

    impl Figure for Square {
        fn size(&self) -> (u32, u32) {
            (40, 30)
        }
        fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
        where
            DB::ErrorType: 'static,
        {
            root.fill(&RED).map_err(perr)?;
            root.present().map_err(perr)
        }
    }

    #[test]
    fn writes_a_complete_png_and_svg_and_names_the_file_on_failure() {
        let dir = tempfile::tempdir().unwrap();
        let files = render(&dir.path().join("sq.png"), &Square).unwrap();
        let png = std::fs::read(&files[0]).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let svg = std::fs::read_to_string(&files[1]).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        // No temporaries left behind.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
        // A directory that does not exist: the error names the file, nothing is written.
        let e = render(&dir.path().join("no/such/sq.png"), &Square).unwrap_err();
        assert!(e.to_string().contains("sq.png"), "{e}");
    }

    /// A picture that is one 200 x 200 bitmap.
    struct Bitmap;

    impl Figure for Bitmap {
        fn size(&self) -> (u32, u32) {
            (220, 220)
        }

        fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), SweepError>
        where
            DB::ErrorType: 'static,
        {
            let rgb: Vec<u8> = (0..200 * 200)
                .flat_map(|i| [(i % 251) as u8, 0, 90])
                .collect();
            let image =
                plotters::element::BitMapElement::with_owned_buffer((10, 10), (200, 200), rgb)
                    .expect("buffer of the right size");
            root.draw(&image).map_err(perr)?;
            root.present().map_err(perr)
        }
    }

    #[test]
    fn a_bitmap_is_one_embedded_png_in_the_svg() {
        let dir = tempfile::tempdir().unwrap();
        let files = render(&dir.path().join("bitmap.png"), &Bitmap).unwrap();
        let svg = std::fs::read_to_string(&files[1]).unwrap();
        assert_eq!(svg.matches("<image").count(), 1, "one image element");
        assert!(
            svg.contains("href=\"data:image/png;base64,"),
            "a PNG with its MIME type"
        );
        // 40 000 pixels as rectangles would be megabytes.
        assert!(svg.len() < 200_000, "{} bytes", svg.len());
        assert!(svg.matches("<rect").count() < 10);
    }
}
