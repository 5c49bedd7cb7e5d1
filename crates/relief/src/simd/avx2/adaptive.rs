//! Adaptive POM's layer counts for eight rays at a time: the view-angle factor (normalise,
//! [`super::math::pow_unit`]) and the two mixes in AVX2 lanes, the complexity lookup (from
//! the byte map, [`crate::maps::complexity::ComplexityCodes`], where the inputs have it) and
//! the final truncation per ray, each step in `AdaptivePom::layers`'s order, so the counts
//! are the scalar function's.

use super::math::pow_unit;
use super::LANES;
use crate::march::adaptive::ANGLE_EXPONENT;
use crate::trace::ReliefInputs;
use glam::{Vec2, Vec3};
use std::arch::x86_64::*;

/// `AdaptivePom::layers` (base range `min..max`) for each ray of `rays` (its complexity read at the entry), as
/// `f32`, into `out`.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn layer_counts(
    min: u32,
    max: u32,
    inp: &ReliefInputs,
    rays: &[(Vec2, Vec3)],
    out: &mut [f32],
) {
    let ps = _mm256_set1_ps;
    let (min, max) = (min as f32, max as f32);
    let (zero, one) = (_mm256_setzero_ps(), ps(1.0));
    let map = inp.complexity;
    let (w, h) = (map.width(), map.height());
    // The complexity lookup in lanes needs power-of-two sides (wrap by masking).
    let masks = (w.is_power_of_two() && h.is_power_of_two() && map.pixels().len() < 1 << 30)
        .then(|| (_mm256_set1_epi32(w as i32 - 1), _mm256_set1_epi32(h as i32 - 1)));
    let (wf, hf, small) = (ps(w as f32), ps(h as f32), ps(1.0e9));
    // The same map in bytes, read instead where it matches (a quarter of the memory).
    let codes = inp.complexity_codes.filter(|k| (k.width(), k.height()) == (w, h));
    for (chunk, outs) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
        let mut comp = [[0.0f32; LANES]; 5];
        for (l, &(uv, v)) in chunk.iter().enumerate() {
            (comp[0][l], comp[1][l], comp[2][l], comp[3][l], comp[4][l]) = (uv.x, uv.y, v.x, v.y, v.z);
        }
        let ld = |a: &[f32; LANES]| _mm256_loadu_ps(a.as_ptr());
        // `complexity_at`: the texel under the entry, wrapped; 0 where the texel coordinates
        // are not finite. Eight lanes whose coordinates are below 10⁹ in magnitude gather;
        // others take the scalar function.
        let tx = _mm256_floor_ps(_mm256_mul_ps(ld(&comp[0]), wf));
        let ty = _mm256_floor_ps(_mm256_mul_ps(ld(&comp[1]), hf));
        let abs = |t: __m256| _mm256_andnot_ps(ps(-0.0), t);
        let near = _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_LT_OQ>(abs(tx), small),
            _mm256_cmp_ps::<_CMP_LT_OQ>(abs(ty), small),
        );
        let c = match masks {
            Some((mx, my)) if chunk.len() == LANES && _mm256_movemask_ps(near) == 0xff => {
                let xi = _mm256_and_si256(_mm256_cvttps_epi32(tx), mx);
                let yi = _mm256_and_si256(_mm256_cvttps_epi32(ty), my);
                let idx = _mm256_add_epi32(_mm256_mullo_epi32(yi, _mm256_set1_epi32(w as i32)), xi);
                let c = match codes {
                    // The byte map: a 32-bit read at each texel's byte (the map is padded for
                    // it), its low byte the code, then the code's value.
                    Some(k) => {
                        let raw = _mm256_i32gather_epi32::<1>(k.codes().as_ptr() as *const i32, idx);
                        let code = _mm256_and_si256(raw, _mm256_set1_epi32(0xff));
                        _mm256_i32gather_ps::<4>(k.values().as_ptr(), code)
                    }
                    None => _mm256_i32gather_ps::<4>(map.pixels().as_ptr(), idx),
                };
                // `clamp(0, 1)`, which keeps NaN.
                let clamped = _mm256_min_ps(_mm256_max_ps(c, zero), one);
                _mm256_blendv_ps(clamped, c, _mm256_cmp_ps::<_CMP_UNORD_Q>(c, c))
            }
            _ => {
                let mut c = [0.0f32; LANES];
                for (l, &(uv, _)) in chunk.iter().enumerate() {
                    c[l] = inp.complexity_at(uv).clamp(0.0, 1.0);
                }
                ld(&c)
            }
        };
        let (vx, vy, vz) = (ld(&comp[2]), ld(&comp[3]), ld(&comp[4]));
        // `normalize_or_zero`'s z: `z · (1 / √(x² + y² + z²))` where that factor is finite
        // and positive, else 0.
        let dot =
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, vx), _mm256_mul_ps(vy, vy)), _mm256_mul_ps(vz, vz));
        let rcp = _mm256_div_ps(one, _mm256_sqrt_ps(dot));
        let finite = _mm256_cmp_ps::<_CMP_EQ_OQ>(_mm256_sub_ps(rcp, rcp), zero);
        let ok = _mm256_and_ps(finite, _mm256_cmp_ps::<_CMP_GT_OQ>(rcp, zero));
        let nz = _mm256_and_ps(_mm256_mul_ps(vz, rcp), ok);
        let a = _mm256_max_ps(_mm256_sub_ps(one, _mm256_andnot_ps(ps(-0.0), nz)), zero);
        let f = pow_unit(a, ANGLE_EXPONENT);
        let lo = _mm256_add_ps(ps(min), _mm256_mul_ps(ps(max / 2.0 - min), f));
        let hi = _mm256_add_ps(ps(min), _mm256_mul_ps(ps(max - min), f));
        let n = _mm256_add_ps(lo, _mm256_mul_ps(_mm256_sub_ps(hi, lo), c));
        let mut nf = [0.0f32; LANES];
        _mm256_storeu_ps(nf.as_mut_ptr(), n);
        for (o, &v) in outs.iter_mut().zip(&nf) {
            *o = (v as u32).max(1) as f32;
        }
    }
}
