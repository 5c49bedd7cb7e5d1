//! Line charts of dense curves: noise functions of one variable and 2D projections of paths.

use super::style::{escape, FONT, PALETTE};
use plotters::prelude::*;

/// A line chart of dense curves (no point markers, which would bury a 1000-point path) as an
/// SVG document. `square` draws a square plot with the same range on both axes and the
/// diagonal y = x dashed, so that a path on the diagonal reads as one at 45°. Curves with an
/// empty name are left out of the legend. Never panics: a drawing error is shown in the SVG.
pub fn line_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    curves: &[(String, Vec<(f64, f64)>)],
    square: bool,
) -> String {
    let (w, h) = if square { (560, 560) } else { (880, 520) };
    let mut svg = String::new();
    let error = {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        let r = draw_lines(&root, title, x_label, y_label, curves, square);
        r.and_then(|_| root.present().map_err(|e| e.into())).err().map(|e| e.to_string())
    };
    match error {
        None => svg,
        Some(e) => format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"60\"><text x=\"10\" y=\"30\">\
             {}: {}</text></svg>",
            escape(title),
            escape(&e)
        ),
    }
}

/// An axis tick value with at most three decimals, no trailing zeros and no "-0".
fn tick(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.replace('-', "−")
    }
}

/// The range `lo..hi` padded by 5 % (at least 0.001) on each side; −1..1 when not finite.
fn padded(lo: f64, hi: f64) -> std::ops::Range<f64> {
    if !(lo.is_finite() && hi.is_finite()) {
        return -1.0..1.0;
    }
    let pad = ((hi - lo) * 0.05).max(1e-3);
    (lo - pad)..(hi + pad)
}

fn draw_lines(
    root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    curves: &[(String, Vec<(f64, f64)>)],
    square: bool,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let ok = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let all = || curves.iter().flat_map(|c| c.1.iter()).filter(ok);
    let range = |f: fn(&(f64, f64)) -> f64| {
        all().map(f).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
    };
    let (x0, x1) = range(|p| p.0);
    let (y0, y1) = range(|p| p.1);
    let (xr, yr) = if square {
        let r = padded(x0.min(y0), x1.max(y1));
        (r.clone(), r)
    } else {
        (padded(x0, x1), padded(y0, y1))
    };
    let mut chart = ChartBuilder::on(root)
        .caption(title, (FONT, 20))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(60)
        .build_cartesian_2d(xr.clone(), yr.clone())?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .max_light_lines(4)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .bold_line_style(RGBColor(0xdd, 0xe1, 0xe6))
        .light_line_style(RGBColor(0xf0, 0xf2, 0xf4))
        .draw()?;
    if square {
        let (lo, hi) = (xr.start, xr.end);
        chart.draw_series(DashedLineSeries::new(
            vec![(lo, lo), (hi, hi)],
            6,
            4,
            RGBColor(0x8a, 0x91, 0x9a).stroke_width(1),
        ))?;
    }
    let mut labelled = false;
    for (i, (name, pts)) in curves.iter().enumerate() {
        let (r, g, b) = PALETTE[i % PALETTE.len()];
        let color = RGBColor(r, g, b);
        let s = chart
            .draw_series(LineSeries::new(pts.iter().copied().filter(|p| ok(&p)), color.stroke_width(2)))?;
        if !name.is_empty() {
            labelled = true;
            s.label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        }
    }
    if labelled {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font((FONT, 13))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(0xdd, 0xe1, 0xe6))
            .draw()?;
    }
    Ok(())
}
