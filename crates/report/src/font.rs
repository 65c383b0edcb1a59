//! The one font of every chart, embedded: text is measured for the layout and drawn into the
//! PNG with it, so a machine with no fonts installed (no fontconfig, no freetype) draws the same
//! figure. The SVG names the generic `sans-serif`, which a viewer may draw narrower; DejaVu Sans
//! is among the widest sans-serif faces, so nothing laid out for it collides in another.
//!
//! `fonts/DejaVuSans-subset.ttf` is DejaVu Sans 2.37 (Bitstream Vera licence,
//! `fonts/LICENSE-DejaVu.txt`) cut to the characters of charts, 103 kB of the full 760 kB:
//! `pyftsubset DejaVuSans.ttf --unicodes="U+0020-007E,U+00A0-017F,U+0370-03FF,U+2000-206F,`
//! `U+2070-209F,U+2100-214F,U+2190-21FF,U+2200-22FF,U+25A0-25FF" --layout-features=kern`
//! `--no-hinting` (Latin, Greek, punctuation, super- and subscripts, arrows, mathematical
//! operators).

use std::sync::OnceLock;

/// The font's bytes.
pub(crate) const FONT: &[u8] = include_bytes!("../fonts/DejaVuSans-subset.ttf");

/// The font's family name, which the PNG's renderer resolves `sans-serif` to.
pub(crate) const FAMILY: &str = "DejaVu Sans";

/// plotters' text sizes are 1.24 times the SVG font size it writes (`font-size = size / 1.24`).
const PLOTTERS_SIZE_RATIO: f64 = 1.24;

/// The parsed font.
fn face() -> Option<&'static ttf_parser::Face<'static>> {
    static FACE: OnceLock<Option<ttf_parser::Face<'static>>> = OnceLock::new();
    FACE.get_or_init(|| ttf_parser::Face::parse(FONT, 0).ok())
        .as_ref()
}

/// The width of `text` and its em height \[px\], drawn at plotters size `size`: the sum of
/// the glyphs' advances (a character the font lacks counts as its replacement glyph's).
pub(crate) fn text_size(text: &str, size: f64) -> (f64, f64) {
    let em = size / PLOTTERS_SIZE_RATIO;
    let Some(face) = face() else {
        return (0.6 * em * text.chars().count() as f64, em);
    };
    let units: f64 = text
        .chars()
        .map(|c| {
            let glyph = face.glyph_index(c).unwrap_or(ttf_parser::GlyphId(0));
            f64::from(face.glyph_hor_advance(glyph).unwrap_or(0))
        })
        .sum();
    (units / f64::from(face.units_per_em()) * em, em)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Text widths grow with the text and the size, and the font has the charts' symbols.
    #[test]
    fn measures_text() {
        let (narrow, _) = text_size("1", 16.0);
        let (wide, h) = text_size("1000", 16.0);
        assert!(narrow > 4.0 && wide > 3.5 * narrow, "{narrow} {wide}");
        assert!((h - 16.0 / 1.24).abs() < 1e-12);
        assert!(text_size("1000", 32.0).0 > 1.9 * wide);
        let face = face().expect("a TrueType font");
        let family = face
            .names()
            .into_iter()
            .find(|n| n.name_id == ttf_parser::name_id::FAMILY)
            .and_then(|n| n.to_string());
        assert_eq!(family.as_deref(), Some(FAMILY));
        for c in "µΔνσ·⁰¹²³⁴⁵⁶⁷⁸⁹⁻′–−≤≈²àéü".chars() {
            assert!(face.glyph_index(c).is_some(), "{c}");
        }
    }
}
