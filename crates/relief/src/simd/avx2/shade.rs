//! The vector kernel of the fused frame's shading ([`crate::fused::lanes`]): eight pixels
//! per group in AVX2 lanes (one group per call, or several with their steps interleaved),
//! each bilinear cell's texels fetched as two 8-byte loads per lane from the texture's padded
//! copy, every arithmetic step in the scalar twin's order (no fused multiply-add), so that the
//! pixels are bit-identical to the scalar twin's (`simd::scalar::shade`).

use super::math::{finite, log2};
use crate::fused::lanes::{ShadeConsts, ShadeLanes, LANES};
use crate::fused::texture8::{Texture8, LINEAR_STEP, MAX_LEVELS, WIDE_BITS, WIDE_MAX};
use crate::trace::Shading;
use renderlab_core::srgb8::{ENCODE_MAX_BITS, ENCODE_MIN_BITS};
use std::arch::x86_64::*;

type V = __m256;
type I = __m256i;

#[inline]
#[target_feature(enable = "avx2")]
unsafe fn splat(x: f32) -> V {
    _mm256_set1_ps(x)
}

/// Non-finite → 0, else clamped to ±10⁷.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn sanitize(v: V) -> V {
    let finite = _mm256_cmp_ps::<_CMP_EQ_OQ>(_mm256_sub_ps(v, v), _mm256_setzero_ps());
    let c = _mm256_min_ps(_mm256_max_ps(v, splat(-1.0e7)), splat(1.0e7));
    _mm256_and_ps(c, finite)
}

#[inline]
#[target_feature(enable = "avx2")]
unsafe fn ld(a: &[f32; LANES]) -> V {
    _mm256_load_ps(a.as_ptr())
}

/// Level of detail in `tex` of the footprints `d` (∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y).
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn lod(d: &[V; 4], tex: &Texture8) -> V {
    let top = splat((tex.level_count() - 1) as f32);
    let (w, h) = (splat(tex.widths_f[0]), splat(tex.heights_f[0]));
    let (ax, ay) = (_mm256_mul_ps(d[0], w), _mm256_mul_ps(d[1], h));
    let (bx, by) = (_mm256_mul_ps(d[2], w), _mm256_mul_ps(d[3], h));
    let a = _mm256_add_ps(_mm256_mul_ps(ax, ax), _mm256_mul_ps(ay, ay));
    let b = _mm256_add_ps(_mm256_mul_ps(bx, bx), _mm256_mul_ps(by, by));
    let ok = _mm256_and_ps(finite(a), finite(b));
    let rho2 = _mm256_max_ps(_mm256_max_ps(a, b), splat(1e-30));
    let l = _mm256_min_ps(_mm256_max_ps(_mm256_mul_ps(splat(0.5), log2(rho2)), _mm256_setzero_ps()), top);
    _mm256_blendv_ps(top, l, ok)
}

/// A bilinear cell per lane: the index in [`Texture8::wide`] of its top-left texel, the
/// padded row length (the bottom-left texel is that far on), and the weights.
type Cell = (I, I, V, V);

/// The bilinear cells of `(u, v)` in level `k` (per lane) of a texture whose level 0 is
/// `w0 × h0` texels: the scalar twin's `taps`, on the padded copy, where the right and bottom
/// neighbours need no wrap. A level's side is `max(side₀ >> k, 1)`, as the pyramid halves it.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn taps(tex: &Texture8, k: I, u: V, v: V) -> Cell {
    let one = _mm256_set1_epi32(1);
    let w = _mm256_max_epi32(_mm256_srlv_epi32(_mm256_set1_epi32(tex.widths[0]), k), one);
    let h = _mm256_max_epi32(_mm256_srlv_epi32(_mm256_set1_epi32(tex.heights[0]), k), one);
    // The level's start from the 16-entry table by two in-register lookups (`k` < 16).
    const _: () = assert!(MAX_LEVELS == 16, "two eight-lane lookups cover the offset table");
    let table = tex.wide_offsets.as_ptr() as *const I;
    let (first, second) = (_mm256_loadu_si256(table), _mm256_loadu_si256(table.add(1)));
    let off = _mm256_blendv_epi8(
        _mm256_permutevar8x32_epi32(first, k),
        _mm256_permutevar8x32_epi32(second, k),
        _mm256_cmpgt_epi32(k, _mm256_set1_epi32(7)),
    );
    let half = splat(0.5);
    let x = _mm256_sub_ps(_mm256_mul_ps(_mm256_sub_ps(u, _mm256_floor_ps(u)), _mm256_cvtepi32_ps(w)), half);
    let y = _mm256_sub_ps(_mm256_mul_ps(_mm256_sub_ps(v, _mm256_floor_ps(v)), _mm256_cvtepi32_ps(h)), half);
    let (xf, yf) = (_mm256_floor_ps(x), _mm256_floor_ps(y));
    let (xi, yi) = (_mm256_cvttps_epi32(xf), _mm256_cvttps_epi32(yf));
    let zero = _mm256_setzero_si256();
    let x0 = _mm256_blendv_epi8(xi, _mm256_sub_epi32(w, one), _mm256_cmpgt_epi32(zero, xi));
    let y0 = _mm256_blendv_epi8(yi, _mm256_sub_epi32(h, one), _mm256_cmpgt_epi32(zero, yi));
    let stride = _mm256_add_epi32(w, one);
    let idx = _mm256_add_epi32(_mm256_add_epi32(off, _mm256_mullo_epi32(y0, stride)), x0);
    (idx, stride, _mm256_sub_ps(x, xf), _mm256_sub_ps(y, yf))
}

/// Entries `i` and `i + 1` of `wide` (one 8-byte load) for lanes `a` and `b` in that order.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn pair_of_lanes(wide: *const u32, ix: &[i32; LANES], a: usize, b: usize) -> __m128i {
    // SAFETY (caller): each index is a texel of a level's unpadded grid, so the entry after
    // it (the padded column at worst) is inside `wide`.
    let lo = _mm_castsi128_pd(_mm_loadl_epi64(wide.add(ix[a] as usize) as *const __m128i));
    _mm_castpd_si128(_mm_loadh_pd(lo, wide.add(ix[b] as usize) as *const f64))
}

/// The channels of the left and right texels of the eight lanes' rows starting at `idx`: one
/// 8-byte load per lane (the two neighbours), the lanes' left and right entries split apart,
/// then each entry's three fields, as the filter reads them (squared for an sRGB texture,
/// `SRGB`).
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn row<const SRGB: bool>(wide: *const u32, idx: I) -> ([V; 3], [V; 3]) {
    let mut ix = [0i32; LANES];
    _mm256_storeu_si256(ix.as_mut_ptr() as *mut I, idx);
    // Element 2j of `q[0]` is lane j's left entry, element 2j + 1 its right one, for lanes
    // 0, 1 | 4, 5; `q[1]` the same for lanes 2, 3 | 6, 7.
    // No closures here: a closure is compiled without this function's target features.
    let q0 = _mm256_inserti128_si256::<1>(
        _mm256_castsi128_si256(pair_of_lanes(wide, &ix, 0, 1)),
        pair_of_lanes(wide, &ix, 4, 5),
    );
    let q1 = _mm256_inserti128_si256::<1>(
        _mm256_castsi128_si256(pair_of_lanes(wide, &ix, 2, 3)),
        pair_of_lanes(wide, &ix, 6, 7),
    );
    let (q0, q1) = (_mm256_castsi256_ps(q0), _mm256_castsi256_ps(q1));
    let l = _mm256_castps_si256(_mm256_shuffle_ps::<0b10_00_10_00>(q0, q1));
    let r = _mm256_castps_si256(_mm256_shuffle_ps::<0b11_01_11_01>(q0, q1));
    (fields::<SRGB>(l), fields::<SRGB>(r))
}

/// The three [`WIDE_BITS`]-bit fields of each lane's entry as floats, squared for `SRGB`.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn fields<const SRGB: bool>(t: I) -> [V; 3] {
    let mask = _mm256_set1_epi32(WIDE_MAX as i32);
    const _: () = assert!(WIDE_BITS == 10, "the shifts below");
    let c = [
        _mm256_and_si256(t, mask),
        _mm256_and_si256(_mm256_srli_epi32::<10>(t), mask),
        _mm256_and_si256(_mm256_srli_epi32::<20>(t), mask),
    ];
    let mut out = [_mm256_setzero_ps(); 3];
    for (o, c) in out.iter_mut().zip(c) {
        let f = _mm256_cvtepi32_ps(c);
        *o = if SRGB { _mm256_mul_ps(f, f) } else { f };
    }
    out
}

/// Bilinear RGB from `tex` at the cells `(idx, stride, fx, fy)`, in the units of
/// [`Texture8::wide`].
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn bilinear<const SRGB: bool>(tex: &Texture8, &(idx, stride, fx, fy): &Cell) -> [V; 3] {
    let wide = tex.wide().as_ptr();
    let (t00, t10) = row::<SRGB>(wide, idx);
    let (t01, t11) = row::<SRGB>(wide, _mm256_add_epi32(idx, stride));
    let mut out = [_mm256_setzero_ps(); 3];
    for (c, o) in out.iter_mut().enumerate() {
        let (a, b, cc, d) = (t00[c], t10[c], t01[c], t11[c]);
        let top = _mm256_add_ps(a, _mm256_mul_ps(_mm256_sub_ps(b, a), fx));
        let bottom = _mm256_add_ps(cc, _mm256_mul_ps(_mm256_sub_ps(d, cc), fx));
        *o = _mm256_add_ps(top, _mm256_mul_ps(_mm256_sub_ps(bottom, top), fy));
    }
    out
}

/// How many pixel rows below its own a group prefetches texels for ([`prefetch_below`]).
const AHEAD: f32 = 3.0;

/// Asks the cache for the texels that the pixels [`AHEAD`] rows below the group's first and
/// last lanes will read from the first level, `(u, v) + AHEAD · ∂(u, v)/∂y` (the frame
/// shades a band's rows top to bottom): where the view is oblique a row's cells lie in other
/// texture rows than the row above read, and their first loads would otherwise wait on
/// memory. A hint only: no value changes.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn prefetch_below(k: &ShadeConsts, lit: bool, p: &ShadeLanes, level: I, u: V, v: V) {
    let ahead = splat(AHEAD);
    let pu = sanitize(_mm256_add_ps(u, _mm256_mul_ps(ld(&p.dudy), ahead)));
    let pv = sanitize(_mm256_add_ps(v, _mm256_mul_ps(ld(&p.dvdy), ahead)));
    let (idx, ..) = taps(k.albedo, level, pu, pv);
    let (first, last) = (_mm256_cvtsi256_si32(idx) as usize, _mm256_extract_epi32::<7>(idx) as usize);
    // `wrapping_add`: the addresses are only hints (they are inside the copies, as every
    // cell's are, but a prefetch needs no such promise).
    let a = k.albedo.wide().as_ptr();
    _mm_prefetch::<_MM_HINT_T0>(a.wrapping_add(first) as *const i8);
    _mm_prefetch::<_MM_HINT_T0>(a.wrapping_add(last) as *const i8);
    if lit {
        let n = k.normal.wide().as_ptr();
        _mm_prefetch::<_MM_HINT_T0>(n.wrapping_add(first) as *const i8);
        _mm_prefetch::<_MM_HINT_T0>(n.wrapping_add(last) as *const i8);
    }
}

/// The two levels around `l` (the upper clamped to the last) and the blend weight.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn levels(tex: &Texture8, l: V) -> (I, I, V) {
    let lf = _mm256_floor_ps(l);
    let k0 = _mm256_cvttps_epi32(lf);
    let k1 = _mm256_min_epi32(
        _mm256_add_epi32(k0, _mm256_set1_epi32(1)),
        _mm256_set1_epi32(tex.level_count() as i32 - 1),
    );
    (k0, k1, _mm256_sub_ps(l, lf))
}

#[inline]
#[target_feature(enable = "avx2")]
unsafe fn blend(s0: [V; 3], s1: [V; 3], t: V) -> [V; 3] {
    let mut out = s0;
    for (o, (a, b)) in out.iter_mut().zip(s0.iter().zip(&s1)) {
        *o = _mm256_add_ps(*a, _mm256_mul_ps(_mm256_sub_ps(*b, *a), t));
    }
    out
}

/// Whether no lane needs the second level: every blend weight is zero (magnified, or at the
/// last level). The blend then gives the first level's value bit for bit — `s0 + (s1 − s0)·0`
/// is `s0` for the finite, non-negative filtered values — so the second level's fetches are
/// skipped without changing a pixel.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn one_level(t: V) -> bool {
    _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_EQ_OQ>(t, _mm256_setzero_ps())) == 0xff
}

/// Trilinear RGB at levels of detail `l`, in the units of the padded copy.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn trilinear<const SRGB: bool>(tex: &Texture8, u: V, v: V, l: V) -> [V; 3] {
    let (k0, k1, t) = levels(tex, l);
    let s0 = bilinear::<SRGB>(tex, &taps(tex, k0, u, v));
    if one_level(t) {
        return s0;
    }
    let s1 = bilinear::<SRGB>(tex, &taps(tex, k1, u, v));
    blend(s0, s1, t)
}

/// Trilinear lookups of two textures with the same pyramid shape at the same point: the
/// level of detail and the taps are computed once.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn trilinear_pair(a: &Texture8, b: &Texture8, u: V, v: V, l: V) -> ([V; 3], [V; 3]) {
    let (k0, k1, t) = levels(a, l);
    let t0 = taps(a, k0, u, v);
    let (a0, b0) = (bilinear::<true>(a, &t0), bilinear::<false>(b, &t0));
    if one_level(t) {
        return (a0, b0);
    }
    let t1 = taps(a, k1, u, v);
    (blend(a0, bilinear::<true>(a, &t1), t), blend(b0, bilinear::<false>(b, &t1), t))
}

/// `c · s` for each channel.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn scaled(c: [V; 3], s: f32) -> [V; 3] {
    let s = splat(s);
    [_mm256_mul_ps(c[0], s), _mm256_mul_ps(c[1], s), _mm256_mul_ps(c[2], s)]
}

#[inline]
#[target_feature(enable = "avx2")]
unsafe fn dot(a: &[V; 3], b: &[V; 3]) -> V {
    _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(a[0], b[0]), _mm256_mul_ps(a[1], b[1])),
        _mm256_mul_ps(a[2], b[2]),
    )
}

/// `v · (1/|v|)` where that factor is finite and positive, `fallback` elsewhere.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn normalized(v: [V; 3], fallback: [V; 3]) -> [V; 3] {
    let r = _mm256_div_ps(splat(1.0), _mm256_sqrt_ps(dot(&v, &v)));
    let ok = _mm256_and_ps(finite(r), _mm256_cmp_ps::<_CMP_GT_OQ>(r, _mm256_setzero_ps()));
    let mut out = fallback;
    for (o, (f, c)) in out.iter_mut().zip(fallback.iter().zip(&v)) {
        *o = _mm256_blendv_ps(*f, _mm256_mul_ps(*c, r), ok);
    }
    out
}

#[inline]
#[target_feature(enable = "avx2")]
unsafe fn encode(x: V, table: &[u32]) -> I {
    let x = _mm256_min_ps(
        _mm256_max_ps(x, splat(f32::from_bits(ENCODE_MIN_BITS))),
        splat(f32::from_bits(ENCODE_MAX_BITS)),
    );
    let bits = _mm256_castps_si256(x);
    let idx = _mm256_srli_epi32::<20>(_mm256_sub_epi32(bits, _mm256_set1_epi32(ENCODE_MIN_BITS as i32)));
    let entry = _mm256_i32gather_epi32::<4>(table.as_ptr() as *const i32, idx);
    let t = _mm256_and_si256(_mm256_srli_epi32::<12>(bits), _mm256_set1_epi32(0xff));
    let bias = _mm256_slli_epi32::<9>(_mm256_srli_epi32::<16>(entry));
    let slope = _mm256_and_si256(entry, _mm256_set1_epi32(0xffff));
    _mm256_srli_epi32::<16>(_mm256_add_epi32(bias, _mm256_mullo_epi32(slope, t)))
}

/// The thesis's light on eight pixels of `p`: `albedo` (linear) lit with the filtered normal
/// map's values `nu` (codes).
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn light(albedo: [V; 3], nu: [V; 3], p: &ShadeLanes, k: &ShadeConsts) -> [V; 3] {
    let zero = _mm256_setzero_ps();
    let mut n = nu;
    for c in &mut n {
        *c = _mm256_sub_ps(_mm256_mul_ps(*c, splat(2.0 / 255.0)), splat(1.0));
    }
    let n = normalized(n, [zero, zero, splat(1.0)]);
    let l = [ld(&p.lx), ld(&p.ly), ld(&p.lz)];
    let diff = _mm256_max_ps(dot(&n, &l), zero);
    let h = [_mm256_add_ps(l[0], ld(&p.vx)), _mm256_add_ps(l[1], ld(&p.vy)), _mm256_add_ps(l[2], ld(&p.vz))];
    let h = normalized(h, [zero; 3]);
    let nh = _mm256_max_ps(dot(&n, &h), zero);
    let powed = match k.whole_exponent() {
        Some(mut e) => {
            let (mut result, mut base) = (splat(1.0), nh);
            while e > 0 {
                if e & 1 == 1 {
                    result = _mm256_mul_ps(result, base);
                }
                base = _mm256_mul_ps(base, base);
                e >>= 1;
            }
            result
        }
        None => {
            let mut lanes = [0.0f32; LANES];
            _mm256_storeu_ps(lanes.as_mut_ptr(), nh);
            for x in &mut lanes {
                *x = x.powf(k.exponent);
            }
            _mm256_loadu_ps(lanes.as_ptr())
        }
    };
    let spec = _mm256_mul_ps(powed, splat(k.strength));
    let facing = _mm256_and_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(l[2], zero), ld(&p.shadow));
    let ambient = splat(k.ambient);
    let mut lit = albedo;
    for c in &mut lit {
        *c = _mm256_add_ps(
            _mm256_mul_ps(*c, ambient),
            _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(*c, diff), spec), facing),
        );
    }
    lit
}

/// Encodes `color` into `out` (RGBA8, alpha 255).
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn store(color: [V; 3], k: &ShadeConsts, out: &mut [u32; LANES]) {
    let r = encode(color[0], k.encode);
    let g = encode(color[1], k.encode);
    let b = encode(color[2], k.encode);
    let rgba = _mm256_or_si256(
        _mm256_or_si256(r, _mm256_slli_epi32::<8>(g)),
        _mm256_or_si256(_mm256_slli_epi32::<16>(b), _mm256_set1_epi32(0xff00_0000u32 as i32)),
    );
    _mm256_storeu_si256(out.as_mut_ptr() as *mut I, rgba);
}

/// Shades the eight lanes of `p` into `out` (RGBA8, alpha 255).
///
/// # Safety
///
/// The CPU must support AVX2; `k`'s textures must be well formed (as
/// [`Texture8::from_texture`] builds them).
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn shade(p: &ShadeLanes, k: &ShadeConsts, out: &mut [u32; LANES]) {
    let (u, v) = (sanitize(ld(&p.u)), sanitize(ld(&p.v)));
    let d = [ld(&p.dudx), ld(&p.dvdx), ld(&p.dudy), ld(&p.dvdy)];
    let la = lod(&d, k.albedo);
    let color = match k.shading {
        Shading::Unlit => scaled(trilinear::<true>(k.albedo, u, v, la), LINEAR_STEP),
        Shading::Lit | Shading::LitShadowed => {
            let (albedo, nu) = if k.albedo.same_shape(k.normal) {
                trilinear_pair(k.albedo, k.normal, u, v, la)
            } else {
                (trilinear::<true>(k.albedo, u, v, la), trilinear::<false>(k.normal, u, v, lod(&d, k.normal)))
            };
            light(scaled(albedo, LINEAR_STEP), nu, p, k)
        }
    };
    store(color, k, out);
}

/// [`shade`] for `G` groups of eight pixels, `p[g]` into `out[g]`, their steps interleaved
/// (and each minified group's texels a few rows below prefetched, [`prefetch_below`]):
/// each group's work is one long chain of dependent steps (level of detail, addresses, loads,
/// filter, normalisation, encoding), and independent chains side by side keep the vector
/// units busy while each waits. The same pixels as `G` calls of [`shade`] (a group whose blend
/// weights are all zero blends in its second level with weight 0, which gives the first
/// level's value bit for bit; see [`one_level`]).
///
/// # Safety
///
/// As [`shade`].
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn shade_groups<const G: usize>(
    p: [&ShadeLanes; G],
    k: &ShadeConsts,
    out: [&mut [u32; LANES]; G],
) {
    let lit = !matches!(k.shading, Shading::Unlit);
    if lit && !k.albedo.same_shape(k.normal) {
        for (q, o) in p.into_iter().zip(out) {
            shade(q, k, o);
        }
        return;
    }
    let zero = _mm256_setzero_ps();
    let (mut u, mut v, mut t) = ([zero; G], [zero; G], [zero; G]);
    let mut k0 = [_mm256_setzero_si256(); G];
    let mut k1 = k0;
    for g in 0..G {
        let q = p[g];
        (u[g], v[g]) = (sanitize(ld(&q.u)), sanitize(ld(&q.v)));
        let l = lod(&[ld(&q.dudx), ld(&q.dvdx), ld(&q.dudy), ld(&q.dvdy)], k.albedo);
        (k0[g], k1[g], t[g]) = levels(k.albedo, l);
    }
    for g in 0..G {
        // Minified groups only: a magnified view reads few texels per row, already cached.
        if !one_level(t[g]) {
            prefetch_below(k, lit, p[g], k0[g], u[g], v[g]);
        }
    }
    let (mut a, mut n) = ([[zero; 3]; G], [[zero; 3]; G]);
    for g in 0..G {
        let c = taps(k.albedo, k0[g], u[g], v[g]);
        a[g] = bilinear::<true>(k.albedo, &c);
        if lit {
            n[g] = bilinear::<false>(k.normal, &c);
        }
    }
    if !t.iter().all(|&t| one_level(t)) {
        for g in 0..G {
            let c = taps(k.albedo, k1[g], u[g], v[g]);
            a[g] = blend(a[g], bilinear::<true>(k.albedo, &c), t[g]);
            if lit {
                n[g] = blend(n[g], bilinear::<false>(k.normal, &c), t[g]);
            }
        }
    }
    for (g, o) in out.into_iter().enumerate() {
        let albedo = scaled(a[g], LINEAR_STEP);
        let color = if lit { light(albedo, n[g], p[g], k) } else { albedo };
        store(color, k, o);
    }
}
