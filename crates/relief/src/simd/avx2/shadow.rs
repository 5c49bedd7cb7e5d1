//! Soft self-shadowing on the packed map in vector lanes: eight hits per vector, two vectors
//! in turn, every lane taking the same number of samples along its light ray. Each lane
//! performs [`crate::render::shadow::soft_shadow`]'s operations in its order on the packed
//! map, so the factors are bit-identical to it.

use super::gather::{packed_depth, DepthConsts};
use super::LANES;
use crate::maps::packed::PackedRelief;
use crate::render::shadow::SHADOW_SHARPNESS;
use crate::trace::{ReliefHit, MIN_VIEW_Z};
use renderlab_core::counter::Counter;
use renderlab_core::ShadePoint;
use std::arch::x86_64::*;

/// Hits shadowed together: two vectors.
const GROUP: usize = 2 * LANES;

macro_rules! kernel {
    ($name:ident, $features:literal, $fetch:ident) => {
        /// The soft-shadow factor of each hit of `hits` (lit by `points`' light) with
        /// `samples` samples, into `out`.
        #[target_feature(enable = $features)]
        pub(crate) unsafe fn $name<C: Counter>(
            map: &PackedRelief,
            height_scale: f32,
            samples: u32,
            hits: &[ReliefHit],
            points: &[ShadePoint],
            out: &mut [f32],
            counter: &mut C,
        ) {
            let k = DepthConsts::new(map);
            let n = hits.len().min(points.len()).min(out.len());
            let nf = samples as f32;
            let (zero, one) = (_mm256_setzero_ps(), _mm256_set1_ps(1.0));
            let (min_z, hs, sharp) =
                (_mm256_set1_ps(MIN_VIEW_Z), _mm256_set1_ps(height_scale), _mm256_set1_ps(SHADOW_SHARPNESS));
            let mut start = 0;
            while start < n {
                let end = (start + GROUP).min(n);
                let (mut u, mut v, mut d, mut lx, mut ly, mut lz) = (
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [1.0f32; GROUP],
                );
                let mut active = 0u32;
                for (l, i) in (start..end).enumerate() {
                    let (hit, light) = (&hits[i], points[i].light_ts);
                    // The early answers of the scalar function.
                    out[i] = if light.z <= 0.0 {
                        0.0
                    } else if hit.depth <= 0.0 || samples == 0 {
                        1.0
                    } else {
                        (u[l], v[l], d[l]) = (hit.uv.x, hit.uv.y, hit.depth);
                        (lx[l], ly[l], lz[l]) = (light.x, light.y, light.z);
                        active |= 1 << l;
                        continue;
                    };
                }
                if active == 0 {
                    start = end;
                    continue;
                }
                let load = |c: &[f32; GROUP], g: usize| _mm256_loadu_ps(c.as_ptr().add(g * LANES));
                let (mut dlx, mut dly, mut step) = ([zero; 2], [zero; 2], [zero; 2]);
                let (mut vu, mut vv, mut vd) = ([zero; 2], [zero; 2], [zero; 2]);
                for g in 0..2 {
                    // `f32::max` returns the bound for NaN; `max_ps` returns its second operand.
                    let z = _mm256_max_ps(load(&lz, g), min_z);
                    dlx[g] = _mm256_mul_ps(_mm256_div_ps(load(&lx, g), z), hs);
                    dly[g] = _mm256_mul_ps(_mm256_div_ps(load(&ly, g), z), hs);
                    (vu[g], vv[g], vd[g]) = (load(&u, g), load(&v, g), load(&d, g));
                    step[g] = _mm256_div_ps(vd[g], _mm256_set1_ps(nf));
                }
                let mut occ = [zero; 2];
                for i in 1..=samples {
                    counter.count(active.count_ones());
                    let fi = _mm256_set1_ps(i as f32);
                    let weight = _mm256_set1_ps(1.0 - i as f32 / (nf + 1.0));
                    for g in 0..2 {
                        let risen = _mm256_mul_ps(step[g], fi);
                        let ray_depth = _mm256_sub_ps(vd[g], risen);
                        let su = _mm256_add_ps(vu[g], _mm256_mul_ps(dlx[g], risen));
                        let sv = _mm256_add_ps(vv[g], _mm256_mul_ps(dly[g], risen));
                        let depth = packed_depth!($fetch, k, su, sv);
                        let pen = _mm256_mul_ps(_mm256_sub_ps(ray_depth, depth), weight);
                        // `occlusion.max(pen)` keeps `occlusion` when `pen` is NaN.
                        occ[g] = _mm256_max_ps(pen, occ[g]);
                    }
                }
                let mut f = [0.0f32; GROUP];
                for g in 0..2 {
                    let c = _mm256_min_ps(_mm256_max_ps(_mm256_mul_ps(occ[g], sharp), zero), one);
                    _mm256_storeu_ps(f.as_mut_ptr().add(g * LANES), _mm256_sub_ps(one, c));
                }
                let mut a = active;
                while a != 0 {
                    let l = a.trailing_zeros() as usize;
                    a &= a - 1;
                    out[start + l] = f[l];
                }
                start = end;
            }
        }
    };
}

kernel!(soft_shadow_row, "avx2", loads);
kernel!(soft_shadow_row_avx512, "avx2,avx512f,avx512vl", gathers);
