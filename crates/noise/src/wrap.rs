//! How a noise lattice's indices wrap: not at all, or modulo a per-axis period (tileable
//! noise), with or without a division. The policies are types, monomorphised into the noise
//! kernels, so the plain path pays nothing for the periodic option.

/// How lattice indices are wrapped: not at all, or modulo a per-axis period (tileable noise).
/// Monomorphised, so the plain path pays nothing for the periodic option.
pub(crate) trait Wrap: Copy {
    /// Wraps lattice index `i` on axis `axis`.
    fn wrap(self, axis: usize, i: i32) -> i32;

    /// The wrapped index after `i` on axis `axis`, for an `i` that [`Wrap::wrap`] gave.
    #[inline(always)]
    fn next(self, axis: usize, i: i32) -> i32 {
        self.wrap(axis, i.wrapping_add(1))
    }
}

/// No wrapping: the lattice repeats only every 256 cells.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NoWrap;

impl Wrap for NoWrap {
    #[inline(always)]
    fn wrap(self, _axis: usize, i: i32) -> i32 {
        i
    }
}

/// Wrap modulo a positive period per axis (in lattice cells).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PeriodWrap(pub(crate) [i32; 4]);

impl Wrap for PeriodWrap {
    #[inline(always)]
    fn wrap(self, axis: usize, i: i32) -> i32 {
        i.rem_euclid(self.0[axis])
    }
}

/// Wrap modulo a positive period per axis, as [`PeriodWrap`] (the same values), without a
/// division when the index lies within one period of `[0, period)`: the common case for
/// texture coordinates in or near the unit square, where a kernel wraps every sample.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NearWrap(pub(crate) [i32; 4]);

impl Wrap for NearWrap {
    #[inline(always)]
    fn wrap(self, axis: usize, i: i32) -> i32 {
        let p = self.0[axis];
        if (0..p).contains(&i) {
            i
        } else if i >= p && i - p < p {
            i - p
        } else if i < 0 && i >= -p {
            i + p
        } else {
            i.rem_euclid(p)
        }
    }

    #[inline(always)]
    fn next(self, axis: usize, i: i32) -> i32 {
        if i + 1 == self.0[axis] {
            0
        } else {
            i + 1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_wrap_equals_period_wrap() {
        for p in [1, 2, 7, 256, 1 << 24] {
            let (near, period) = (NearWrap([p; 4]), PeriodWrap([p; 4]));
            for i in
                (-3 * p..=3 * p).step_by((p as usize / 64).max(1)).chain([i32::MIN, i32::MAX, -1, 0, p - 1])
            {
                assert_eq!(near.wrap(0, i), period.wrap(0, i), "{i} mod {p}");
                let w = near.wrap(0, i);
                assert_eq!(near.next(0, w), period.next(0, w), "after {w} mod {p}");
            }
        }
    }
}
