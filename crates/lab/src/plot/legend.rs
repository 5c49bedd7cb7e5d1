//! The legend column beside a chart: a swatch and a name per series.

use super::style::font;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Draws the legend entries (swatch + name) down the left edge of `area`.
pub(super) fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    entries: &[(String, RGBColor)],
    bars: bool,
    lines: &[bool],
    top: i32,
) -> Result<(), Box<dyn std::error::Error>> {
    let row_h = 22;
    for (i, (name, color)) in entries.iter().enumerate() {
        let y = top + i as i32 * row_h;
        if bars {
            area.draw(&Rectangle::new([(6, y - 6), (18, y + 6)], color.filled()))?;
        } else {
            if lines.get(i).copied().unwrap_or(false) {
                area.draw(&PathElement::new(vec![(2, y), (22, y)], color.stroke_width(2)))?;
            }
            area.draw(&Circle::new((12, y), 4, color.filled()))?;
        }
        area.draw(&Text::new(name.clone(), (30, y), font(15).pos(Pos::new(HPos::Left, VPos::Center))))?;
    }
    Ok(())
}

/// The legend column width for these names (0 without names), with long names shortened.
pub(super) fn legend_layout(names: &[String]) -> (u32, Vec<String>) {
    const MAX_CHARS: usize = 28;
    if names.iter().all(|n| n.is_empty()) {
        return (0, names.to_vec());
    }
    let short: Vec<String> = names
        .iter()
        .map(|n| {
            if n.chars().count() > MAX_CHARS {
                let mut s: String = n.chars().take(MAX_CHARS - 1).collect();
                s.push('…');
                s
            } else {
                n.clone()
            }
        })
        .collect();
    let longest = short.iter().map(|n| n.chars().count()).max().unwrap_or(0) as u32;
    (44 + longest * 7 + 16, short)
}
