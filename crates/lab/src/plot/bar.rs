//! Grouped bar charts: one group per category, one bar per series.

use super::axis::{format_tick, y_label_area, Axis, Scale};
use super::legend::{draw_legend, legend_layout};
use super::series::BarSeries;
use super::style::{finish, font, series_color, DrawResult, AXIS, GRID, MUTED, PLOT_HEIGHT, PLOT_WIDTH};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A grouped bar chart as an SVG document: one group per category along x, one bar per
/// series inside each group (in series order, coloured as in the legend), values on a linear y
/// axis titled `y_label` that always includes 0. Values are printed above the bars when the
/// bars are wide enough to hold them. Non-finite or missing values draw no bar.
pub fn bar_svg<S: AsRef<str>>(title: &str, y_label: &str, categories: &[S], series: &[BarSeries]) -> String {
    let mut svg = String::new();
    let error = {
        let root = SVGBackend::with_string(&mut svg, (PLOT_WIDTH, PLOT_HEIGHT)).into_drawing_area();
        let cats: Vec<String> = categories.iter().map(|c| c.as_ref().to_string()).collect();
        let r = draw_bars(&root, title, y_label, &cats, series);
        let r = r.and_then(|_| root.present().map_err(|e| e.into()));
        r.err().map(|e| e.to_string())
    };
    finish(svg, title, error)
}

fn draw_bars(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    title: &str,
    y_label: &str,
    categories: &[String],
    series: &[BarSeries],
) -> DrawResult {
    root.fill(&WHITE)?;
    let body = root.titled(title, font(22))?;
    let n_cat = categories.len().max(1);
    let values = || {
        series.iter().flat_map(|s| s.values.iter().take(categories.len()).copied()).filter(|v| v.is_finite())
    };
    let lo = values().fold(0.0f64, f64::min);
    let hi = values().fold(0.0f64, f64::max);
    let (lo, hi) = if lo == hi {
        (0.0, 1.0)
    } else {
        let span = hi - lo;
        (if lo < 0.0 { lo - 0.08 * span } else { 0.0 }, if hi > 0.0 { hi + 0.1 * span } else { 0.0 })
    };
    let x_axis = Axis { lo: -0.5, hi: n_cat as f64 - 0.5, scale: Scale::Category(categories.to_vec()) };
    let y_axis = Axis::linear(lo, hi);

    let names: Vec<String> = series.iter().map(|s| s.name.clone()).collect();
    let (legend_w, short) = legend_layout(&names);
    let (plot_area, legend_area) = body.split_horizontally(PLOT_WIDTH - legend_w);
    let mut chart = ChartBuilder::on(&plot_area)
        .margin_top(8)
        .margin_left(8)
        .margin_right(16)
        .margin_bottom(8)
        .x_label_area_size(40)
        .y_label_area_size(y_label_area(&y_axis, 8))
        .build_cartesian_2d(x_axis, y_axis)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(n_cat.min(24))
        .y_labels(8)
        .y_desc(y_label)
        .max_light_lines(0)
        .label_style(font(14).color(&MUTED))
        .x_label_style(font(15))
        .axis_desc_style(font(16))
        .bold_line_style(GRID)
        .axis_style(AXIS)
        .draw()?;

    let m = series.len().max(1) as f64;
    let group = 0.8;
    let bar = group / m;
    let plot_px = plot_area.dim_in_pixel().0.saturating_sub(96) as f64;
    let bar_px = plot_px / n_cat as f64 * bar;
    for (j, s) in series.iter().enumerate() {
        let color = series_color(j);
        let x_of = |i: usize| i as f64 - group / 2.0 + j as f64 * bar;
        let bars = s.values.iter().take(categories.len()).enumerate().filter(|(_, v)| v.is_finite());
        chart.draw_series(bars.clone().map(|(i, &v)| {
            let x0 = x_of(i) + 0.06 * bar;
            let x1 = x_of(i) + 0.94 * bar;
            Rectangle::new([(x0, 0.0), (x1, v)], color.filled())
        }))?;
        chart.draw_series(bars.filter_map(|(i, &v)| {
            let text = format_tick(v);
            if (text.chars().count() as f64) * 7.0 > bar_px {
                return None;
            }
            let (dy, vpos) = if v >= 0.0 { (-3, VPos::Bottom) } else { (3, VPos::Top) };
            Some(
                EmptyElement::at((x_of(i) + bar / 2.0, v))
                    + Text::new(text, (0, dy), font(13).color(&MUTED).pos(Pos::new(HPos::Center, vpos))),
            )
        }))?;
    }
    if lo < 0.0 {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(-0.5, 0.0), (n_cat as f64 - 0.5, 0.0)],
            AXIS.stroke_width(1),
        )))?;
    }

    if legend_w > 0 {
        let entries: Vec<(String, RGBColor)> =
            short.into_iter().enumerate().map(|(i, n)| (n, series_color(i))).collect();
        draw_legend(&legend_area, &entries, true, &[], 24)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::style::looks_like_svg;

    #[test]
    fn bars_contain_categories_and_series() {
        let cats = ["0°", "30°", "60°", "80°"];
        let series = vec![
            BarSeries::new("POM", vec![120.0, 110.0, 80.0, 45.0]),
            BarSeries::new("relief", vec![90.0, f64::NAN, 60.0]),
        ];
        let svg = bar_svg("FPS by view angle", "frames per second", &cats, &series);
        looks_like_svg(&svg);
        for c in cats {
            assert!(svg.contains(c), "category {c}");
        }
        assert!(svg.contains("relief") && svg.contains("POM"));
        assert!(svg.contains("<rect"));
        for svg in [
            bar_svg::<&str>("none", "y", &[], &[]),
            bar_svg("neg", "y", &["a", "b"], &[BarSeries::new("s", vec![-1.0, 2.0])]),
            bar_svg("zero", "y", &["a"], &[BarSeries::new("s", vec![0.0])]),
        ] {
            looks_like_svg(&svg);
            assert!(!svg.contains("could not be drawn"), "{svg}");
        }
    }
}
