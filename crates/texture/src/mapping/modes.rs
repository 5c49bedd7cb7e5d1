//! The scanline evaluation modes of the perspective mapping, each as the thesis (§2.1 and
//! §2.3 of the thesis; §2.2/§2.4 of the seed summary) describes it, plus affine interpolation
//! for contrast. Every kernel fills `out[n]` with the texture coordinate of pixel
//! `(x0 + n, y)` and reports its floating-point operations to an [`OpCounter`].
//!
//! | mode | per pixel (as written here) |
//! |---|---|
//! | [`Mode::Direct`] (2.4) | `u = (A·x+B·y+C)/(G·x+H·y+I)`, `v` alike: 8 mul, 8 add, 2 div |
//! | [`Mode::PerRow`] (2.5) | `u = (u_t + A·n)/(u_b + G·n)`, `v` alike: 4 mul, 4 add, 2 div |
//! | [`Mode::Incremental`] (2.6) | `w += A`, `q += G`, one reciprocal shared by `u` and `v`: 3 add, 2 mul, 1 div |
//! | [`Mode::IncrementalRows`] | (2.6) on 4 rows at once, one SIMD lane per row: as incremental |
//! | [`Mode::KStride`] (2.7) | `k` independent lanes, `w_n = w_{n−k} + k·A`: as incremental |
//! | [`Mode::TwoWay`] (Fig. 2.4) | incremental from both ends toward the middle |
//! | [`Mode::Affine`] | `u += du`, `v += dv` between exact end points: 2 add (not exact) |
//! | [`Mode::DepthCoordinate`] (2.32) | `w = z₁t / (z₂ − t(z₂ − z₁))`, then lerp: 4 mul, 3 add, 1 sub, 1 div |
//!
//! Pixel indices are converted through `i32` (a vectorisable conversion; rows beyond 2³¹
//! pixels are meaningless in `f32` anyway).
//!
//! Where a row crosses the horizon (`G·x + H·y + I = 0`) the results are the IEEE values of
//! the division (infinite or NaN); no kernel loops on data or panics.

use super::error::MappingError;
use super::ops::OpCounter;
use super::projective::Coeffs;
use glam::Vec2;

/// Largest stride [`Mode::KStride`] accepts.
pub const MAX_STRIDE: usize = 64;

/// How a scanline's texture coordinates are evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Heckbert's rational form evaluated afresh at every pixel, `u` and `v` each with its own
    /// numerator and denominator as (2.4) writes them — the thesis's "base Heckbert".
    Direct,
    /// (2.5): the parts `u_t = A·x0 + B·y + C`, `u_b = G·x0 + H·y + I` (and `v_t`) are constant
    /// along the row and computed once; each pixel is `(u_t + A·n)/(u_b + G·n)`, independent of
    /// its neighbours (the thesis's "parallel" form, Fig. 2.1).
    PerRow,
    /// (2.6): numerators and denominator stepped by one addition each per pixel; `u` and `v`
    /// share one reciprocal of the common denominator.
    Incremental,
    /// (2.6) run on four rows at once, each row in one lane of a 4-wide SIMD register
    /// ([`incremental_rows4`], through [`eval_spans`]): every lane performs exactly the
    /// sequential recurrence of [`Mode::Incremental`] — same operations, same order, same
    /// rounding for the same start pixel — but the four independent chains fill the vector
    /// unit that the one-row form leaves idle. On a single row ([`eval_row`]) it *is*
    /// [`Mode::Incremental`].
    IncrementalRows,
    /// (2.7): `k` interleaved lanes (the thesis's `k` threads; here SIMD-friendly lanes), each
    /// stepping `w_n = w_{n−k} + k·A`, `q_n = q_{n−k} + k·G`; the first `k` pixels come from
    /// (2.5). Needs `1 ≤ k ≤` [`MAX_STRIDE`].
    KStride(usize),
    /// Counter-directional ("зустрічне") texturing: one stream steps left to right with
    /// `w_n = w_{n−1} + A`, the other right to left with `w_n = w_{n+1} − A`; they meet in the
    /// middle. Interleaved in one loop they form two independent dependency chains.
    TwoWay,
    /// Affine ("linear interpolation"): exact at both ends of the span, linear in between.
    /// Not perspective-correct; here for contrast.
    Affine,
    /// The thesis's texel-depth method (2.32)/(2.33): the fraction along the object-space span
    /// is `w = z₁·t / (z₂ − t·(z₂ − z₁))` for screen fraction `t`, and the texture coordinate
    /// is interpolated linearly in `w`. Depths are taken as `1/q` (depth up to a constant
    /// factor, which the formula does not see). Exact, like the rational form.
    DepthCoordinate,
}

impl Mode {
    /// Every mode, with `k = 8` for the stride, in report order.
    pub const ALL: [Mode; 8] = [
        Mode::Direct,
        Mode::PerRow,
        Mode::Incremental,
        Mode::IncrementalRows,
        Mode::KStride(8),
        Mode::TwoWay,
        Mode::Affine,
        Mode::DepthCoordinate,
    ];

    /// Short name for reports.
    pub fn name(&self) -> String {
        match self {
            Mode::Direct => "direct".into(),
            Mode::PerRow => "per_row".into(),
            Mode::Incremental => "incremental".into(),
            Mode::IncrementalRows => "incremental_rows4".into(),
            Mode::KStride(k) => format!("k_stride_{k}"),
            Mode::TwoWay => "two_way".into(),
            Mode::Affine => "affine".into(),
            Mode::DepthCoordinate => "depth_coordinate".into(),
        }
    }

    /// Whether the mode computes the perspective mapping exactly (up to rounding).
    pub fn is_exact(&self) -> bool {
        !matches!(self, Mode::Affine)
    }
}

/// Evaluates one scanline: `out[n]` gets `(u, v)` at pixel `(x0 + n, y)`.
///
/// Errors only on a bad stride; any coefficients (even NaN) give a defined, possibly
/// non-finite, result.
pub fn eval_row<O: OpCounter>(
    c: &Coeffs,
    mode: Mode,
    x0: i32,
    y: i32,
    out: &mut [Vec2],
    ops: &mut O,
) -> Result<(), MappingError> {
    match mode {
        Mode::Direct => direct(c, x0, y, out, ops),
        Mode::PerRow => per_row(c, x0, y, out, ops),
        Mode::Incremental | Mode::IncrementalRows => incremental(c, x0, y, out, ops),
        Mode::KStride(k) => k_stride(c, k, x0, y, out, ops)?,
        Mode::TwoWay => two_way(c, x0, y, out, ops),
        Mode::Affine => affine(c, x0, y, out, ops),
        Mode::DepthCoordinate => depth_coordinate(c, x0, y, out, ops),
    }
    Ok(())
}

/// (2.4) direct: four linear forms and two divisions per pixel.
#[inline]
pub fn direct<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let yf = y as f32;
    for (n, o) in out.iter_mut().enumerate() {
        let x = x0.wrapping_add(n as i32) as f32;
        let u = (c.a * x + c.b * yf + c.c) / (c.g * x + c.h * yf + c.i);
        let v = (c.d * x + c.e * yf + c.f) / (c.g * x + c.h * yf + c.i);
        ops.mul(8);
        ops.add(8);
        ops.div(2);
        *o = Vec2::new(u, v);
    }
}

/// Row constants of (2.5): `(u_t, v_t, u_b)` at pixel `x0 + n0`.
#[inline(always)]
fn row_constants<O: OpCounter>(c: &Coeffs, x: f32, y: f32, ops: &mut O) -> (f32, f32, f32) {
    ops.mul(6);
    ops.add(6);
    (c.a * x + c.b * y + c.c, c.d * x + c.e * y + c.f, c.g * x + c.h * y + c.i)
}

/// (2.5) per-row constants, each pixel independent.
#[inline]
pub fn per_row<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (ut, vt, ub) = row_constants(c, x0 as f32, y as f32, ops);
    let vb = ub;
    for (n, o) in out.iter_mut().enumerate() {
        let nf = n as i32 as f32;
        let u = (ut + c.a * nf) / (ub + c.g * nf);
        let v = (vt + c.d * nf) / (vb + c.g * nf);
        ops.mul(4);
        ops.add(4);
        ops.div(2);
        *o = Vec2::new(u, v);
    }
}

/// (2.6) incremental with one shared reciprocal.
#[inline]
pub fn incremental<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (mut wu, mut wv, mut q) = row_constants(c, x0 as f32, y as f32, ops);
    for o in out.iter_mut() {
        let r = 1.0 / q;
        *o = Vec2::new(wu * r, wv * r);
        wu += c.a;
        wv += c.d;
        q += c.g;
        ops.div(1);
        ops.mul(2);
        ops.add(3);
    }
}

/// (2.6) on four rows at once. `rows[j]` receives row `y0 + j` for pixels `x0 .. x0 + len`
/// (each slice must hold `len` values). Each lane is the recurrence of [`incremental`]:
/// `r = 1/q; (u, v) = (w_u·r, w_v·r); w_u += A; w_v += D; q += G`.
#[inline]
pub fn incremental_rows4<O: OpCounter>(c: &Coeffs, x0: i32, y0: i32, rows: [&mut [Vec2]; 4], ops: &mut O) {
    use glam::Vec4;
    let x = x0 as f32;
    let mut lane = [(0.0f32, 0.0f32, 0.0f32); 4];
    for (j, l) in lane.iter_mut().enumerate() {
        *l = row_constants(c, x, y0.wrapping_add(j as i32) as f32, ops);
    }
    let mut wu = Vec4::new(lane[0].0, lane[1].0, lane[2].0, lane[3].0);
    let mut wv = Vec4::new(lane[0].1, lane[1].1, lane[2].1, lane[3].1);
    let mut q = Vec4::new(lane[0].2, lane[1].2, lane[2].2, lane[3].2);
    let (sa, sd, sg) = (Vec4::splat(c.a), Vec4::splat(c.d), Vec4::splat(c.g));
    let [r0, r1, r2, r3] = rows;
    let len = r0.len().min(r1.len()).min(r2.len()).min(r3.len());
    let (r0, r1, r2, r3) = (&mut r0[..len], &mut r1[..len], &mut r2[..len], &mut r3[..len]);
    for (((a, b), cc), d) in r0.iter_mut().zip(r1.iter_mut()).zip(r2.iter_mut()).zip(r3.iter_mut()) {
        let r = Vec4::ONE / q;
        let u = wu * r;
        let v = wv * r;
        *a = Vec2::new(u.x, v.x);
        *b = Vec2::new(u.y, v.y);
        *cc = Vec2::new(u.z, v.z);
        *d = Vec2::new(u.w, v.w);
        wu += sa;
        wv += sd;
        q += sg;
    }
    ops.div(4 * len as u32);
    ops.mul(8 * len as u32);
    ops.add(12 * len as u32);
}

/// The pixels of one row that a frame evaluation fills: `len` pixels from column `x0`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Span {
    /// First column.
    pub x0: u32,
    /// Number of pixels (0: none).
    pub len: u32,
}

/// Evaluates a whole frame: row `y0 + k` gets `(u, v)` for `spans[k]`, written into
/// `out[k·width + x]` (`out` holds `spans.len()` rows of `width`). Spans reaching past
/// `width` are cut. [`Mode::IncrementalRows`] takes four rows at a time over the union of
/// their spans (so it may also write pixels of those rows outside their own spans, inside
/// the union); every other mode evaluates each span with [`eval_row`].
pub fn eval_spans<O: OpCounter>(
    c: &Coeffs,
    mode: Mode,
    y0: i32,
    spans: &[Span],
    width: usize,
    out: &mut [Vec2],
    ops: &mut O,
) -> Result<(), MappingError> {
    let clip = |s: &Span| {
        let x0 = (s.x0 as usize).min(width);
        (x0, (s.len as usize).min(width - x0))
    };
    let rows_out = out.chunks_mut(width.max(1));
    if mode != Mode::IncrementalRows {
        for (k, (s, row)) in spans.iter().zip(rows_out).enumerate() {
            let (x0, len) = clip(s);
            if len > 0 {
                eval_row(c, mode, x0 as i32, y0.wrapping_add(k as i32), &mut row[x0..x0 + len], ops)?;
            }
        }
        return Ok(());
    }
    let mut rows: Vec<&mut [Vec2]> = rows_out.collect();
    let mut k = 0;
    while k < spans.len().min(rows.len()) {
        let group = &spans[k..(k + 4).min(spans.len())];
        let clipped: Vec<(usize, usize)> = group.iter().map(clip).collect();
        let y = y0.wrapping_add(k as i32);
        if clipped.len() == 4 && clipped.iter().all(|&(_, l)| l > 0) && k + 4 <= rows.len() {
            let lo = clipped.iter().map(|&(x, _)| x).min().unwrap_or(0);
            let hi = clipped.iter().map(|&(x, l)| x + l).max().unwrap_or(0);
            let [a, b, cc, d] = &mut rows[k..k + 4] else { unreachable!("four rows") };
            incremental_rows4(
                c,
                lo as i32,
                y,
                [&mut a[lo..hi], &mut b[lo..hi], &mut cc[lo..hi], &mut d[lo..hi]],
                ops,
            );
            k += 4;
        } else {
            let (x0, len) = clipped[0];
            if len > 0 {
                incremental(c, x0 as i32, y, &mut rows[k][x0..x0 + len], ops);
            }
            k += 1;
        }
    }
    Ok(())
}

/// (2.7) k interleaved lanes. Errors on `k = 0` or `k >` [`MAX_STRIDE`].
#[inline]
pub fn k_stride<O: OpCounter>(
    c: &Coeffs,
    k: usize,
    x0: i32,
    y: i32,
    out: &mut [Vec2],
    ops: &mut O,
) -> Result<(), MappingError> {
    match k {
        1 => k_stride_const::<1, O>(c, x0, y, out, ops),
        2 => k_stride_const::<2, O>(c, x0, y, out, ops),
        4 => k_stride_const::<4, O>(c, x0, y, out, ops),
        8 => k_stride_const::<8, O>(c, x0, y, out, ops),
        16 => k_stride_const::<16, O>(c, x0, y, out, ops),
        3 | 5..=7 | 9..=15 | 17..=MAX_STRIDE => k_stride_dyn(c, k, x0, y, out, ops),
        _ => return Err(MappingError::BadStride { k, max: MAX_STRIDE }),
    }
    Ok(())
}

/// Lane start values by (2.5) for lanes `0..k`, and the `k`-fold steps.
#[inline(always)]
fn lane_starts<O: OpCounter>(
    c: &Coeffs,
    x0: i32,
    y: i32,
    wu: &mut [f32],
    wv: &mut [f32],
    q: &mut [f32],
    ops: &mut O,
) -> (f32, f32, f32) {
    let (ut, vt, ub) = row_constants(c, x0 as f32, y as f32, ops);
    for j in 0..wu.len() {
        let jf = j as f32;
        wu[j] = ut + c.a * jf;
        wv[j] = vt + c.d * jf;
        q[j] = ub + c.g * jf;
        ops.mul(3);
        ops.add(3);
    }
    let kf = wu.len() as f32;
    ops.mul(3);
    (kf * c.a, kf * c.d, kf * c.g)
}

#[inline]
fn k_stride_const<const K: usize, O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (mut wu, mut wv, mut q) = ([0.0f32; K], [0.0f32; K], [0.0f32; K]);
    let (ka, kd, kg) = lane_starts(c, x0, y, &mut wu, &mut wv, &mut q, ops);
    let mut chunks = out.chunks_exact_mut(K);
    for chunk in &mut chunks {
        for j in 0..K {
            let r = 1.0 / q[j];
            chunk[j] = Vec2::new(wu[j] * r, wv[j] * r);
            wu[j] += ka;
            wv[j] += kd;
            q[j] += kg;
        }
        ops.div(K as u32);
        ops.mul(2 * K as u32);
        ops.add(3 * K as u32);
    }
    for (j, o) in chunks.into_remainder().iter_mut().enumerate() {
        let r = 1.0 / q[j];
        *o = Vec2::new(wu[j] * r, wv[j] * r);
        ops.div(1);
        ops.mul(2);
    }
}

fn k_stride_dyn<O: OpCounter>(c: &Coeffs, k: usize, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let (mut wu, mut wv, mut q) = ([0.0f32; MAX_STRIDE], [0.0f32; MAX_STRIDE], [0.0f32; MAX_STRIDE]);
    let (ka, kd, kg) = lane_starts(c, x0, y, &mut wu[..k], &mut wv[..k], &mut q[..k], ops);
    for chunk in out.chunks_mut(k) {
        for (j, o) in chunk.iter_mut().enumerate() {
            let r = 1.0 / q[j];
            *o = Vec2::new(wu[j] * r, wv[j] * r);
            wu[j] += ka;
            wv[j] += kd;
            q[j] += kg;
            ops.div(1);
            ops.mul(2);
            ops.add(3);
        }
    }
}

/// Counter-directional: forward from the left end, backward from the right end.
#[inline]
pub fn two_way<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let len = out.len();
    if len == 0 {
        return;
    }
    let (mut lu, mut lv, mut lq) = row_constants(c, x0 as f32, y as f32, ops);
    let xr = (x0 as i64 + len as i64 - 1) as f32;
    let (mut ru, mut rv, mut rq) = row_constants(c, xr, y as f32, ops);
    let (left, right) = out.split_at_mut(len.div_ceil(2));
    let odd_middle = left.len() > right.len();
    // Pairs: one pixel from each end per iteration, two independent dependency chains.
    for (l, o) in left.iter_mut().zip(right.iter_mut().rev()) {
        let r = 1.0 / lq;
        *l = Vec2::new(lu * r, lv * r);
        lu += c.a;
        lv += c.d;
        lq += c.g;
        let r = 1.0 / rq;
        *o = Vec2::new(ru * r, rv * r);
        ru -= c.a;
        rv -= c.d;
        rq -= c.g;
        ops.div(2);
        ops.mul(4);
        ops.add(3);
        ops.sub(3);
    }
    if odd_middle {
        let r = 1.0 / lq;
        left[left.len() - 1] = Vec2::new(lu * r, lv * r);
        ops.div(1);
        ops.mul(2);
    }
}

/// Exact `(u, v)` and denominator at one pixel, by the direct form (for span end points).
#[inline(always)]
fn end_point<O: OpCounter>(c: &Coeffs, x: f32, y: f32, ops: &mut O) -> (Vec2, f32) {
    let q = c.g * x + c.h * y + c.i;
    let u = (c.a * x + c.b * y + c.c) / q;
    let v = (c.d * x + c.e * y + c.f) / q;
    ops.mul(6);
    ops.add(6);
    ops.div(2);
    (Vec2::new(u, v), q)
}

/// Affine interpolation between the exact end points.
#[inline]
pub fn affine<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let len = out.len();
    if len == 0 {
        return;
    }
    let (a, _) = end_point(c, x0 as f32, y as f32, ops);
    if len == 1 {
        out[0] = a;
        return;
    }
    let (b, _) = end_point(c, (x0 as i64 + len as i64 - 1) as f32, y as f32, ops);
    let inv = 1.0 / (len - 1) as f32;
    let d = (b - a) * inv;
    ops.div(1);
    ops.sub(2);
    ops.mul(2);
    let mut uv = a;
    for o in out.iter_mut() {
        *o = uv;
        uv += d;
        ops.add(2);
    }
}

/// The thesis's depth-coordinate method (2.32)/(2.33) along one span.
#[inline]
pub fn depth_coordinate<O: OpCounter>(c: &Coeffs, x0: i32, y: i32, out: &mut [Vec2], ops: &mut O) {
    let len = out.len();
    if len == 0 {
        return;
    }
    let (t1, q1) = end_point(c, x0 as f32, y as f32, ops);
    if len == 1 {
        out[0] = t1;
        return;
    }
    let (t2, q2) = end_point(c, (x0 as i64 + len as i64 - 1) as f32, y as f32, ops);
    // Depths up to one common factor: z ∝ 1/q on a plane.
    let (z1, z2) = (1.0 / q1, 1.0 / q2);
    let dz = z2 - z1;
    let dt = 1.0 / (len - 1) as f32;
    let duv = t2 - t1;
    ops.div(3);
    ops.sub(3);
    let mut t = 0.0f32;
    for o in out.iter_mut() {
        let w = z1 * t / (z2 - t * dz);
        *o = t1 + duv * w;
        t += dt;
        ops.mul(4);
        ops.sub(1);
        ops.add(3);
        ops.div(1);
    }
}
