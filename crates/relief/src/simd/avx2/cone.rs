//! The vector kernel of relaxed cone stepping on the packed map (the scalar twin is
//! `simd::scalar::cone`): eight rays per vector, two vectors in turn, each lane a ray
//! in one of the three phases (cone steps, the fallback tail, the refinement), one gather per
//! step for all of them. A finished lane takes the row's next ray at once. Each lane performs
//! the scalar twin's operations in its order, so the hits are bit-identical to it.

use super::gather::packed_sample;
use super::lanes::{interp_v, lane_group, setup_rays, RayLanes, RaySoa, COLUMNS};
use crate::maps::packed::PackedRelief;
use crate::march::cone_lanes::MIN_STEP;
use crate::march::cone_step::{
    lane_start, ConeStep, Refinement, CONE, MAX_EPS, REFINE, TAIL, TAIL_PHASE, TOLERANCE_TEXELS,
};
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use std::arch::x86_64::*;

/// Vectors of rays stepped in turn, so that one's gathers overlap the other's arithmetic.
const GROUPS: usize = 2;

lane_group!(ConeStep, lane_start, side);

macro_rules! kernel {
    ($name:ident, $features:literal) => {
        /// Traces `rays` eight at a time, refilling finished lanes (see the module
        /// documentation).
        #[target_feature(enable = $features)]
        pub(crate) unsafe fn $name<C: Counter>(
            cs: &ConeStep,
            inp: &ReliefInputs,
            map: &PackedRelief,
            rays: &[(Vec2, Vec3)],
            out: &mut [ReliefHit],
            counter: &mut C,
        ) {
            let n = rays.len().min(out.len());
            let secant = cs.refine == Refinement::Secant;
            let mut soa = COLUMNS.take();
            setup_rays(TOLERANCE_TEXELS, MAX_EPS, inp, &rays[..n], &mut soa);
            if !secant {
                // Bisection never stops early (`cone_step::lane_ray`).
                soa.eps.iter_mut().for_each(|e| *e = 0.0);
            }
            let (mxk, myk) = map.masks().expect("power-of-two map");
            let base = map.texels().as_ptr() as *const i32;
            let stride = map.stride() as i32;
            let z = _mm256_setzero_ps();
            let zi = _mm256_setzero_si256();
            let empty =
                Group { ray: RayLanes::empty(), t: z, a: z, fa: z, b: z, fb: z, k: zi, phase: zi, side: zi };
            let mut groups = [empty; GROUPS];
            let mut next = 0usize;
            for g in groups.iter_mut() {
                next = refill(cs, g, 0xff, next, n, &soa);
            }

            let ps = _mm256_set1_ps;
            let pi = _mm256_set1_epi32;
            let (one, half, sign, min_step) = (ps(1.0), ps(0.5), ps(-0.0), ps(MIN_STEP));
            let tail_f = ps(TAIL as f32);
            let (cone_i, tail_i, refine_i) = (pi(CONE), pi(TAIL_PHASE), pi(REFINE));
            let (one_i, minus_one_i) = (pi(1), pi(-1));
            let steps_m1 = pi(cs.steps as i32 - 1);
            let refine_m1 = pi(cs.refine_steps as i32 - 1);
            let tail_max = pi(TAIL as i32);
            let secant_v = if secant { _mm256_castsi256_ps(minus_one_i) } else { z };
            let no_refine = if cs.refine_steps == 0 { _mm256_castsi256_ps(minus_one_i) } else { z };
            let (mask_x, mask_y, stride_v) = (pi(mxk), pi(myk), pi(stride));
            let lane_order = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
            // Where the refinement samples: the midpoint or the false position.
            let refine_point = |a: __m256, fa: __m256, b: __m256, fb: __m256| {
                if secant {
                    interp_v(a, fa, b, fb)
                } else {
                    _mm256_mul_ps(half, _mm256_add_ps(a, b))
                }
            };

            while groups.iter().any(|g| g.ray.active != 0) {
                for grp in groups.iter_mut() {
                    if grp.ray.active == 0 {
                        continue;
                    }
                    counter.count(grp.ray.active.count_ones());
                    let RayLanes { px, py, tu, tv, s, eps, .. } = grp.ray;
                    let Group { t, a, fa, b, fb, k, phase, side, .. } = *grp;
                    let is_cone_i = _mm256_cmpeq_epi32(phase, cone_i);
                    let is_tail_i = _mm256_cmpeq_epi32(phase, tail_i);
                    let (is_cone, is_tail) = (_mm256_castsi256_ps(is_cone_i), _mm256_castsi256_ps(is_tail_i));
                    let is_refine =
                        _mm256_andnot_ps(_mm256_or_ps(is_cone, is_tail), _mm256_castsi256_ps(minus_one_i));
                    let any_refine = _mm256_movemask_ps(is_refine) != 0;

                    // The depth sampled: the cone's, the tail's or the refinement's.
                    let kf = _mm256_cvtepi32_ps(k);
                    let c_tail =
                        _mm256_add_ps(t, _mm256_div_ps(_mm256_mul_ps(_mm256_sub_ps(one, t), kf), tail_f));
                    let c = _mm256_blendv_ps(t, c_tail, is_tail);
                    let c_ref = if any_refine { refine_point(a, fa, b, fb) } else { c };
                    let c = _mm256_blendv_ps(c, c_ref, is_refine);

                    let x = _mm256_add_ps(px, _mm256_mul_ps(tu, c));
                    let y = _mm256_add_ps(py, _mm256_mul_ps(tv, c));
                    let (depth, ratio, ..) =
                        packed_sample!(base, stride, x, y, mask_x, mask_y, stride_v, lane_order);

                    let f = _mm256_sub_ps(c, depth);
                    let pos = _mm256_cmp_ps::<_CMP_GE_OQ>(f, z);
                    let k1 = _mm256_add_epi32(k, one_i);

                    // Cone steps.
                    let gap = _mm256_sub_ps(depth, c);
                    let near = _mm256_andnot_ps(pos, _mm256_cmp_ps::<_CMP_LE_OQ>(gap, eps));
                    let stepping = _mm256_andnot_ps(_mm256_or_ps(pos, near), is_cone);
                    let cone = _mm256_div_ps(_mm256_mul_ps(ratio, gap), _mm256_add_ps(s, ratio));
                    let cone = _mm256_blendv_ps(gap, cone, _mm256_cmp_ps::<_CMP_GT_OQ>(s, z));
                    let t_next = _mm256_min_ps(_mm256_add_ps(c, _mm256_max_ps(cone, min_step)), one);
                    let to_tail =
                        _mm256_and_ps(stepping, _mm256_castsi256_ps(_mm256_cmpgt_epi32(k1, steps_m1)));
                    // The tail: a bracket below the surface or after its last sample.
                    let tail_end = _mm256_or_ps(pos, _mm256_castsi256_ps(_mm256_cmpgt_epi32(k1, tail_max)));
                    let tail_on = _mm256_andnot_ps(tail_end, is_tail);
                    // Bracket found (cone or tail): finished when there is nothing to refine.
                    let bracket = _mm256_or_ps(_mm256_and_ps(pos, is_cone), _mm256_and_ps(tail_end, is_tail));
                    let fb_bracket = _mm256_blendv_ps(_mm256_max_ps(f, z), f, is_cone);
                    let b_le0 = _mm256_cmp_ps::<_CMP_LE_OQ>(c, z);
                    let bracket_done = _mm256_and_ps(bracket, _mm256_or_ps(b_le0, no_refine));
                    let bracket_out = _mm256_andnot_ps(b_le0, c);
                    let starts_refine = _mm256_andnot_ps(bracket_done, bracket);

                    // Moves above the surface (cone steps, tail samples).
                    let moves_a = _mm256_or_ps(stepping, tail_on);
                    let mut new_a = _mm256_blendv_ps(a, c, moves_a);
                    let mut new_fa = _mm256_blendv_ps(fa, f, moves_a);
                    let mut new_b = _mm256_blendv_ps(b, c, bracket);
                    let mut new_fb = _mm256_blendv_ps(fb, fb_bracket, bracket);
                    let new_t = _mm256_blendv_ps(t, t_next, stepping);
                    let moves_k = _mm256_castps_si256(_mm256_andnot_ps(to_tail, moves_a));
                    // Stepping on: k + 1; into the tail or the refinement: 0; others keep k.
                    let resets = _mm256_castps_si256(_mm256_or_ps(moves_a, bracket));
                    let mut new_k = _mm256_blendv_epi8(k, _mm256_blendv_epi8(zi, k1, moves_k), resets);
                    let mut new_phase = _mm256_blendv_epi8(phase, tail_i, _mm256_castps_si256(to_tail));
                    new_phase = _mm256_blendv_epi8(new_phase, refine_i, _mm256_castps_si256(starts_refine));
                    let mut new_side = _mm256_blendv_epi8(side, zi, _mm256_castps_si256(bracket));
                    let mut done = _mm256_or_ps(_mm256_and_ps(near, is_cone), bracket_done);
                    let mut result = _mm256_blendv_ps(c, bracket_out, bracket_done);

                    if any_refine {
                        let conv = _mm256_and_ps(
                            secant_v,
                            _mm256_cmp_ps::<_CMP_LE_OQ>(_mm256_andnot_ps(sign, f), eps),
                        );
                        let on = _mm256_andnot_ps(conv, is_refine);
                        let on_pos = _mm256_and_ps(on, pos);
                        let on_neg = _mm256_andnot_ps(pos, on);
                        // Illinois: halve the other end's value when the same end moves twice.
                        let halve_a = _mm256_and_ps(
                            _mm256_and_ps(on_pos, secant_v),
                            _mm256_castsi256_ps(_mm256_cmpeq_epi32(side, minus_one_i)),
                        );
                        let halve_b = _mm256_and_ps(
                            _mm256_and_ps(on_neg, secant_v),
                            _mm256_castsi256_ps(_mm256_cmpeq_epi32(side, one_i)),
                        );
                        new_b = _mm256_blendv_ps(new_b, c, on_pos);
                        new_fb = _mm256_blendv_ps(new_fb, f, on_pos);
                        new_fa = _mm256_blendv_ps(new_fa, _mm256_mul_ps(fa, half), halve_a);
                        new_a = _mm256_blendv_ps(new_a, c, on_neg);
                        new_fa = _mm256_blendv_ps(new_fa, f, on_neg);
                        new_fb = _mm256_blendv_ps(new_fb, _mm256_mul_ps(fb, half), halve_b);
                        new_side = _mm256_blendv_epi8(new_side, minus_one_i, _mm256_castps_si256(on_pos));
                        new_side = _mm256_blendv_epi8(new_side, one_i, _mm256_castps_si256(on_neg));
                        new_k = _mm256_blendv_epi8(new_k, k1, _mm256_castps_si256(on));
                        let last = _mm256_and_ps(on, _mm256_castsi256_ps(_mm256_cmpgt_epi32(k1, refine_m1)));
                        let final_point = refine_point(new_a, new_fa, new_b, new_fb);
                        result = _mm256_blendv_ps(result, final_point, last);
                        done = _mm256_or_ps(done, _mm256_or_ps(_mm256_and_ps(conv, is_refine), last));
                    }

                    // Assembled and refilled as a value, stored once (see `cone_newton`).
                    let mut ng = Group {
                        ray: grp.ray,
                        t: new_t,
                        a: new_a,
                        fa: new_fa,
                        b: new_b,
                        fb: new_fb,
                        k: new_k,
                        phase: new_phase,
                        side: new_side,
                    };
                    let finished = _mm256_movemask_ps(done) as u32 & ng.ray.active;
                    if finished != 0 {
                        ng.ray.write_hits(finished, result, cs.steps, &soa, out);
                        next = refill(cs, &mut ng, finished, next, n, &soa);
                    }
                    *grp = ng;
                }
            }
            COLUMNS.set(soa);
        }
    };
}

kernel!(trace_row, "avx2");
kernel!(trace_row_avx512, "avx2,avx512f,avx512vl");
