//! Improved Perlin gradient noise in 1 to 4 dimensions, with analytic derivatives.
//!
//! This is Ken Perlin's 2002 "improved noise": a pseudo-random gradient at every integer
//! lattice point, the dot product of each surrounding corner's gradient with the offset from
//! that corner (the thesis's S, T, U, V in §2.6, step 4), blended with the quintic fade
//! `f(t) = 6t⁵ − 15t⁴ + 10t³` (step 5), whose first and second derivatives vanish at the cell
//! edges so that the noise is C² across cells. Noise is exactly 0 at every lattice point.
//!
//! # Seeds per axis and how they combine
//!
//! The thesis builds pictures from a separate generator and seed per axis. [`Perlin`] keeps
//! one 256-entry permutation table `P_a` per axis `a`, each shuffled from that axis's seed
//! (Fisher–Yates driven by SplitMix64). A lattice point `(i₀, …, i_{N−1})` is hashed by
//! nesting the tables from the last axis to the first, every index taken modulo 256:
//!
//! ```text
//! h = P_{N−1}[i_{N−1}]            then for a = N−2 down to 0:   h = P_a[h + i_a]
//! 3D:  h(X, Y, Z) = P_x[ P_y[ P_z[Z] + Y ] + X ]
//! ```
//!
//! With equal seeds on every axis this is Perlin's reference hash `p[p[p[·]+·]+·]` (axes
//! taken in the reverse order). Putting x outermost lets the batch evaluator hash the (y, z)
//! part once per row. The low bits of `h` pick the gradient. The lattice repeats every 256
//! cells per axis (exactly as Perlin's reference does); the periodic variants wrap it at any
//! smaller whole period.
//!
//! The hand-scheduled 2D kernel takes its gradients from any lattice (`Lattice2`: a row part,
//! then a column part of the hash), so that the hashed lattice of [`crate::hashed`] is
//! evaluated by the same code as these tables.
//!
//! # Output range and scale
//!
//! Every function is scaled so that the value at a cell centre with every corner's gradient
//! aimed at it (the extreme for these gradient sets) is ±1, so outputs lie in `[−1, 1]`. The
//! tests check this by search (largest |n| found: 1.0, 0.99997 and 0.9988 in 1D–3D, 0.79 in
//! 4D, where the aligned configuration is rare) and by a property test over arbitrary f32
//! coordinates. Non-finite coordinates (NaN, ±∞) give 0 with zero derivative. Coordinates
//! are f32: beyond about 2²² the fraction inside a cell loses resolution, and beyond 2³¹ the
//! cell index saturates (the result stays defined and finite).

use crate::wrap::{NoWrap, Wrap};

/// Number of entries in each permutation table (the lattice period when no tiling is asked).
pub const TABLE_SIZE: usize = 256;

/// The quintic fade `6t⁵ − 15t⁴ + 10t³` (thesis §2.6 step 5).
#[inline(always)]
pub fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Derivative of [`fade`]: `30t⁴ − 60t³ + 30t² = 30t²(t − 1)²`.
#[inline(always)]
pub fn fade_derivative(t: f32) -> f32 {
    let s = t * (t - 1.0);
    30.0 * s * s
}

/// SplitMix64: a tiny, well-mixed generator, used only to shuffle the tables from a seed.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// The permutation of 0..=255 that `seed` selects (Fisher–Yates over SplitMix64).
pub fn permutation(seed: u32) -> [u8; TABLE_SIZE] {
    let mut table = [0u8; TABLE_SIZE];
    for (i, v) in table.iter_mut().enumerate() {
        *v = i as u8;
    }
    let mut rng = SplitMix64(u64::from(seed) ^ 0x005E_ED0F_9E21_u64);
    for i in (1..TABLE_SIZE).rev() {
        // Multiply-shift gives an unbiased-enough index in 0..=i without division.
        let j = ((rng.next() >> 32) * (i as u64 + 1)) >> 32;
        table.swap(i, j as usize);
    }
    table
}

/// A seeded improved-Perlin generator: one permutation table per axis.
///
/// Cheap to clone (1 KiB) and immutable, so it can be shared across threads; every method is
/// a pure function of the seeds and the coordinates.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Perlin {
    seeds: [u32; 4],
    pub(crate) perm: [[u8; TABLE_SIZE]; 4],
}

/// Scale factor per dimension that maps the extreme value to ±1 (see the module docs).
#[inline(always)]
pub(crate) const fn scale<const N: usize>() -> f32 {
    match N {
        1 => 2.0,
        2 => std::f32::consts::SQRT_2,
        3 => 1.0,
        _ => 2.0 / 3.0,
    }
}

/// The gradient that hash `h` selects in `N` dimensions.
///
/// * 1D: 16 slopes evenly spaced in [−1, 1].
/// * 2D: 8 unit vectors (axes and diagonals).
/// * 3D: Perlin's 12 cube-edge vectors (four repeated to make 16).
/// * 4D: Perlin's 32 vectors with one zero and three ±1 components.
#[inline(always)]
pub(crate) fn gradient<const N: usize>(h: u8) -> [f32; N] {
    let mut g = [0.0f32; N];
    match N {
        1 => g[0] = (f32::from(h & 15) - 7.5) / 7.5,
        2 => {
            const S: f32 = std::f32::consts::FRAC_1_SQRT_2;
            const G2: [[f32; 2]; 8] =
                [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0], [S, S], [-S, S], [S, -S], [-S, -S]];
            let v = G2[usize::from(h & 7)];
            g[0] = v[0];
            g[1] = v[1];
        }
        3 => {
            const G3: [[f32; 3]; 16] = [
                [1.0, 1.0, 0.0],
                [-1.0, 1.0, 0.0],
                [1.0, -1.0, 0.0],
                [-1.0, -1.0, 0.0],
                [1.0, 0.0, 1.0],
                [-1.0, 0.0, 1.0],
                [1.0, 0.0, -1.0],
                [-1.0, 0.0, -1.0],
                [0.0, 1.0, 1.0],
                [0.0, -1.0, 1.0],
                [0.0, 1.0, -1.0],
                [0.0, -1.0, -1.0],
                [1.0, 1.0, 0.0],
                [0.0, -1.0, 1.0],
                [-1.0, 1.0, 0.0],
                [0.0, -1.0, -1.0],
            ];
            let v = G3[usize::from(h & 15)];
            g[0] = v[0];
            g[1] = v[1];
            g[2] = v[2];
        }
        _ => {
            let zero = usize::from((h >> 3) & 3);
            let mut bit = 0;
            for (a, ga) in g.iter_mut().enumerate().take(4) {
                if a == zero {
                    continue;
                }
                *ga = if (h >> bit) & 1 == 0 { 1.0 } else { -1.0 };
                bit += 1;
            }
        }
    }
    g
}

/// Nested hash of one lattice point (see the module docs); `salt` shifts the innermost
/// (last-axis) index, which the fractal sums use to decorrelate octaves.
#[inline(always)]
pub(crate) fn hash<const N: usize>(perm: &[[u8; TABLE_SIZE]; 4], idx: [i32; N], salt: u8) -> u8 {
    let mut h = perm[N - 1][usize::from((idx[N - 1] as u8).wrapping_add(salt))];
    for a in (0..N - 1).rev() {
        h = perm[a][usize::from(h.wrapping_add(idx[a] as u8))];
    }
    h
}

/// Splits a coordinate into its lattice cell and the fraction inside it.
///
/// Equal to `(x.floor() as i32, x - x.floor())` but without `floor`, which on baseline x86-64
/// (no SSE4.1) is a library call: truncate, then step down for negative non-integers. Beyond
/// 2^31 in magnitude every f32 is an integer, so the fraction is 0 and the cell saturates.
#[inline(always)]
pub(crate) fn split(x: f32) -> (i32, f32) {
    if x.abs() < 2_147_483_520.0 {
        let i = x as i32;
        let i = i - i32::from(i as f32 > x);
        (i, x - i as f32)
    } else {
        (x as i32, 0.0)
    }
}

/// General N-dimensional evaluation: value and, when `DERIV`, the gradient.
#[allow(clippy::needless_range_loop)] // per-axis index arithmetic reads clearer with `a`
#[inline(always)]
pub(crate) fn eval<const N: usize, const DERIV: bool, W: Wrap>(
    perm: &[[u8; TABLE_SIZE]; 4],
    p: [f32; N],
    salt: u8,
    wrap: W,
) -> (f32, [f32; N]) {
    if !p.iter().all(|v| v.is_finite()) {
        return (0.0, [0.0; N]);
    }
    let mut i0 = [0i32; N];
    let mut t = [0.0f32; N];
    let mut u = [0.0f32; N];
    let mut du = [0.0f32; N];
    for a in 0..N {
        let (i, f) = split(p[a]);
        i0[a] = i;
        t[a] = f;
        u[a] = fade(f);
        du[a] = fade_derivative(f);
    }
    let mut value = 0.0f32;
    let mut deriv = [0.0f32; N];
    for corner in 0..(1usize << N) {
        let mut idx = [0i32; N];
        let mut d = [0.0f32; N];
        let mut w = 1.0f32;
        for a in 0..N {
            let bit = (corner >> a) & 1;
            idx[a] = wrap.wrap(a, i0[a].wrapping_add(bit as i32));
            d[a] = t[a] - bit as f32;
            w *= if bit == 1 { u[a] } else { 1.0 - u[a] };
        }
        let g = gradient::<N>(hash::<N>(perm, idx, salt));
        let mut dot = 0.0f32;
        for a in 0..N {
            dot += g[a] * d[a];
        }
        value += w * dot;
        if DERIV {
            for j in 0..N {
                let mut wj = if (corner >> j) & 1 == 1 { du[j] } else { -du[j] };
                for a in 0..N {
                    if a != j {
                        wj *= if (corner >> a) & 1 == 1 { u[a] } else { 1.0 - u[a] };
                    }
                }
                deriv[j] += wj * dot + w * g[j];
            }
        }
    }
    let s = scale::<N>();
    if DERIV {
        for v in deriv.iter_mut() {
            *v *= s;
        }
    }
    (value * s, deriv)
}

/// Hand-scheduled 3D value evaluation (the hot single-sample path).
#[inline(always)]
pub(crate) fn eval3_fast<W: Wrap>(perm: &[[u8; TABLE_SIZE]; 4], p: [f32; 3], salt: u8, wrap: W) -> f32 {
    if !(p[0].is_finite() && p[1].is_finite() && p[2].is_finite()) {
        return 0.0;
    }
    let (xi, x) = split(p[0]);
    let (yi, y) = split(p[1]);
    let (zi, z) = split(p[2]);
    let (x0, x1) = (wrap.wrap(0, xi) as u8, wrap.wrap(0, xi.wrapping_add(1)) as u8);
    let (y0, y1) = (wrap.wrap(1, yi) as u8, wrap.wrap(1, yi.wrapping_add(1)) as u8);
    let (z0, z1) = (
        (wrap.wrap(2, zi) as u8).wrapping_add(salt),
        (wrap.wrap(2, zi.wrapping_add(1)) as u8).wrapping_add(salt),
    );
    let (px, py, pz) = (&perm[0], &perm[1], &perm[2]);
    let hz0 = pz[usize::from(z0)];
    let hz1 = pz[usize::from(z1)];
    let h00 = py[usize::from(hz0.wrapping_add(y0))];
    let h10 = py[usize::from(hz0.wrapping_add(y1))];
    let h01 = py[usize::from(hz1.wrapping_add(y0))];
    let h11 = py[usize::from(hz1.wrapping_add(y1))];
    let g = |h: u8, x: f32, y: f32, z: f32| {
        let v = gradient::<3>(px[usize::from(h)]);
        v[0] * x + v[1] * y + v[2] * z
    };
    let (u, v, w) = (fade(x), fade(y), fade(z));
    let n000 = g(h00.wrapping_add(x0), x, y, z);
    let n100 = g(h00.wrapping_add(x1), x - 1.0, y, z);
    let n010 = g(h10.wrapping_add(x0), x, y - 1.0, z);
    let n110 = g(h10.wrapping_add(x1), x - 1.0, y - 1.0, z);
    let n001 = g(h01.wrapping_add(x0), x, y, z - 1.0);
    let n101 = g(h01.wrapping_add(x1), x - 1.0, y, z - 1.0);
    let n011 = g(h11.wrapping_add(x0), x, y - 1.0, z - 1.0);
    let n111 = g(h11.wrapping_add(x1), x - 1.0, y - 1.0, z - 1.0);
    let a = n000 + u * (n100 - n000);
    let b = n010 + u * (n110 - n010);
    let c = n001 + u * (n101 - n001);
    let d = n011 + u * (n111 - n011);
    let e = a + v * (b - a);
    let f = c + v * (d - c);
    e + w * (f - e)
}

/// Where a 2D kernel's lattice gradients come from. The hash of a lattice point is split into
/// a row part (from `iy`) and a column part (`ix` within that row), the shape of both the
/// nested permutation hash `P_x[P_y[y] + x]` and the integer hash of [`crate::hashed`], so that
/// a kernel hashes each row once.
pub(crate) trait Lattice2 {
    /// What a row contributes to the hash of its points.
    type Row: Copy;
    /// The row part of (wrapped) lattice row `iy`.
    fn row(&self, iy: i32) -> Self::Row;
    /// The gradient at (wrapped) lattice column `ix` of `row`.
    fn gradient(&self, row: Self::Row, ix: i32) -> [f32; 2];
}

/// Hand-scheduled 2D value evaluation over any [`Lattice2`]: the four corners' dot products
/// blended by a chain of lerps `a + (b − a)·fade(t)` (x first, then y, the order of
/// [`eval3_fast`]), scaled to ±1. Non-finite coordinates give 0.
#[inline(always)]
pub(crate) fn eval2_lerp<L: Lattice2, W: Wrap>(lattice: &L, p: [f32; 2], wrap: W) -> f32 {
    if !(p[0].is_finite() && p[1].is_finite()) {
        return 0.0;
    }
    let (xi, x) = split(p[0]);
    let (yi, y) = split(p[1]);
    let (x0, y0) = (wrap.wrap(0, xi), wrap.wrap(1, yi));
    let x1 = wrap.next(0, x0);
    let (r0, r1) = (lattice.row(y0), lattice.row(wrap.next(1, y0)));
    let g = |row: L::Row, ix: i32, dx: f32, dy: f32| {
        let v = lattice.gradient(row, ix);
        v[0] * dx + v[1] * dy
    };
    let n00 = g(r0, x0, x, y);
    let n10 = g(r0, x1, x - 1.0, y);
    let n01 = g(r1, x0, x, y - 1.0);
    let n11 = g(r1, x1, x - 1.0, y - 1.0);
    let (u, v) = (fade(x), fade(y));
    let a = n00 + (n10 - n00) * u;
    let b = n01 + (n11 - n01) * u;
    (a + (b - a) * v) * scale::<2>()
}

impl Perlin {
    /// A generator using the same seed on every axis.
    pub fn new(seed: u32) -> Self {
        Self::with_axis_seeds([seed; 4])
    }

    /// A generator with its own seed per axis `[x, y, z, w]` (the thesis's per-axis
    /// initial conditions). Axes a function does not use ignore their seed.
    pub fn with_axis_seeds(seeds: [u32; 4]) -> Self {
        Self { seeds, perm: seeds.map(permutation) }
    }

    /// The per-axis seeds this generator was built from.
    pub fn seeds(&self) -> [u32; 4] {
        self.seeds
    }

    /// 1D noise at `x`, in [−1, 1].
    #[inline]
    pub fn noise1(&self, x: f32) -> f32 {
        eval::<1, false, _>(&self.perm, [x], 0, NoWrap).0
    }

    /// 2D noise at `(x, y)`, in [−1, 1].
    #[inline]
    pub fn noise2(&self, x: f32, y: f32) -> f32 {
        eval::<2, false, _>(&self.perm, [x, y], 0, NoWrap).0
    }

    /// 3D noise at `(x, y, z)`, in [−1, 1].
    #[inline]
    pub fn noise3(&self, x: f32, y: f32, z: f32) -> f32 {
        eval3_fast(&self.perm, [x, y, z], 0, NoWrap)
    }

    /// 4D noise at `(x, y, z, w)`, in [−1, 1]; `w` is typically time (animated 3D noise).
    #[inline]
    pub fn noise4(&self, x: f32, y: f32, z: f32, w: f32) -> f32 {
        eval::<4, false, _>(&self.perm, [x, y, z, w], 0, NoWrap).0
    }

    /// N-dimensional noise (N = 1..=4) for generic callers.
    #[inline]
    pub fn noise<const N: usize>(&self, p: [f32; N]) -> f32 {
        const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
        eval::<N, false, _>(&self.perm, p, 0, NoWrap).0
    }

    /// Value and analytic gradient `(n, [∂n/∂x, …])`, N = 1..=4.
    ///
    /// The gradient differentiates the fade weights exactly (`fade_derivative`), so it is
    /// continuous across cells and matches finite differences.
    #[inline]
    pub fn noise_with_derivative<const N: usize>(&self, p: [f32; N]) -> (f32, [f32; N]) {
        const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
        eval::<N, true, _>(&self.perm, p, 0, NoWrap)
    }

    /// Noise with octave salt (used by the fractal sums); salt 0 is [`Perlin::noise`].
    #[inline(always)]
    pub(crate) fn noise_salted<const N: usize, W: Wrap>(&self, p: [f32; N], salt: u8, wrap: W) -> f32 {
        if N == 3 {
            eval3_fast(&self.perm, [p[0], p[1 % N], p[2 % N]], salt, wrap)
        } else {
            eval::<N, false, W>(&self.perm, p, salt, wrap).0
        }
    }

    /// Derivative variant of [`Perlin::noise_salted`].
    #[inline(always)]
    pub(crate) fn noise_deriv_salted<const N: usize, W: Wrap>(
        &self,
        p: [f32; N],
        salt: u8,
        wrap: W,
    ) -> (f32, [f32; N]) {
        eval::<N, true, W>(&self.perm, p, salt, wrap)
    }
}

impl Default for Perlin {
    /// Seed 0 on every axis.
    fn default() -> Self {
        Self::new(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wrap::PeriodWrap;

    #[test]
    fn fade_has_the_thesis_shape() {
        assert_eq!(fade(0.0), 0.0);
        assert_eq!(fade(1.0), 1.0);
        assert_eq!(fade(0.5), 0.5);
        assert_eq!(fade_derivative(0.0), 0.0);
        assert_eq!(fade_derivative(1.0), 0.0);
        for i in 0..=100 {
            let t = i as f32 / 100.0;
            let direct = 6.0 * t.powi(5) - 15.0 * t.powi(4) + 10.0 * t.powi(3);
            assert!((fade(t) - direct).abs() < 1e-5);
        }
    }

    #[test]
    fn tables_are_permutations_and_depend_on_the_seed() {
        for seed in [0, 1, 100, u32::MAX] {
            let mut seen = [false; TABLE_SIZE];
            for &v in permutation(seed).iter() {
                assert!(!seen[usize::from(v)]);
                seen[usize::from(v)] = true;
            }
        }
        assert_ne!(permutation(100), permutation(101));
    }

    #[test]
    fn gradient_sets_have_the_documented_lengths() {
        for h in 0..=255u8 {
            let g2 = gradient::<2>(h);
            assert!((g2[0] * g2[0] + g2[1] * g2[1] - 1.0).abs() < 1e-6);
            let g3 = gradient::<3>(h);
            assert_eq!(g3.iter().map(|v| v * v).sum::<f32>(), 2.0);
            let g4 = gradient::<4>(h);
            assert_eq!(g4.iter().filter(|v| **v == 0.0).count(), 1);
            assert_eq!(g4.iter().map(|v| v * v).sum::<f32>(), 3.0);
            assert!(gradient::<1>(h)[0].abs() <= 1.0);
        }
    }

    #[test]
    fn split_matches_floor() {
        for &x in &[
            0.0f32,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1.5,
            3.999_999_8,
            -3.999_999_8,
            16_777_215.0,
            -8e6 - 0.5,
            2e9,
            -2e9,
            3e9,
            -3e9,
            1e30,
            -1e30,
        ] {
            let (i, t) = split(x);
            if x.abs() < 2e9 + 1.0 {
                assert_eq!(i, x.floor() as i32, "{x}");
                assert_eq!(t, x - x.floor(), "{x}");
            } else {
                assert_eq!((i, t), (x as i32, 0.0), "{x}");
            }
            assert!((0.0..1.0).contains(&t));
        }
    }

    /// The permutation tables as a [`Lattice2`]: `P_x[P_y[y] + x]`, the gradient of [`eval`].
    struct Tables<'a>(&'a [[u8; TABLE_SIZE]; 4]);

    impl Lattice2 for Tables<'_> {
        type Row = u8;
        fn row(&self, iy: i32) -> u8 {
            self.0[1][usize::from(iy as u8)]
        }
        fn gradient(&self, row: u8, ix: i32) -> [f32; 2] {
            gradient::<2>(self.0[0][usize::from(row.wrapping_add(ix as u8))])
        }
    }

    #[test]
    fn lerp_2d_kernel_equals_the_general_one() {
        let p = Perlin::with_axis_seeds([5, 6, 7, 8]);
        let period = PeriodWrap([7, 5, 1, 1]);
        for i in 0..500 {
            let x = [i as f32 * 0.173 - 40.0, i as f32 * 0.071 + 0.5];
            let fast = eval2_lerp(&Tables(&p.perm), x, NoWrap);
            let general = eval::<2, false, _>(&p.perm, x, 0, NoWrap).0;
            assert!((fast - general).abs() < 1e-6, "{fast} vs {general}");
            let fast = eval2_lerp(&Tables(&p.perm), x, period);
            let general = eval::<2, false, _>(&p.perm, x, 0, period).0;
            assert!((fast - general).abs() < 1e-6, "periodic: {fast} vs {general}");
        }
        assert_eq!(eval2_lerp(&Tables(&p.perm), [f32::NAN, 0.5], NoWrap), 0.0);
    }

    #[test]
    fn fast_3d_path_equals_the_general_one() {
        let p = Perlin::with_axis_seeds([5, 6, 7, 8]);
        for i in 0..500 {
            let x = [i as f32 * 0.173 - 40.0, i as f32 * 0.071 + 0.5, 3.3 - i as f32 * 0.029];
            let fast = eval3_fast(&p.perm, x, 17, NoWrap);
            let general = eval::<3, false, _>(&p.perm, x, 17, NoWrap).0;
            assert!((fast - general).abs() < 1e-6, "{fast} vs {general}");
        }
    }
}
