//! Scatter plots: cost against error, one series per technique.

use super::axis::{data_axis, y_label_area};
use super::legend::{draw_legend, legend_layout};
use super::series::Series;
use super::style::{
    finish, font, series_color, DrawResult, AXIS, GRID, GRID_LIGHT, MUTED, PLOT_HEIGHT, PLOT_WIDTH,
};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A scatter plot of `series` as an SVG document: axes titled `x_label` and `y_label`, each
/// logarithmic if asked (non-positive values are then skipped), a legend on the right, optional
/// point labels and connecting lines. Ranges cover all finite points with a little padding;
/// with no point at all, empty axes and "no data" are drawn.
pub fn scatter_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    log_x: bool,
    log_y: bool,
) -> String {
    let mut svg = String::new();
    let error = {
        let root = SVGBackend::with_string(&mut svg, (PLOT_WIDTH, PLOT_HEIGHT)).into_drawing_area();
        let r = draw_scatter(&root, title, x_label, y_label, series, log_x, log_y);
        let r = r.and_then(|_| root.present().map_err(|e| e.into()));
        r.err().map(|e| e.to_string())
    };
    finish(svg, title, error)
}

fn draw_scatter(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    log_x: bool,
    log_y: bool,
) -> DrawResult {
    root.fill(&WHITE)?;
    let body = root.titled(title, font(22))?;
    let visible =
        |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite() && (!log_x || x > 0.0) && (!log_y || y > 0.0);
    let all = || series.iter().flat_map(|s| s.points.iter().copied()).filter(visible);
    let x_axis = data_axis(all().map(|p| p.0), log_x);
    let y_axis = data_axis(all().map(|p| p.1), log_y);
    let has_data = all().next().is_some();

    let names: Vec<String> = series.iter().map(|s| s.name.clone()).collect();
    let (legend_w, short) = legend_layout(&names);
    let (plot_area, legend_area) = body.split_horizontally(PLOT_WIDTH - legend_w);

    let mut chart = ChartBuilder::on(&plot_area)
        .margin_top(8)
        .margin_left(8)
        .margin_right(16)
        .margin_bottom(8)
        .x_label_area_size(50)
        .y_label_area_size(y_label_area(&y_axis, 8))
        .build_cartesian_2d(x_axis, y_axis)?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_labels(9)
        .y_labels(8)
        .max_light_lines(9)
        .label_style(font(14).color(&MUTED))
        .axis_desc_style(font(16))
        .bold_line_style(GRID)
        .light_line_style(GRID_LIGHT)
        .axis_style(AXIS)
        .draw()?;

    if !has_data {
        let (w, h) = plot_area.dim_in_pixel();
        plot_area.draw(&Text::new(
            "no data",
            (w as i32 / 2, h as i32 / 2),
            font(16).color(&MUTED).pos(Pos::new(HPos::Center, VPos::Center)),
        ))?;
    }

    for (i, s) in series.iter().enumerate() {
        let color = series_color(i);
        let pts: Vec<(usize, (f64, f64))> =
            s.points.iter().copied().enumerate().filter(|(_, p)| visible(p)).collect();
        if s.connect && pts.len() >= 2 {
            chart.draw_series(std::iter::once(PathElement::new(
                pts.iter().map(|&(_, p)| p).collect::<Vec<_>>(),
                color.stroke_width(2),
            )))?;
        }
        chart.draw_series(pts.iter().map(|&(_, p)| {
            EmptyElement::at(p)
                + Circle::new((0, 0), 5, color.filled())
                + Circle::new((0, 0), 5, WHITE.stroke_width(1))
        }))?;
    }

    // Point labels, placed where they overlap the least with markers and earlier labels.
    let (px_range, py_range) = chart.plotting_area().get_pixel_range();
    let bounds = [px_range.start as f64, py_range.start as f64, px_range.end as f64, py_range.end as f64];
    let mut occupied: Vec<[f64; 4]> = Vec::new();
    let mut labels = Vec::new();
    for s in series {
        for (k, p) in s.points.iter().enumerate().filter(|(_, p)| visible(p)) {
            let (cx, cy) = chart.backend_coord(p);
            let (cx, cy) = (cx as f64, cy as f64);
            occupied.push([cx - 6.0, cy - 6.0, cx + 6.0, cy + 6.0]);
            if let Some(text) = s.labels.get(k).filter(|t| !t.is_empty()) {
                labels.push((cx, cy, text.clone()));
            }
        }
    }
    let label_style = font(13).color(&MUTED);
    for (cx, cy, text) in labels {
        let w = 6.0 * text.chars().count() as f64;
        let h = 11.0;
        let candidates = [(7.0, -h - 4.0), (7.0, 3.0), (-7.0 - w, -h - 4.0), (-7.0 - w, 3.0)];
        let boxes = candidates.map(|(dx, dy)| [cx + dx, cy + dy, cx + dx + w, cy + dy + h]);
        let cost = |b: &[f64; 4]| -> f64 {
            let outside = (bounds[0] - b[0]).max(0.0)
                + (b[2] - bounds[2]).max(0.0)
                + (bounds[1] - b[1]).max(0.0)
                + (b[3] - bounds[3]).max(0.0);
            let overlap: f64 = occupied
                .iter()
                .map(|o| {
                    let ox = (b[2].min(o[2]) - b[0].max(o[0])).max(0.0);
                    let oy = (b[3].min(o[3]) - b[1].max(o[1])).max(0.0);
                    ox * oy
                })
                .sum();
            overlap + 50.0 * outside
        };
        let best = boxes.iter().min_by(|a, b| cost(a).total_cmp(&cost(b))).copied().unwrap_or(boxes[0]);
        root.draw(&Text::new(text, (best[0].round() as i32, best[1].round() as i32), label_style.clone()))?;
        occupied.push(best);
    }

    if legend_w > 0 {
        let entries: Vec<(String, RGBColor)> =
            short.into_iter().enumerate().map(|(i, n)| (n, series_color(i))).collect();
        let lines: Vec<bool> = series.iter().map(|s| s.connect).collect();
        draw_legend(&legend_area, &entries, false, &lines, 24)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::style::looks_like_svg;

    #[test]
    fn scatter_contains_series_names_labels_and_title() {
        let series = vec![
            Series::new("POM", vec![(1.0, 30.0), (2.0, 34.0), (4.0, 36.5)])
                .with_labels(vec!["8".into(), "16".into(), "32".into()])
                .connected(),
            Series::new("relief <binary>", vec![(1.5, 33.0), (3.0, 38.0)]),
        ];
        let svg = scatter_svg("cost & error", "time (ms)", "PSNR (dB)", &series, true, false);
        looks_like_svg(&svg);
        assert!(svg.contains("POM"));
        assert!(svg.contains("relief &lt;binary&gt;"));
        assert!(svg.contains("\n32\n"), "point labels are drawn");
        assert!(svg.contains("<title>cost &amp; error</title>"));
        assert!(svg.contains("PSNR (dB)"));
    }

    #[test]
    fn scatter_survives_empty_and_non_finite_input() {
        let cases = vec![
            vec![],
            vec![Series::new("empty", vec![])],
            vec![Series::new("bad", vec![(f64::NAN, 1.0), (1.0, f64::INFINITY), (-1.0, -2.0)])],
            vec![Series::new("one", vec![(0.0, 0.0)]).connected()],
            vec![Series::new("same", vec![(5.0, 5.0), (5.0, 5.0)])],
            vec![Series::new("huge", vec![(1e-300, 1e300), (1e300, 1e-300)])],
            vec![Series::new("", vec![(1.0, 2.0)]).with_labels(vec![])],
        ];
        for series in cases {
            for (lx, ly) in [(false, false), (true, true), (true, false)] {
                let svg = scatter_svg("t", "x", "y", &series, lx, ly);
                looks_like_svg(&svg);
                assert!(!svg.contains("could not be drawn"), "{svg}");
            }
        }
    }
}
