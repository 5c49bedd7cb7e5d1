//! The footprint's second moments in level-0 texels after the eccentricity clamp
//! ([`second_moments`]), and the footprint ellipse on one mip level ([`Footprint`]): its
//! support and its Gaussian's conic in that level's texels, the inclusive texel span of each row inside the support
//! (from the quadratic, so no texel of the bounding box outside the ellipse is visited), and
//! the exact texel count the level choice needs. Integer conversions here are written without
//! libm calls (the baseline x86-64 target has no `roundss`).

// `!(x >= t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::ellipse::Ellipse;
use glam::Vec2;
use std::mem::MaybeUninit;

/// The footprint's second moments after the eccentricity clamp, with its squared semi-axes.
pub(super) struct Shape {
    /// `[m00, m01, m11]` of `J·Jᵀ` with the minor axis grown to `major/ecc` where it was
    /// shorter.
    pub m: [f32; 3],
    /// Squared major semi-axis (the larger eigenvalue of `J·Jᵀ`).
    pub major2: f32,
    /// Squared minor semi-axis after the clamp.
    pub minor2: f32,
}

/// The second moments `J·Jᵀ` of the footprint with columns `dx`, `dy` (level-0 texels per
/// pixel), its eigenvalues (as [`Jacobian::axes`](crate::ellipse::Jacobian::axes) computes them: `λ₁` from the trace and the
/// discriminant, `λ₂ = det²/λ₁`), and the eccentricity clamp applied as a rank-one update
/// along the minor axis (`Σ + (λ₂' − λ₂)·n·nᵀ`, `n` the unit minor direction), so that the
/// common unclamped footprint needs one square root and one division, no direction.
#[inline]
pub(super) fn second_moments(dx: Vec2, dy: Vec2, ecc: f32) -> Shape {
    let (ux, vx, uy, vy) = (dx.x, dx.y, dy.x, dy.y);
    let m00 = ux * ux + uy * uy;
    let m01 = ux * vx + uy * vy;
    let m11 = vx * vx + vy * vy;
    let half_tr = 0.5 * (m00 + m11);
    let half_diff = 0.5 * (m00 - m11);
    let l1 = half_tr + (half_diff * half_diff + m01 * m01).sqrt();
    // λ₂ = det²/λ₁ keeps its precision when the footprint is very eccentric.
    let det = ux * vy - uy * vx;
    let l2 = if l1 > 0.0 { (det * det / l1).min(l1) } else { 0.0 };
    let floor = l1 / (ecc * ecc);
    if !(l2 < floor) {
        return Shape { m: [m00, m01, m11], major2: l1, minor2: l2 };
    }
    // The major direction from whichever row of (Σ − λ₁·I) is better conditioned; the minor
    // direction is its perpendicular.
    let e1 = Vec2::new(l1 - m11, m01);
    let e2 = Vec2::new(m01, l1 - m00);
    let e = if e1.length_squared() >= e2.length_squared() { e1 } else { e2 };
    let len2 = e.length_squared();
    let k = if len2 > 0.0 && len2.is_finite() { (floor - l2) / len2 } else { 0.0 };
    Shape { m: [m00 + k * e.y * e.y, m01 - k * e.x * e.y, m11 + k * e.x * e.x], major2: l1, minor2: floor }
}

/// Rows whose spans [`Footprint::count`] keeps for the scan (a multiple of 8, the vector
/// kernel's rows per step; 512 bytes, which the compiler clears without a call to `memset`).
pub(super) const STORED_ROWS: usize = 64;

/// Where [`Footprint::count`] keeps the spans: not cleared first (a lookup reads only the rows
/// its count wrote, which the count reports).
pub(super) type Store = [MaybeUninit<(i32, i32)>; STORED_ROWS];

/// An empty [`Store`] (nothing written, nothing cleared).
#[inline(always)]
pub(super) fn store() -> Store {
    [MaybeUninit::uninit(); STORED_ROWS]
}

/// The rows of `store` a count wrote (`written` from its result).
#[inline(always)]
pub(super) fn written(store: &Store, written: usize) -> &[(i32, i32)] {
    let w = &store[..written.min(STORED_ROWS)];
    // SAFETY: the count wrote these rows; `MaybeUninit<T>` has `T`'s layout.
    unsafe { &*(w as *const [MaybeUninit<(i32, i32)>] as *const [(i32, i32)]) }
}

/// The ellipse on one level and the centre in that level's texel coordinates (texel `i` at
/// `i`).
pub(super) struct Footprint {
    /// The support: Heckbert's coefficients on this level (`F = A·C − B²/4`).
    pub e: Ellipse,
    /// The Gaussian's own conic (`Σ = J·Jᵀ + (ρ²/σ²)·I`): the weight's exponent is
    /// `Q/(2σ²·F)` of this one.
    pub g: Ellipse,
    /// The lookup point in this level's texel coordinates.
    pub centre: Vec2,
    /// Half-height of the bounding box, `√A`.
    pub half_v: f32,
    /// `1/A` of the support, for the spans.
    pub inv_a: f32,
}

/// `⌊x⌋` as an integer. Saturates for values beyond `i32`, which the callers' bounded
/// coordinates never reach.
#[inline(always)]
pub(super) fn floor_i(x: f32) -> i64 {
    let i = x as i32;
    (i - ((i as f32) > x) as i32) as i64
}

/// `⌈x⌉` as an integer, like [`floor_i`].
#[inline(always)]
pub(super) fn ceil_i(x: f32) -> i64 {
    let i = x as i32;
    (i + ((i as f32) < x) as i32) as i64
}

/// `⌊log₂ x⌋` of a finite `x ≥ 1` from its exponent bits.
#[inline(always)]
pub(super) fn floor_log2(x: f32) -> i32 {
    ((x.to_bits() >> 23) & 0xFF) as i32 - 127
}

impl Footprint {
    /// Inclusive texel range of row `j`, empty when `lo > hi`.
    #[inline(always)]
    pub fn span(&self, j: i64) -> (i64, i64) {
        let v = j as f32 - self.centre.y;
        let e = &self.e;
        // B² − 4AC = −4F, so the discriminant of A·U² + B·V·U + (C·V² − F) is 4F·(A − V²).
        let d = e.f * (e.a - v * v);
        if !(d >= 0.0) {
            return (1, 0);
        }
        let r = d.sqrt();
        let mid = -0.5 * e.b * v;
        let inv_a = self.inv_a;
        (ceil_i((mid - r) * inv_a + self.centre.x), floor_i((mid + r) * inv_a + self.centre.x))
    }

    /// The first and last row the support reaches.
    #[inline]
    pub fn rows(&self) -> (i64, i64) {
        (ceil_i(self.centre.y - self.half_v), floor_i(self.centre.y + self.half_v))
    }

    /// Exact number of texels inside, stopping once it passes `limit`, and the rows of
    /// `store` written: the spans of the first [`STORED_ROWS`] rows are kept there (in
    /// order from the first row) so that the scan need not solve them again.
    pub fn count(&self, limit: u64, store: &mut Store) -> (u64, usize) {
        let (j0, j1) = self.rows();
        let mut n = 0u64;
        let mut written = 0;
        for j in j0..=j1 {
            let (lo, hi) = self.span(j);
            if let Some(slot) = store.get_mut((j - j0) as usize) {
                slot.write((lo as i32, hi as i32));
                written += 1;
            }
            if hi >= lo {
                n += (hi - lo + 1) as u64;
                if n > limit {
                    break;
                }
            }
        }
        (n, written)
    }
}
