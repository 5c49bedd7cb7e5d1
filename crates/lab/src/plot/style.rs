//! The look every chart shares: size, palette, font, colours, and how an SVG is finished (its
//! title, or a message in place of a chart that could not be drawn).

use plotters::prelude::*;

/// Width of every chart in SVG pixels (the HTML report scales it to the page width).
pub const PLOT_WIDTH: u32 = 880;
/// Height of every chart in SVG pixels.
pub const PLOT_HEIGHT: u32 = 520;

/// Series colours (Tableau 10), used in order and repeated after ten series.
pub const PALETTE: [(u8, u8, u8); 10] = [
    (0x4E, 0x79, 0xA7),
    (0xF2, 0x8E, 0x2B),
    (0xE1, 0x57, 0x59),
    (0x76, 0xB7, 0xB2),
    (0x59, 0xA1, 0x4F),
    (0xED, 0xC9, 0x48),
    (0xB0, 0x7A, 0xA1),
    (0xFF, 0x9D, 0xA7),
    (0x9C, 0x75, 0x5F),
    (0xBA, 0xB0, 0xAC),
];

pub(super) const FONT: &str = "Helvetica, Arial, sans-serif";
pub(super) const INK: RGBColor = RGBColor(0x22, 0x26, 0x2e);
pub(super) const MUTED: RGBColor = RGBColor(0x5a, 0x61, 0x6b);
pub(super) const GRID: RGBColor = RGBColor(0xdd, 0xe1, 0xe6);
pub(super) const GRID_LIGHT: RGBColor = RGBColor(0xf0, 0xf2, 0xf4);
pub(super) const AXIS: RGBColor = RGBColor(0x8a, 0x91, 0x9a);

/// The colour of series `i`.
pub(super) fn series_color(i: usize) -> RGBColor {
    let (r, g, b) = PALETTE[i % PALETTE.len()];
    RGBColor(r, g, b)
}

/// A text style in the chart font. plotters' SVG backend writes `size / 1.24` as the CSS font
/// size, so 15 gives about 12 px.
pub(super) fn font(size: u32) -> TextStyle<'static> {
    (FONT, size).into_font().color(&INK)
}

/// Escapes text for an SVG element.
pub(super) fn escape(s: &str) -> String {
    crate::report::escape_html(s)
}

/// Finishes an SVG string: adds a `<title>` for accessibility, or replaces the whole chart by
/// a short message if drawing failed.
pub(super) fn finish(mut svg: String, title: &str, error: Option<String>) -> String {
    if let Some(e) = error {
        return format!(
            "<svg width=\"{PLOT_WIDTH}\" height=\"80\" viewBox=\"0 0 {PLOT_WIDTH} 80\" \
             xmlns=\"http://www.w3.org/2000/svg\"><title>{t}</title><text x=\"10\" y=\"40\" \
             font-family=\"{FONT}\" font-size=\"14\">chart '{t}' could not be drawn: {m}</text></svg>\n",
            t = escape(title),
            m = escape(&e)
        );
    }
    if let Some(end) = svg.find('>') {
        svg.insert_str(end + 1, &format!("\n<title>{}</title>", escape(title)));
    }
    svg
}

pub(super) type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// Checks that `s` is one complete SVG document (for the charts' tests).
#[cfg(test)]
pub(super) fn looks_like_svg(s: &str) {
    assert!(s.starts_with("<svg"), "{}", &s[..s.len().min(80)]);
    assert!(s.trim_end().ends_with("</svg>"));
    assert_eq!(s.matches("<svg").count(), 1);
}
