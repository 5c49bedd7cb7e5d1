//! Batch evaluation over regular grids: rows, planes and volumes in one call.
//!
//! A grid is `origin + (i·step[0], j·step[1], k·step[2])` for `i < dims[0]` (fastest in
//! memory), `j < dims[1]`, `k < dims[2]`. The output slice is written in that order.
//!
//! Why this is fast: along a row only x changes, so for each octave the (y, z) part of the
//! work (two fades, four nested hashes, four bilinear weights) is done once per row, and the
//! eight corner dot products collapse, per lattice cell crossed, into four numbers
//! `(aₓ, a_c, bₓ, b_c)`; the face shared with the previous cell is reused, so crossing into
//! the next cell costs four hashes, not eight. Each sample then costs one fade and a handful
//! of multiply-adds: `n = A + fade(t)(B − A)` with `A = aₓt + a_c`, `B = bₓ(t − 1) + b_c`.
//! The row is done in two passes over structure-of-arrays scratch (each sample's cell and
//! fraction, branch-free), then per run of samples sharing a cell (a straight-line loop over
//! contiguous slices). Scratch is allocated once per row (2D) or slice (3D), never per
//! sample, and octaves are summed in a fixed order, so the results are identical for any
//! thread count. Rows with coordinates beyond 2³¹ or non-finite fall back to a per-sample loop
//! with the point API's semantics.
//!
//! 2D rows use the same scheme with two corners instead of four. 1D and 4D grids evaluate the
//! point API per sample. The batch result equals [`Fractal::sample`] up to f32 rounding (the
//! tests bound the difference by 2·10⁻⁵).

use rayon::prelude::*;

use crate::error::{NoiseError, Result};
use crate::fractal::{final_scale, salt, shape, Fractal, FractalKind};
use crate::perlin::{fade, gradient, split, TABLE_SIZE};
use crate::wrap::{NoWrap, Wrap};

/// Checks the grid and the output slice; returns the sample count.
fn check_grid<const N: usize>(
    origin: [f32; N],
    step: [f32; N],
    dims: [usize; N],
    len: usize,
) -> Result<usize> {
    for (a, (&o, &s)) in origin.iter().zip(step.iter()).enumerate() {
        if !o.is_finite() {
            return Err(NoiseError::Parameter {
                name: ["origin.x", "origin.y", "origin.z", "origin.w"][a],
                value: f64::from(o),
                reason: "must be finite",
            });
        }
        if !s.is_finite() {
            return Err(NoiseError::Parameter {
                name: ["step.x", "step.y", "step.z", "step.w"][a],
                value: f64::from(s),
                reason: "must be finite",
            });
        }
    }
    let mut count = 1usize;
    for &d in &dims {
        if d == 0 {
            return Err(NoiseError::Size { dims: dims.to_vec(), reason: "every extent must be positive" });
        }
        count = count.checked_mul(d).ok_or_else(|| NoiseError::Size {
            dims: dims.to_vec(),
            reason: "sample count overflows usize",
        })?;
    }
    if count > crate::MAX_SAMPLES {
        return Err(NoiseError::Size { dims: dims.to_vec(), reason: "more than 2^31 samples" });
    }
    if len != count {
        return Err(NoiseError::OutputLength { expected: count, got: len });
    }
    Ok(count)
}

/// Fills `out` with `fractal` sampled over an `N`-dimensional grid (N = 1..=4).
///
/// 2D and 3D grids take the row-hoisted fast path; 1D and 4D evaluate per sample.
/// Errors: non-finite origin or step, a zero or overflowing extent, or a wrong `out` length.
pub fn fill<const N: usize>(
    fractal: &Fractal,
    origin: [f32; N],
    step: [f32; N],
    dims: [usize; N],
    out: &mut [f32],
) -> Result<()> {
    const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
    check_grid(origin, step, dims, out.len())?;
    for (k, chunk) in out.chunks_mut(slab_len(dims)).enumerate() {
        fill_slab(fractal, origin, step, dims, k, chunk);
    }
    Ok(())
}

/// Like [`fill`] but splits the grid over rayon threads by its slowest axis (rows for 2D,
/// z-slices for 3D). The output is bit-identical to [`fill`]'s for any thread count.
pub fn fill_par<const N: usize>(
    fractal: &Fractal,
    origin: [f32; N],
    step: [f32; N],
    dims: [usize; N],
    out: &mut [f32],
) -> Result<()> {
    const { assert!(N >= 1 && N <= 4, "noise is defined for 1 to 4 dimensions") };
    check_grid(origin, step, dims, out.len())?;
    out.par_chunks_mut(slab_len(dims))
        .enumerate()
        .for_each(|(k, chunk)| fill_slab(fractal, origin, step, dims, k, chunk));
    Ok(())
}

/// Samples per slab: everything with the same last index (the whole grid in 1D).
fn slab_len<const N: usize>(dims: [usize; N]) -> usize {
    if N == 1 {
        dims[0]
    } else {
        dims[..N - 1].iter().product()
    }
}

/// Evaluates slab `last` of the grid into `out`, on the fast path where there is one.
fn fill_slab<const N: usize>(
    fractal: &Fractal,
    origin: [f32; N],
    step: [f32; N],
    dims: [usize; N],
    last: usize,
    out: &mut [f32],
) {
    match N {
        2 => {
            let y = origin[1 % N] + last as f32 * step[1 % N];
            row2(fractal, origin[0], step[0], y, out);
        }
        3 => {
            let o = [origin[0], origin[1 % N], origin[2 % N]];
            let s = [step[0], step[1 % N], step[2 % N]];
            volume3(fractal, o, s, [dims[0], dims[1 % N]], last, out);
        }
        _ => fill_generic_slab(fractal, origin, step, dims, last, out),
    }
}

/// One slab (all samples with last index `last`) evaluated per sample.
fn fill_generic_slab<const N: usize>(
    fractal: &Fractal,
    origin: [f32; N],
    step: [f32; N],
    dims: [usize; N],
    last: usize,
    out: &mut [f32],
) {
    for (flat, v) in out.iter_mut().enumerate() {
        let mut p = [0.0f32; N];
        if N == 1 {
            p[0] = origin[0] + flat as f32 * step[0];
        } else {
            let mut rest = flat;
            for a in 0..N - 1 {
                let i = rest % dims[a];
                rest /= dims[a];
                p[a] = origin[a] + i as f32 * step[a];
            }
            p[N - 1] = origin[N - 1] + last as f32 * step[N - 1];
        }
        *v = fractal.sample(p);
    }
}

/// Evaluates one row (fixed `y`) of a 2D grid into `out`.
fn row2(fractal: &Fractal, ox: f32, sx: f32, y: f32, out: &mut [f32]) {
    out.fill(0.0);
    let n = out.len();
    let sc = &mut Scratch { t: vec![0.0; n], cell: vec![0; n] };
    match fractal.kind {
        FractalKind::Thesis => octaves2::<0>(fractal, ox, sx, y, out, sc),
        FractalKind::Fbm => octaves2::<1>(fractal, ox, sx, y, out, sc),
        FractalKind::Turbulence => octaves2::<2>(fractal, ox, sx, y, out, sc),
        FractalKind::Ridged => octaves2::<3>(fractal, ox, sx, y, out, sc),
    }
    let s = final_scale(fractal.kind, &fractal.params);
    if s != 1.0 {
        out.iter_mut().for_each(|v| *v *= s);
    }
}

/// All octaves of one 2D row, accumulated into `acc`.
#[inline(always)]
fn octaves2<const KIND: u8>(fractal: &Fractal, ox: f32, sx: f32, y: f32, acc: &mut [f32], sc: &mut Scratch) {
    let kind = kind_of(KIND);
    let perm = &fractal.perlin.perm;
    for oct in 0..fractal.params.octaves() as usize {
        let f = fractal.params.freq(oct);
        let a = fractal.params.amp(oct);
        let s = salt(kind, oct);
        match fractal.params.wrap(oct) {
            None => octave_row2::<KIND, _>(perm, s, NoWrap, ox, sx, f, y * f, a, acc, sc),
            Some(w) => octave_row2::<KIND, _>(perm, s, w, ox, sx, f, y * f, a, acc, sc),
        }
    }
}

/// One octave of 2D noise along a row, shaped, scaled by `amp` and added to `acc`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn octave_row2<const KIND: u8, W: Wrap>(
    perm: &[[u8; TABLE_SIZE]; 4],
    salt: u8,
    wrap: W,
    ox: f32,
    sx: f32,
    f: f32,
    y: f32,
    amp: f32,
    acc: &mut [f32],
    sc: &mut Scratch,
) {
    let kind = kind_of(KIND);
    if !y.is_finite() {
        let v = amp * shape(kind, 0.0);
        acc.iter_mut().for_each(|o| *o += v);
        return;
    }
    let scale = crate::perlin::scale::<2>();
    let (yi, ty) = split(y);
    let v = fade(ty);
    let y0 = (wrap.wrap(1, yi) as u8).wrapping_add(salt);
    let y1 = (wrap.wrap(1, yi.wrapping_add(1)) as u8).wrapping_add(salt);
    let (px, py) = (&perm[0], &perm[1]);
    let corners = [(py[usize::from(y0)], 1.0 - v, ty), (py[usize::from(y1)], v, ty - 1.0)];
    let face = |x: i32| {
        let xw = wrap.wrap(0, x) as u8;
        let (mut gx, mut gc) = (0.0f32, 0.0f32);
        for &(h, wy, dy) in &corners {
            let g = gradient::<2>(px[usize::from(h.wrapping_add(xw))]);
            gx += wy * g[0];
            gc += wy * g[1] * dy;
        }
        (gx, gc)
    };
    if !two_pass_row::<KIND>(ox, sx, f, amp, scale, acc, sc, &face) {
        walk_row(kind, ox, sx, f, amp, scale, acc, face);
    }
}

/// Evaluates slice `k` (all x and y for one z) of a 3D grid into `out` (`nx·ny` samples).
fn volume3(
    fractal: &Fractal,
    origin: [f32; 3],
    step: [f32; 3],
    dims_xy: [usize; 2],
    k: usize,
    out: &mut [f32],
) {
    let nx = dims_xy[0];
    let z = origin[2] + k as f32 * step[2];
    // One scratch row per slice, reused by every row and octave.
    let mut scratch = Scratch { t: vec![0.0; nx], cell: vec![0; nx] };
    let sc = &mut scratch;
    for (j, row) in out.chunks_mut(nx).enumerate() {
        let y = origin[1] + j as f32 * step[1];
        row.fill(0.0);
        match fractal.kind {
            FractalKind::Thesis => rows3::<0>(fractal, origin[0], step[0], y, z, row, sc),
            FractalKind::Fbm => rows3::<1>(fractal, origin[0], step[0], y, z, row, sc),
            FractalKind::Turbulence => rows3::<2>(fractal, origin[0], step[0], y, z, row, sc),
            FractalKind::Ridged => rows3::<3>(fractal, origin[0], step[0], y, z, row, sc),
        }
        let s = final_scale(fractal.kind, &fractal.params);
        if s != 1.0 {
            row.iter_mut().for_each(|v| *v *= s);
        }
    }
}

/// The kind as a const parameter, so the shaping is resolved at compile time.
const fn kind_of(k: u8) -> FractalKind {
    match k {
        0 => FractalKind::Thesis,
        1 => FractalKind::Fbm,
        2 => FractalKind::Turbulence,
        _ => FractalKind::Ridged,
    }
}

/// Per-row structure-of-arrays scratch: each sample's fraction and lattice cell along x.
struct Scratch {
    t: Vec<f32>,
    cell: Vec<i32>,
}

/// All octaves of one row, accumulated into `acc`.
#[inline(always)]
fn rows3<const KIND: u8>(
    fractal: &Fractal,
    ox: f32,
    sx: f32,
    y: f32,
    z: f32,
    acc: &mut [f32],
    sc: &mut Scratch,
) {
    let kind = kind_of(KIND);
    let perm = &fractal.perlin.perm;
    for oct in 0..fractal.params.octaves() as usize {
        let f = fractal.params.freq(oct);
        let a = fractal.params.amp(oct);
        let s = salt(kind, oct);
        match fractal.params.wrap(oct) {
            None => row3::<KIND, _>(perm, s, NoWrap, ox, sx, f, y * f, z * f, a, acc, sc),
            Some(w) => row3::<KIND, _>(perm, s, w, ox, sx, f, y * f, z * f, a, acc, sc),
        }
    }
}

/// One octave of 3D noise along a row, shaped, scaled by `amp` and added to `acc`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn row3<const KIND: u8, W: Wrap>(
    perm: &[[u8; TABLE_SIZE]; 4],
    salt: u8,
    wrap: W,
    ox: f32,
    sx: f32,
    f: f32,
    y: f32,
    z: f32,
    amp: f32,
    acc: &mut [f32],
    sc: &mut Scratch,
) {
    let kind = kind_of(KIND);
    if !(y.is_finite() && z.is_finite()) {
        let v = amp * shape(kind, 0.0);
        acc.iter_mut().for_each(|o| *o += v);
        return;
    }
    let (yi, ty) = split(y);
    let (zi, tz) = split(z);
    let (v, w) = (fade(ty), fade(tz));
    let (y0, y1) = (wrap.wrap(1, yi) as u8, wrap.wrap(1, yi.wrapping_add(1)) as u8);
    let z0 = (wrap.wrap(2, zi) as u8).wrapping_add(salt);
    let z1 = (wrap.wrap(2, zi.wrapping_add(1)) as u8).wrapping_add(salt);
    let (px, py, pz) = (&perm[0], &perm[1], &perm[2]);
    let hz0 = pz[usize::from(z0)];
    let hz1 = pz[usize::from(z1)];
    // (y, z) corners: hash prefix, bilinear weight, and offsets from the corner.
    let corners = [
        (py[usize::from(hz0.wrapping_add(y0))], (1.0 - v) * (1.0 - w), ty, tz),
        (py[usize::from(hz0.wrapping_add(y1))], v * (1.0 - w), ty - 1.0, tz),
        (py[usize::from(hz1.wrapping_add(y0))], (1.0 - v) * w, ty, tz - 1.0),
        (py[usize::from(hz1.wrapping_add(y1))], v * w, ty - 1.0, tz - 1.0),
    ];
    // The coefficients of the lattice face at x-index `x`: Σ over the (y, z) corners of the
    // weight times the gradient's x component, and times its (y, z) dot product.
    let face = |x: i32| {
        let xw = wrap.wrap(0, x) as u8;
        let (mut gx, mut gc) = (0.0f32, 0.0f32);
        for &(h, wyz, dy, dz) in &corners {
            let g = gradient::<3>(px[usize::from(h.wrapping_add(xw))]);
            gx += wyz * g[0];
            gc += wyz * (g[1] * dy + g[2] * dz);
        }
        (gx, gc)
    };
    if !two_pass_row::<KIND>(ox, sx, f, amp, 1.0, acc, sc, &face) {
        walk_row(kind, ox, sx, f, amp, 1.0, acc, face);
    }
}

/// The per-sample fallback of [`two_pass_row`] for rows whose coordinates leave the range
/// where its branch-free cell split is exact: the same face coefficients and face reuse, one
/// sample at a time with the exact `split`; non-finite samples contribute the shape of 0.
#[allow(clippy::too_many_arguments)]
fn walk_row(
    kind: FractalKind,
    ox: f32,
    sx: f32,
    f: f32,
    amp: f32,
    scale: f32,
    acc: &mut [f32],
    face: impl Fn(i32) -> (f32, f32),
) {
    let (mut cell, mut have_cell) = (0i32, false);
    let (mut ax, mut ac, mut bx, mut bc) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for (i, o) in acc.iter_mut().enumerate() {
        let x = (ox + i as f32 * sx) * f;
        if !x.is_finite() {
            *o += amp * shape(kind, 0.0);
            continue;
        }
        let (xi, t) = split(x);
        if !have_cell || xi != cell {
            // The face shared with the previous cell keeps its coefficients: stepping right,
            // the old B face becomes the new A face (and vice versa stepping left).
            if have_cell && xi == cell.wrapping_add(1) {
                (ax, ac) = (bx, bc);
                (bx, bc) = face(xi.wrapping_add(1));
            } else if have_cell && xi == cell.wrapping_sub(1) {
                (bx, bc) = (ax, ac);
                (ax, ac) = face(xi);
            } else {
                (ax, ac) = face(xi);
                (bx, bc) = face(xi.wrapping_add(1));
            }
            cell = xi;
            have_cell = true;
        }
        let a = ax * t + ac;
        let b = bx * (t - 1.0) + bc;
        let n = (a + fade(t) * (b - a)) * scale;
        *o += amp * shape(kind, n);
    }
}

/// The vectorising row kernel shared by 2D and 3D: `face(x)` gives the coefficients of the
/// lattice face at x-index `x`; the octave's shaped, scaled noise is added to `acc`. Returns
/// `false` (having done nothing) when some coordinate is beyond 2^31 or not finite, so that the
/// per-sample [`walk_row`] handles the row with `split`'s exact semantics.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn two_pass_row<const KIND: u8>(
    ox: f32,
    sx: f32,
    f: f32,
    amp: f32,
    scale: f32,
    acc: &mut [f32],
    sc: &mut Scratch,
    face: impl Fn(i32) -> (f32, f32),
) -> bool {
    let kind = kind_of(KIND);
    // Pass 1 (branch-free, vectorises): every sample's cell and fraction; this equals
    // `split` for |x| < 2^31, which `in_range` checks.
    let n = acc.len();
    let (ts, cells) = (&mut sc.t[..n], &mut sc.cell[..n]);
    let mut in_range = true;
    for (i, (t, c)) in ts.iter_mut().zip(cells.iter_mut()).enumerate() {
        let x = (ox + i as f32 * sx) * f;
        in_range &= x.abs() < 2_147_483_520.0;
        let xi = x as i32;
        let xi = xi.wrapping_sub(i32::from(xi as f32 > x)); // wraps only out of range
        *c = xi;
        *t = x - xi as f32;
    }
    if !in_range {
        return false;
    }
    // Pass 2: a run of samples in one cell shares four coefficients, and the face shared
    // with the previous cell keeps its coefficients; the inner loop is straight-line
    // arithmetic over contiguous slices.
    let (mut ax, mut ac, mut bx, mut bc) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    let (mut prev, mut have_prev) = (0i32, false);
    let mut i = 0;
    while i < n {
        let c = cells[i];
        let mut j = i + 1;
        while j < n && cells[j] == c {
            j += 1;
        }
        if have_prev && c == prev.wrapping_add(1) {
            (ax, ac) = (bx, bc);
            (bx, bc) = face(c.wrapping_add(1));
        } else if have_prev && c == prev.wrapping_sub(1) {
            (bx, bc) = (ax, ac);
            (ax, ac) = face(c);
        } else if !have_prev || c != prev {
            (ax, ac) = face(c);
            (bx, bc) = face(c.wrapping_add(1));
        }
        (prev, have_prev) = (c, true);
        for (o, &t) in acc[i..j].iter_mut().zip(&ts[i..j]) {
            let a = ax * t + ac;
            let b = bx * (t - 1.0) + bc;
            let v = (a + fade(t) * (b - a)) * scale;
            *o += amp * shape(kind, v);
        }
        i = j;
    }
    true
}
