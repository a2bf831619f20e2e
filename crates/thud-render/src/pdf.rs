//! PDF figures: an SVG figure of [`super::figures`] converted with `svg2pdf` (the SVG is first
//! parsed and laid out by `usvg`, re-exported by `svg2pdf`).
//!
//! Text is set in a subset of DejaVu Sans embedded in the binary (`assets/fonts`, licence in
//! `assets/fonts/LICENSE-DejaVu.txt`), loaded into its own font database: no system font is
//! read, so a PDF is the same on every machine, and the font is embedded (subset) in the PDF.
//! Every generic family (`sans-serif`, the figures' own) maps to it. A character the font
//! lacks is an error ([`PdfError::MissingGlyph`]), never a blank box.
//!
//! The page is the figure's size in CSS pixels at 96 per inch: 1 px = 0.75 pt, so the
//! default 860×540 px figure is a 645×405 pt page (8.96 × 5.63 in).

use std::sync::{Arc, LazyLock};

use svg2pdf::usvg::{self, fontdb};
use thiserror::Error;

/// The embedded font: DejaVu Sans (Book), subset to Latin, Greek, punctuation, arrows,
/// super/subscripts and mathematical operators (`assets/fonts/LICENSE-DejaVu.txt`).
pub const FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans-thud.ttf");

/// The family name of [`FONT`].
pub const FONT_FAMILY: &str = "DejaVu Sans";

/// CSS pixels per inch: the PDF page is the SVG's size in px × 72/96 pt.
pub const DPI: f32 = 96.0;

/// Why a figure could not be made a PDF (each a bug in thud's SVG or font, not bad input).
#[derive(Debug, Error)]
pub enum PdfError {
    /// The SVG could not be parsed.
    #[error("cannot read the SVG figure: {0}")]
    Svg(#[from] usvg::Error),
    /// A character of the figure's text is not in the embedded font.
    #[error("the embedded font has no glyph for {0:?} (U+{code:04X})", code = u32::from(*.0))]
    MissingGlyph(char),
    /// svg2pdf refused the tree.
    #[error("cannot convert the figure to PDF: {0}")]
    Convert(svg2pdf::ConversionError),
}

/// The font database holding only [`FONT`], every generic family mapped to it.
fn font_database() -> Arc<fontdb::Database> {
    static DB: LazyLock<Arc<fontdb::Database>> = LazyLock::new(|| {
        let mut db = fontdb::Database::new();
        db.load_font_data(FONT.to_vec());
        db.set_sans_serif_family(FONT_FAMILY);
        db.set_serif_family(FONT_FAMILY);
        db.set_monospace_family(FONT_FAMILY);
        db.set_cursive_family(FONT_FAMILY);
        db.set_fantasy_family(FONT_FAMILY);
        Arc::new(db)
    });
    Arc::clone(&DB)
}

/// The `usvg` tree of an SVG figure, text laid out in [`FONT`]: what [`from_svg`] converts
/// (public so tests can render the PDF's source to pixels).
pub fn tree(svg: &str) -> Result<usvg::Tree, PdfError> {
    let options = usvg::Options {
        font_family: FONT_FAMILY.into(),
        dpi: DPI,
        fontdb: font_database(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options)?;
    if let Some(c) = missing_glyph(tree.root()) {
        return Err(PdfError::MissingGlyph(c));
    }
    Ok(tree)
}

/// The first character of the group's text that was set as the font's `.notdef` glyph.
fn missing_glyph(group: &usvg::Group) -> Option<char> {
    group.children().iter().find_map(|node| match node {
        usvg::Node::Group(g) => missing_glyph(g),
        usvg::Node::Text(t) => t
            .layouted()
            .iter()
            .flat_map(|span| &span.positioned_glyphs)
            .find(|g| g.id.0 == 0)
            .and_then(|g| g.text.chars().next()),
        usvg::Node::Path(_) | usvg::Node::Image(_) => None,
    })
}

/// An SVG figure as a one-page PDF of the same size (see the module doc), text embedded.
pub fn from_svg(svg: &str) -> Result<Vec<u8>, PdfError> {
    let tree = tree(svg)?;
    let page = svg2pdf::PageOptions { dpi: DPI };
    svg2pdf::to_pdf(&tree, svg2pdf::ConversionOptions::default(), page).map_err(PdfError::Convert)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A figure with `text` in it.
    fn figure(text: &str) -> String {
        let mut s = crate::svg::Svg::new(600.0, 400.0, "t");
        s.text(10.0, 50.0, text, 14.0, crate::svg::Anchor::Start, 0.0);
        s.finish()
    }

    #[test]
    fn the_figures_symbols_are_in_the_font() {
        for text in ["± μ µ θ τ ² ³ – — − × ° · → … §", "SPLmax 94.2 dB, U0 1.4 m/s"] {
            let t = tree(&figure(text)).unwrap();
            assert_eq!(missing_glyph(t.root()), None, "{text}");
        }
    }

    #[test]
    fn a_character_outside_the_font_is_an_error_not_a_box() {
        let e = from_svg(&figure("dB 中")).unwrap_err();
        assert!(matches!(e, PdfError::MissingGlyph('中')), "{e}");
    }
}
