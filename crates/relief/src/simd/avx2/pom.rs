//! The vector kernel of POM on the packed map ([`crate::march::pom_lanes`], scalar twin
//! `simd::scalar::pom`): eight rays per
//! vector in AVX2 lanes, two vectors in turn, a finished lane taking the row's next ray at
//! once. Each lane performs the scalar twin's operations in the same order, so the results
//! are bit-identical to it.

use super::gather::{packed_depth, DepthConsts};
use super::{LANES, RANKS};
use crate::maps::packed::PackedRelief;
use crate::march::pom_lanes::LayerRule;
use crate::trace::{ReliefHit, ReliefInputs, MIN_VIEW_Z};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use std::arch::x86_64::*;

#[derive(Clone, Copy)]
struct Group {
    u0: __m256,
    v0: __m256,
    su: __m256,
    sv: __m256,
    /// Layer to fetch next.
    i: __m256i,
    /// The ray's layer depth, `1 / layers`.
    ld: __m256,
    /// The ray's layer count.
    nl: __m256i,
    prev: __m256,
    owner: __m256i,
    active: u32,
}

/// [`setup`](crate::march::pom_lanes::setup) for every ray, eight at a time (the same
/// operations in the same order): the entry, the per-layer step and the layer depth of each
/// ray into the columns, from its layer count in `counts`.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn setup_columns(height_scale: f32, rays: &[(Vec2, Vec3)], cols: [&mut Vec<f32>; 5], counts: &[f32]) {
    let [cu, cv, csu, csv, cld] = cols;
    let sign = _mm256_set1_ps(-0.0);
    let inf = _mm256_set1_ps(f32::INFINITY);
    let finite = |x: __m256| _mm256_cmp_ps::<_CMP_LT_OQ>(_mm256_andnot_ps(sign, x), inf);
    let (min_z, scale, one) = (_mm256_set1_ps(MIN_VIEW_Z), _mm256_set1_ps(height_scale), _mm256_set1_ps(1.0));
    for start in (0..rays.len()).step_by(LANES) {
        let mut comp = [[0.0f32; LANES]; 5];
        for (l, &(uv, v)) in rays[start..rays.len().min(start + LANES)].iter().enumerate() {
            (comp[0][l], comp[1][l], comp[2][l], comp[3][l], comp[4][l]) = (uv.x, uv.y, v.x, v.y, v.z);
        }
        let ld = |c: &[f32; LANES]| _mm256_loadu_ps(c.as_ptr());
        let (ux, uy, vx, vy, vz) = (ld(&comp[0]), ld(&comp[1]), ld(&comp[2]), ld(&comp[3]), ld(&comp[4]));
        // uv_per_depth, then non-finite values replaced by zero.
        let vz = _mm256_max_ps(vz, min_z);
        let dx = _mm256_mul_ps(_mm256_div_ps(_mm256_xor_ps(vx, sign), vz), scale);
        let dy = _mm256_mul_ps(_mm256_div_ps(_mm256_xor_ps(vy, sign), vz), scale);
        let dp_ok = _mm256_and_ps(finite(dx), finite(dy));
        let (dx, dy) = (_mm256_and_ps(dx, dp_ok), _mm256_and_ps(dy, dp_ok));
        let uv_ok = _mm256_and_ps(finite(ux), finite(uy));
        let layer_depth = _mm256_div_ps(one, _mm256_loadu_ps(counts.as_ptr().add(start)));
        let st = |v: &mut Vec<f32>, x: __m256| _mm256_storeu_ps(v.as_mut_ptr().add(start), x);
        st(cu, _mm256_and_ps(ux, uv_ok));
        st(cv, _mm256_and_ps(uy, uv_ok));
        st(csu, _mm256_mul_ps(dx, layer_depth));
        st(csv, _mm256_mul_ps(dy, layer_depth));
        st(cld, layer_depth);
    }
}

macro_rules! kernel {
    ($name:ident, $features:literal, $fetch:ident) => {
        #[target_feature(enable = $features)]
        pub(crate) unsafe fn $name<R: LayerRule, C: Counter>(
            rule: &R,
            inp: &ReliefInputs,
            map: &PackedRelief,
            rays: &[(Vec2, Vec3)],
            out: &mut [ReliefHit],
            counter: &mut C,
        ) {
            let n = rays.len().min(out.len());
            let len = n.div_ceil(LANES) * LANES + LANES;
            let mut cols = COLUMNS.take();
            for c in cols.iter_mut() {
                c.clear();
                c.resize(len, 0.0);
            }
            let [cu, cv, csu, csv, cld, cn] = &mut cols;
            rule.layer_counts(inp, &rays[..n], &mut cn[..n]);
            setup_columns(inp.height_scale, &rays[..n], [cu, cv, csu, csv, cld], cn);
            let [cu, cv, csu, csv, cld, cn] = &cols;
            let k = DepthConsts::new(map);
            let zero_i = _mm256_setzero_si256();
            let one_i = _mm256_set1_epi32(1);
            let bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);

            let refill = |g: &mut Group, free: u32, next: usize| -> usize {
                if free == 0 {
                    return next;
                }
                let rank = _mm256_loadu_si256(RANKS[free as usize].as_ptr() as *const __m256i);
                let idx = _mm256_add_epi32(_mm256_set1_epi32(next as i32), rank);
                let is_free =
                    _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(free as i32), bits), bits);
                let take = _mm256_and_si256(is_free, _mm256_cmpgt_epi32(_mm256_set1_epi32(n as i32), idx));
                let take_ps = _mm256_castsi256_ps(take);
                let col = |src: __m256, v: &Vec<f32>| {
                    let vals = _mm256_loadu_ps(v.as_ptr().add(next));
                    _mm256_blendv_ps(src, _mm256_permutevar8x32_ps(vals, rank), take_ps)
                };
                g.u0 = col(g.u0, cu);
                g.v0 = col(g.v0, cv);
                g.su = col(g.su, csu);
                g.sv = col(g.sv, csv);
                g.ld = col(g.ld, cld);
                g.nl = _mm256_cvttps_epi32(col(_mm256_cvtepi32_ps(g.nl), cn));
                g.i = _mm256_blendv_epi8(g.i, zero_i, take);
                g.owner = _mm256_blendv_epi8(g.owner, idx, take);
                g.active = (g.active & !free) | _mm256_movemask_ps(take_ps) as u32;
                (next + free.count_ones() as usize).min(n)
            };

            let z = _mm256_setzero_ps();
            let empty = Group {
                u0: z,
                v0: z,
                su: z,
                sv: z,
                i: zero_i,
                ld: z,
                nl: zero_i,
                prev: z,
                owner: zero_i,
                active: 0,
            };
            let mut groups = [empty; 2];
            let mut next = 0usize;
            for g in groups.iter_mut() {
                next = refill(g, 0xff, next);
            }
            while groups.iter().any(|g| g.active != 0) {
                for g in groups.iter_mut() {
                    if g.active == 0 {
                        continue;
                    }
                    counter.count(g.active.count_ones());
                    // The UV of layer i (the entry itself for layer 0).
                    let fi = _mm256_cvtepi32_ps(g.i);
                    let first = _mm256_castsi256_ps(_mm256_cmpeq_epi32(g.i, zero_i));
                    let u = _mm256_blendv_ps(_mm256_add_ps(g.u0, _mm256_mul_ps(g.su, fi)), g.u0, first);
                    let v = _mm256_blendv_ps(_mm256_add_ps(g.v0, _mm256_mul_ps(g.sv, fi)), g.v0, first);
                    // PackedRelief::depth, from the depth plane.
                    let m = packed_depth!($fetch, k, u, v);
                    // Layer 0 has no layer above: its own value.
                    let prev = _mm256_blendv_ps(g.prev, m, first);
                    let go_on = _mm256_and_ps(
                        _mm256_cmp_ps::<_CMP_LT_OQ>(_mm256_mul_ps(fi, g.ld), m),
                        _mm256_castsi256_ps(_mm256_cmpgt_epi32(g.nl, g.i)),
                    );
                    let done = (!(_mm256_movemask_ps(go_on) as u32)) & 0xff & g.active;
                    if done != 0 {
                        // Every lane's result at once, with the operations and order of the
                        // scalar twin's ending ([`crate::march::layered::interpolate`]), then the
                        // finished lanes' results written: measured in one program against the
                        // ending lane by lane, the whole frame's medians −5 to −10 % for POM-32,
                        // −9 to −12 % for adaptive POM, −2 to −6 % for relief mapping.
                        // The layer depth is the lane's `ld`: `1 / count` of a count of at least
                        // one (every `LayerRule::layer_counts` clamps it), the scalar ending's
                        // `1 / layers.max(1)`.
                        let one = _mm256_set1_ps(1.0);
                        let zero = _mm256_setzero_ps();
                        let layer_depth = g.ld;
                        let layer = _mm256_mul_ps(fi, layer_depth);
                        let (hu, hv, depth) = if rule.interpolates() {
                            let ip = _mm256_max_epi32(_mm256_sub_epi32(g.i, one_i), zero_i);
                            let fp = _mm256_cvtepi32_ps(ip);
                            let p0 = _mm256_castsi256_ps(_mm256_cmpeq_epi32(ip, zero_i));
                            let pu = _mm256_blendv_ps(_mm256_add_ps(g.u0, _mm256_mul_ps(g.su, fp)), g.u0, p0);
                            let pv = _mm256_blendv_ps(_mm256_add_ps(g.v0, _mm256_mul_ps(g.sv, fp)), g.v0, p0);
                            let prev_layer = _mm256_blendv_ps(_mm256_sub_ps(layer, layer_depth), zero, first);
                            let after = _mm256_sub_ps(m, layer);
                            let before = _mm256_sub_ps(prev, prev_layer);
                            let denom = _mm256_sub_ps(after, before);
                            let q = _mm256_div_ps(after, denom);
                            // `clamp(0, 1)` as `f32::clamp` (a −0 stays −0).
                            let q = _mm256_blendv_ps(q, zero, _mm256_cmp_ps::<_CMP_LT_OQ>(q, zero));
                            let q = _mm256_blendv_ps(q, one, _mm256_cmp_ps::<_CMP_GT_OQ>(q, one));
                            let big = _mm256_cmp_ps::<_CMP_GT_OQ>(
                                _mm256_andnot_ps(_mm256_set1_ps(-0.0), denom),
                                _mm256_set1_ps(1e-12),
                            );
                            let w = _mm256_and_ps(q, big);
                            let w1 = _mm256_sub_ps(one, w);
                            (
                                _mm256_add_ps(_mm256_mul_ps(pu, w), _mm256_mul_ps(u, w1)),
                                _mm256_add_ps(_mm256_mul_ps(pv, w), _mm256_mul_ps(v, w1)),
                                _mm256_add_ps(_mm256_mul_ps(prev_layer, w), _mm256_mul_ps(layer, w1)),
                            )
                        } else {
                            (u, v, layer)
                        };
                        let (mut ou, mut ov, mut od, mut on, mut own) =
                            ([0.0f32; LANES], [0.0f32; LANES], [0.0f32; LANES], [0i32; LANES], [0i32; LANES]);
                        _mm256_storeu_ps(ou.as_mut_ptr(), hu);
                        _mm256_storeu_ps(ov.as_mut_ptr(), hv);
                        _mm256_storeu_ps(od.as_mut_ptr(), depth);
                        _mm256_storeu_si256(on.as_mut_ptr() as *mut __m256i, g.nl);
                        _mm256_storeu_si256(own.as_mut_ptr() as *mut __m256i, g.owner);
                        let mut f = done;
                        while f != 0 {
                            let l = f.trailing_zeros() as usize;
                            f &= f - 1;
                            out[own[l] as usize] =
                                ReliefHit { uv: Vec2::new(ou[l], ov[l]), depth: od[l], layers: on[l] as u32 };
                        }
                    }
                    // Going on: this layer becomes the previous one.
                    g.prev = m;
                    g.i = _mm256_add_epi32(g.i, _mm256_and_si256(_mm256_castps_si256(go_on), one_i));
                    let _ = prev;
                    if done != 0 {
                        next = refill(g, done, next);
                    }
                }
            }
            COLUMNS.set(cols);
        }
    };
}

kernel!(march_row, "avx2", loads);

thread_local! {
    /// Each thread's ray columns (entry, step, layer depth and count), reused from row to
    /// row so that a frame allocates nothing.
    static COLUMNS: std::cell::Cell<[Vec<f32>; 6]> = const { std::cell::Cell::new([const { Vec::new() }; 6]) };
}
kernel!(march_row_avx512, "avx2,avx512f,avx512vl", gathers);

/// Stamps out the whole trace of a row for one build of the kernels: the layered march in
/// lanes, then, for relief mapping's rules, the bisection pass ([`super::bisect`]). Without
/// target features of its own, so that each pass stays the function it is compiled as.
macro_rules! trace {
    ($name:ident, $march:ident, $refine:ident) => {
        /// Traces `rays` into `out`: the march, then the bisection where the rule asks for it.
        ///
        /// # Safety
        ///
        /// The CPU must support the build's features and the map must have power-of-two sides
        /// (`masks()`).
        #[inline]
        pub(crate) unsafe fn $name<R: LayerRule, C: Counter>(
            rule: &R,
            inp: &ReliefInputs,
            map: &PackedRelief,
            rays: &[(Vec2, Vec3)],
            out: &mut [ReliefHit],
            counter: &mut C,
        ) {
            $march(rule, inp, map, rays, out, counter);
            if let Some(steps) = rule.bisect_steps() {
                super::bisect::$refine(steps, inp, map, rays, out, counter);
            }
        }
    };
}

trace!(trace_row, march_row, refine_row);
trace!(trace_row_avx512, march_row_avx512, refine_row_avx512);

/// The scalar twin, compiled with AVX2 and SSE4.1 (a single instruction for each `floor`):
/// what runs where the lanes cannot; results are the same as without the features.
#[target_feature(enable = "avx2,sse4.1")]
pub(crate) fn twin_row<R: LayerRule, C: Counter>(
    rule: &R,
    inp: &ReliefInputs,
    map: &PackedRelief,
    rays: &[(Vec2, Vec3)],
    out: &mut [ReliefHit],
    counter: &mut C,
) {
    crate::simd::scalar::pom::trace_row(rule, inp, map, rays, out, counter)
}
