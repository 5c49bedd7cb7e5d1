//! The numeric ranges of the command line. Each flag's range is one constant, from which both
//! its `--help` text (by `Display`) and its clap value parser are made, so that the two cannot
//! disagree; a value outside it is refused while the arguments are parsed, in one line naming
//! the flag, the value and the range. Whole numbers are read as `i128` first, so that `-1` is
//! named as out of range rather than as "invalid digit"; floats must be finite (NaN and the
//! infinities are refused by name).

use std::fmt;

/// An inclusive range of whole numbers, shown `MIN..=MAX`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Whole<T> {
    /// The smallest value accepted.
    pub min: T,
    /// The largest value accepted.
    pub max: T,
}

impl<T> Whole<T> {
    /// `min..=max`.
    pub const fn new(min: T, max: T) -> Self {
        Whole { min, max }
    }
}

impl<T: fmt::Display> fmt::Display for Whole<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..={}", self.min, self.max)
    }
}

impl<T: Copy + Into<i128> + TryFrom<i128>> Whole<T> {
    /// Whether `v` lies in the range.
    pub fn contains(&self, v: T) -> bool {
        (self.min.into()..=self.max.into()).contains(&v.into())
    }
}

/// The clap value parser of a whole-number flag whose values must lie in `range`.
pub fn in_range<T>(range: Whole<T>) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: Copy + fmt::Display + Into<i128> + TryFrom<i128> + Send + Sync + 'static,
{
    move |s: &str| {
        let v: i128 = s.trim().parse().map_err(|_| format!("'{s}' is not a whole number in {range}"))?;
        if v < range.min.into() || v > range.max.into() {
            return Err(format!("{v} is not in {range}"));
        }
        T::try_from(v).map_err(|_| format!("{v} is not in {range}"))
    }
}

/// An interval of finite floats, closed at the top and closed or open at the bottom; shown
/// `[MIN, MAX]` or `(MIN, MAX]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// The lower bound.
    pub min: f32,
    /// The upper bound (accepted).
    pub max: f32,
    /// Whether the lower bound itself is refused.
    pub open_min: bool,
}

impl Interval {
    /// `[min, max]`.
    pub const fn closed(min: f32, max: f32) -> Self {
        Interval { min, max, open_min: false }
    }

    /// `(min, max]`: above `min`, at most `max`.
    pub const fn above(min: f32, max: f32) -> Self {
        Interval { min, max, open_min: true }
    }

    /// Whether `v` lies in the interval (never for NaN).
    pub fn contains(&self, v: f32) -> bool {
        let low = if self.open_min { v > self.min } else { v >= self.min };
        low && v <= self.max
    }
}

impl fmt::Display for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let open = if self.open_min { '(' } else { '[' };
        write!(f, "{open}{}, {}]", self.min, self.max)
    }
}

/// The clap value parser of a float flag whose values must be finite and lie in `range`.
pub fn finite_in(range: Interval) -> impl Fn(&str) -> Result<f32, String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        let v: f32 = s.trim().parse().map_err(|_| format!("'{s}' is not a number in {range}"))?;
        if !v.is_finite() {
            return Err(format!("{v} is not a finite number in {range}"));
        }
        if !range.contains(v) {
            return Err(format!("{v} is not in {range}"));
        }
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_numbers_are_refused_outside_their_range_by_value() {
        const R: Whole<u32> = Whole::new(1, 1000);
        let p = in_range(R);
        assert_eq!(R.to_string(), "1..=1000");
        assert_eq!(p("1"), Ok(1));
        assert_eq!(p("1000"), Ok(1000));
        assert_eq!(p("0"), Err("0 is not in 1..=1000".into()));
        assert_eq!(p("-1"), Err("-1 is not in 1..=1000".into()));
        assert_eq!(p("99999999999999999999"), Err("99999999999999999999 is not in 1..=1000".into()));
        assert!(p("x").unwrap_err().contains("not a whole number in 1..=1000"));
        assert!(R.contains(5) && !R.contains(1001));
    }

    #[test]
    fn floats_must_be_finite_and_inside() {
        const C: Interval = Interval::closed(-89.0, 89.0);
        const O: Interval = Interval::above(0.0, 60.0);
        assert_eq!((C.to_string(), O.to_string()), ("[-89, 89]".into(), "(0, 60]".into()));
        let (c, o) = (finite_in(C), finite_in(O));
        assert_eq!(c("-89"), Ok(-89.0));
        assert_eq!(c("95"), Err("95 is not in [-89, 89]".into()));
        assert_eq!(o("60"), Ok(60.0));
        assert_eq!(o("0"), Err("0 is not in (0, 60]".into()));
        for bad in ["nan", "NaN", "-nan", "inf", "-inf"] {
            assert!(c(bad).unwrap_err().contains("is not a finite number in [-89, 89]"), "{bad}");
        }
        assert!(c("ten").unwrap_err().contains("'ten' is not a number in [-89, 89]"));
    }
}
