//! Tileable (periodic) noise: the lattice wraps after a whole number of cells per axis.
//!
//! Wrapping happens on the lattice indices before hashing, so the noise, and its derivative,
//! are exactly periodic: `n(p + k·period) == n(p)` bit for bit for whole-cell `p` offsets
//! (and to rounding of the f32 fraction otherwise). A texture sampled over one period tiles
//! seamlessly. For tileable fractal sums see [`crate::FractalParams::with_period`].

use crate::error::{NoiseError, Result};
use crate::perlin::{eval, Perlin};
use crate::wrap::PeriodWrap;

/// Largest accepted period, in lattice cells (keeps `i32` index arithmetic exact).
pub const MAX_PERIOD: u32 = 1 << 24;

/// A validated per-axis period in lattice cells, for `N`-dimensional noise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Period<const N: usize> {
    cells: [u32; N],
}

impl<const N: usize> Period<N> {
    /// Validates a period per axis: each must be in `1..=MAX_PERIOD`.
    pub fn new(cells: [u32; N]) -> Result<Self> {
        for (axis, &c) in cells.iter().enumerate() {
            if c == 0 || c > MAX_PERIOD {
                return Err(NoiseError::Period {
                    axis,
                    value: f64::from(c),
                    reason: "must be a whole number of cells between 1 and 2^24",
                });
            }
        }
        Ok(Self { cells })
    }

    /// The period per axis, in lattice cells.
    pub fn cells(&self) -> [u32; N] {
        self.cells
    }

    pub(crate) fn wrap(&self) -> PeriodWrap {
        let mut w = [1i32; 4];
        for (a, &c) in self.cells.iter().enumerate() {
            w[a] = c as i32;
        }
        PeriodWrap(w)
    }
}

impl Perlin {
    /// Noise that repeats with `period` cells along each axis.
    #[inline]
    pub fn noise_periodic<const N: usize>(&self, p: [f32; N], period: &Period<N>) -> f32 {
        const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
        self.noise_salted(p, 0, period.wrap())
    }

    /// Periodic noise with its analytic gradient.
    #[inline]
    pub fn noise_periodic_with_derivative<const N: usize>(
        &self,
        p: [f32; N],
        period: &Period<N>,
    ) -> (f32, [f32; N]) {
        const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
        eval::<N, true, _>(&self.perm, p, 0, period.wrap())
    }
}
