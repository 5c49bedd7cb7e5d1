//! SVG charts for reports, drawn with plotters' SVG backend into a `String` that
//! [`crate::report::Report::svg`] embeds inline (no image files, crisp at any zoom).
//!
//! Two kinds cover the experiments: [`scatter_svg`], cost against error with one series per
//! technique (optionally connected, optionally labelled point by point, linear or logarithmic
//! axes), and [`bar_svg`], grouped bars such as frames per second per view angle per
//! technique. Both skip non-finite values (and non-positive ones on a log axis), pad their
//! ranges, give each series a distinct colour from a colour-blind-aware palette ([`PALETTE`]) and
//! draw the legend beside the plot so that it never hides data. Neither panics: if plotters
//! reports an error, the SVG shows the message instead of the chart.

use plotters::coord::ranged1d::{BoldPoints, KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::ops::Range;

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

const FONT: &str = "Helvetica, Arial, sans-serif";
const INK: RGBColor = RGBColor(0x22, 0x26, 0x2e);
const MUTED: RGBColor = RGBColor(0x5a, 0x61, 0x6b);
const GRID: RGBColor = RGBColor(0xdd, 0xe1, 0xe6);
const GRID_LIGHT: RGBColor = RGBColor(0xf0, 0xf2, 0xf4);
const AXIS: RGBColor = RGBColor(0x8a, 0x91, 0x9a);

/// One named set of points in a [`scatter_svg`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Series {
    /// Name shown in the legend (e.g. the technique).
    pub name: String,
    /// `(x, y)` points in data units; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Optional small text beside each point (e.g. the parameter value); empty for none, or
    /// one per point (missing entries draw nothing).
    pub labels: Vec<String>,
    /// Whether to join the points with a line, in the order given.
    pub connect: bool,
}

impl Series {
    /// A series of unconnected, unlabelled points.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), points, labels: Vec::new(), connect: false }
    }

    /// Adds one label per point.
    pub fn with_labels(mut self, labels: Vec<String>) -> Self {
        self.labels = labels;
        self
    }

    /// Joins the points with a line in the order given.
    pub fn connected(mut self) -> Self {
        self.connect = true;
        self
    }
}

/// One named set of bars in a [`bar_svg`]: one value per category.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BarSeries {
    /// Name shown in the legend (e.g. the technique).
    pub name: String,
    /// Value per category, in category order; missing or non-finite values draw no bar.
    pub values: Vec<f64>,
}

impl BarSeries {
    /// A bar series.
    pub fn new(name: impl Into<String>, values: Vec<f64>) -> Self {
        BarSeries { name: name.into(), values }
    }
}

/// The colour of series `i`.
fn series_color(i: usize) -> RGBColor {
    let (r, g, b) = PALETTE[i % PALETTE.len()];
    RGBColor(r, g, b)
}

/// Formats an axis or bar value with up to four significant digits, without trailing zeros;
/// exponent form for magnitudes outside [0.001, 100000).
fn format_tick(v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.2e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = if mantissa.contains('.') {
            mantissa.trim_end_matches('0').trim_end_matches('.')
        } else {
            mantissa
        };
        return format!("{mantissa}e{exp}");
    }
    let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// How an axis maps data to the page.
#[derive(Clone, Debug)]
enum Scale {
    Linear,
    Log,
    /// Integer positions 0..n named by the strings.
    Category(Vec<String>),
}

/// A plotters coordinate axis with our own tick choice and formatting.
#[derive(Clone, Debug)]
struct Axis {
    lo: f64,
    hi: f64,
    scale: Scale,
}

/// The "nice" step (1, 2 or 5 × 10^k) giving at most `max_ticks` ticks over `span`.
fn nice_step(span: f64, max_ticks: usize) -> f64 {
    let raw = span / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * mag).find(|&s| s >= raw * (1.0 - 1e-9)).unwrap_or(10.0 * mag)
}

/// Multiples of `step` inside [lo, hi], computed as integer multiples so that 0 is exact.
fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    if step.is_nan() || step <= 0.0 || step.is_infinite() {
        return Vec::new();
    }
    let k0 = (lo / step - 1e-9).ceil() as i64;
    let k1 = (hi / step + 1e-9).floor() as i64;
    if k1 < k0 || k1 - k0 > 10_000 {
        return Vec::new();
    }
    (k0..=k1).map(|k| k as f64 * step).collect()
}

impl Axis {
    fn linear(lo: f64, hi: f64) -> Self {
        Axis { lo, hi, scale: Scale::Linear }
    }

    /// Position of `v` along the axis in [0, 1] (unclamped).
    fn fraction(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Log => (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10()),
            _ => (v - self.lo) / (self.hi - self.lo),
        }
    }

    fn linear_ticks(&self, max_bold: usize, light: bool) -> Vec<f64> {
        let step = nice_step(self.hi - self.lo, max_bold);
        if !light {
            return multiples(self.lo, self.hi, step);
        }
        let mantissa = step / 10f64.powf(step.log10().floor());
        let minor = if (mantissa - 2.0).abs() < 1e-6 { step / 4.0 } else { step / 5.0 };
        multiples(self.lo, self.hi, minor)
    }

    fn log_ticks(&self, max_bold: usize, light: bool) -> Vec<f64> {
        let (e0, e1) = (self.lo.log10().floor() as i32, self.hi.log10().ceil() as i32);
        if e1 - e0 > 700 {
            return Vec::new();
        }
        let inside = |v: &f64| *v >= self.lo * (1.0 - 1e-12) && *v <= self.hi * (1.0 + 1e-12);
        let with_mantissas = |ms: &[f64]| -> Vec<f64> {
            (e0..=e1).flat_map(|e| ms.iter().map(move |m| m * 10f64.powi(e))).filter(inside).collect()
        };
        let decades = with_mantissas(&[1.0]);
        if decades.len() >= 2 {
            if light {
                return with_mantissas(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
            }
            let every = decades.len().div_ceil(max_bold.max(1)).max(1);
            return decades.into_iter().step_by(every).collect();
        }
        let v = with_mantissas(&[1.0, 2.0, 5.0]);
        if v.len() >= 3 && v.len() <= max_bold {
            return if light { with_mantissas(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]) } else { v };
        }
        // About a decade or less: plain linear ticks read best.
        self.linear_ticks(max_bold, light)
    }
}

impl Ranged for Axis {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let t = self.fraction(*value);
        let t = if t.is_finite() { t.clamp(-4.0, 5.0) } else { 0.0 };
        (limit.0 as f64 + t * (limit.1 - limit.0) as f64).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        let light = hint.weight().allow_light_points();
        let max_bold = hint.bold_points();
        if max_bold == 0 || (light && hint.max_num_points() <= max_bold) {
            // No room for light lines beyond the bold ones.
            return Vec::new();
        }
        let ticks = |light| match &self.scale {
            Scale::Log => self.log_ticks(max_bold, light),
            _ => self.linear_ticks(max_bold, light),
        };
        match &self.scale {
            Scale::Linear | Scale::Log => {
                let t = ticks(light);
                if light && t.len() > hint.max_num_points() {
                    Vec::new()
                } else {
                    t
                }
            }
            Scale::Category(names) => {
                if light {
                    return Vec::new();
                }
                let every = names.len().div_ceil(max_bold.max(1)).max(1);
                (0..names.len()).step_by(every).map(|i| i as f64).collect()
            }
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for Axis {
    fn format_ext(&self, value: &f64) -> String {
        match &self.scale {
            Scale::Category(names) => {
                let i = value.round();
                if i >= 0.0 && (i as usize) < names.len() {
                    names[i as usize].clone()
                } else {
                    String::new()
                }
            }
            _ => format_tick(*value),
        }
    }
}

/// A padded axis range covering `values` (finite ones, and positive ones on a log axis).
fn data_axis(values: impl Iterator<Item = f64>, log: bool) -> Axis {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if log {
        let (l0, l1) = if lo > hi {
            (0.0, 1.0)
        } else if lo == hi {
            (lo.log10() - 0.5, hi.log10() + 0.5)
        } else {
            let pad = 0.06 * (hi.log10() - lo.log10());
            (lo.log10() - pad, hi.log10() + pad)
        };
        // Keep 10^l representable (no underflow to 0, no overflow to infinity).
        let (l0, l1) = (l0.clamp(-300.0, 299.0), l1.clamp(-299.0, 300.0));
        return Axis { lo: 10f64.powf(l0), hi: 10f64.powf(l1), scale: Scale::Log };
    }
    if lo > hi {
        return Axis::linear(0.0, 1.0);
    }
    if lo == hi {
        let pad = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return Axis::linear(lo - pad, hi + pad);
    }
    let pad = 0.06 * (hi - lo);
    Axis::linear(lo - pad, hi + pad)
}

/// Width of the y label area: room for the longest tick label and the rotated axis title.
fn y_label_area(axis: &Axis, n: usize) -> u32 {
    let chars =
        axis.key_points(BoldPoints(n)).iter().map(|v| axis.format_ext(v).chars().count()).max().unwrap_or(1)
            as u32;
    34 + 7 * chars
}

/// A text style in the chart font. plotters' SVG backend writes `size / 1.24` as the CSS font
/// size, so 15 gives about 12 px.
fn font(size: u32) -> TextStyle<'static> {
    (FONT, size).into_font().color(&INK)
}

/// Escapes text for an SVG element.
fn escape(s: &str) -> String {
    crate::report::escape_html(s)
}

/// Finishes an SVG string: adds a `<title>` for accessibility, or replaces the whole chart by
/// a short message if drawing failed.
fn finish(mut svg: String, title: &str, error: Option<String>) -> String {
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

/// Draws the legend entries (swatch + name) down the left edge of `area`.
fn draw_legend(
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
fn legend_layout(names: &[String]) -> (u32, Vec<String>) {
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

type DrawResult = Result<(), Box<dyn std::error::Error>>;

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

    fn looks_like_svg(s: &str) {
        assert!(s.starts_with("<svg"), "{}", &s[..s.len().min(80)]);
        assert!(s.trim_end().ends_with("</svg>"));
        assert_eq!(s.matches("<svg").count(), 1);
    }

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

    #[test]
    fn ticks_are_nice_and_exact() {
        let a = Axis::linear(-0.07, 1.07);
        let t: Vec<String> = a.linear_ticks(8, false).into_iter().map(format_tick).collect();
        assert_eq!(t, ["0", "0.2", "0.4", "0.6", "0.8", "1"]);
        let log = Axis { lo: 0.5, hi: 2000.0, scale: Scale::Log };
        assert_eq!(log.log_ticks(8, false), vec![1.0, 10.0, 100.0, 1000.0]);
        assert_eq!(format_tick(1250.0), "1250");
        assert_eq!(format_tick(12.5), "12.5");
        assert_eq!(format_tick(1e-5), "1e-5");
        assert_eq!(format_tick(123456.0), "1.23e5");
        assert_eq!(format_tick(-0.25), "-0.25");
    }
}
