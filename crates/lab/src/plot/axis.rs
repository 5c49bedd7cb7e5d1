//! Chart axes: linear or logarithmic ranges padded around the data, "nice" tick positions and
//! their labels.

use plotters::coord::ranged1d::{BoldPoints, KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use std::ops::Range;

/// Formats an axis or bar value with up to four significant digits, without trailing zeros;
/// exponent form for magnitudes outside [0.001, 100000).
pub(super) fn format_tick(v: f64) -> String {
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
pub(super) enum Scale {
    Linear,
    Log,
    /// Integer positions 0..n named by the strings.
    Category(Vec<String>),
}

/// A plotters coordinate axis with our own tick choice and formatting.
#[derive(Clone, Debug)]
pub(super) struct Axis {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) scale: Scale,
}

/// The "nice" step (1, 2 or 5 × 10^k) giving at most `max_ticks` ticks over `span`.
pub(super) fn nice_step(span: f64, max_ticks: usize) -> f64 {
    let raw = span / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * mag).find(|&s| s >= raw * (1.0 - 1e-9)).unwrap_or(10.0 * mag)
}

/// Multiples of `step` inside [lo, hi], computed as integer multiples so that 0 is exact.
pub(super) fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
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
    pub(super) fn linear(lo: f64, hi: f64) -> Self {
        Axis { lo, hi, scale: Scale::Linear }
    }

    /// Position of `v` along the axis in [0, 1] (unclamped).
    pub(super) fn fraction(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Log => (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10()),
            _ => (v - self.lo) / (self.hi - self.lo),
        }
    }

    pub(super) fn linear_ticks(&self, max_bold: usize, light: bool) -> Vec<f64> {
        let step = nice_step(self.hi - self.lo, max_bold);
        if !light {
            return multiples(self.lo, self.hi, step);
        }
        let mantissa = step / 10f64.powf(step.log10().floor());
        let minor = if (mantissa - 2.0).abs() < 1e-6 { step / 4.0 } else { step / 5.0 };
        multiples(self.lo, self.hi, minor)
    }

    pub(super) fn log_ticks(&self, max_bold: usize, light: bool) -> Vec<f64> {
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
pub(super) fn data_axis(values: impl Iterator<Item = f64>, log: bool) -> Axis {
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
pub(super) fn y_label_area(axis: &Axis, n: usize) -> u32 {
    let chars =
        axis.key_points(BoldPoints(n)).iter().map(|v| axis.format_ext(v).chars().count()).max().unwrap_or(1)
            as u32;
    34 + 7 * chars
}

#[cfg(test)]
mod tests {
    use super::*;

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
