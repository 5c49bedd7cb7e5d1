//! Order statistics of measured samples (timings, error values): one definition for every
//! crate, so that a "median" means the same thing in every table.

/// The median of `v`: the middle value for an odd count, the mean of the middle two for an
/// even count; NaN when `v` is empty. Sorts `v` in place (by `f64::total_cmp`, so NaN samples
/// sort last instead of panicking).
pub fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::median;

    #[test]
    fn odd_even_and_empty_counts() {
        assert_eq!(median(&mut [5.0, 1.0, 3.0]), 3.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!(median(&mut []).is_nan());
    }

    #[test]
    fn nan_samples_sort_last() {
        assert_eq!(median(&mut [f64::NAN, 1.0, 2.0]), 2.0);
    }
}
