//! Relief mapping's bisection on the packed map in vector lanes: after the layered march
//! ([`super::pom`]) left each ray's hit at the first layer at or below the surface, the
//! brackets of a row are bisected sixteen rays at a time (two vectors, so that one vector's
//! gathers overlap the other's arithmetic). Every ray takes the same number of steps, so the
//! lanes never diverge. Each lane performs the scalar twin's operations
//! (`simd::scalar::bisect`) in its order: the hits are bit-identical to it.

use super::gather::{packed_depth, DepthConsts};
use super::LANES;
use crate::maps::packed::PackedRelief;
use crate::march::pom_lanes::bracket;
use crate::trace::{ReliefHit, ReliefInputs};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use std::arch::x86_64::*;

/// Rays bisected together: two vectors.
const GROUP: usize = 2 * LANES;

macro_rules! kernel {
    ($name:ident, $features:literal, $fetch:ident) => {
        /// Bisects, `steps` times, the bracket of each of `out`'s hits (the march's results
        /// for `rays`), replacing the hit by the bracket's final midpoint.
        #[target_feature(enable = $features)]
        pub(crate) unsafe fn $name<C: Counter>(
            steps: u32,
            inp: &ReliefInputs,
            map: &PackedRelief,
            rays: &[(Vec2, Vec3)],
            out: &mut [ReliefHit],
            counter: &mut C,
        ) {
            let k = DepthConsts::new(map);
            let half = _mm256_set1_ps(0.5);
            let n = rays.len().min(out.len());
            let mut start = 0;
            while start < n {
                let end = (start + GROUP).min(n);
                let (mut u0, mut v0, mut du, mut dv, mut a, mut b) = (
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                    [0.0f32; GROUP],
                );
                let mut active = 0u32;
                for (l, r) in (start..end).enumerate() {
                    if let Some((uv0, dp, lo, hi)) = bracket(inp, rays[r].0, rays[r].1, &out[r]) {
                        (u0[l], v0[l], du[l], dv[l], a[l], b[l]) = (uv0.x, uv0.y, dp.x, dp.y, lo, hi);
                        active |= 1 << l;
                    }
                }
                if active != 0 {
                    let load = |c: &[f32; GROUP], g: usize| _mm256_loadu_ps(c.as_ptr().add(g * LANES));
                    let mut va = [load(&a, 0), load(&a, 1)];
                    let mut vb = [load(&b, 0), load(&b, 1)];
                    let (vu0, vv0) = ([load(&u0, 0), load(&u0, 1)], [load(&v0, 0), load(&v0, 1)]);
                    let (vdu, vdv) = ([load(&du, 0), load(&du, 1)], [load(&dv, 0), load(&dv, 1)]);
                    for _ in 0..steps {
                        counter.count(active.count_ones());
                        for g in 0..2 {
                            let mid = _mm256_mul_ps(half, _mm256_add_ps(va[g], vb[g]));
                            let u = _mm256_add_ps(vu0[g], _mm256_mul_ps(vdu[g], mid));
                            let v = _mm256_add_ps(vv0[g], _mm256_mul_ps(vdv[g], mid));
                            let depth = packed_depth!($fetch, k, u, v);
                            // `mid >= depth` (false for NaN, as in the scalar comparison).
                            let below = _mm256_cmp_ps::<_CMP_GE_OQ>(mid, depth);
                            vb[g] = _mm256_blendv_ps(vb[g], mid, below);
                            va[g] = _mm256_blendv_ps(mid, va[g], below);
                        }
                    }
                    let (mut t, mut u, mut v) = ([0.0f32; GROUP], [0.0f32; GROUP], [0.0f32; GROUP]);
                    for g in 0..2 {
                        let tg = _mm256_mul_ps(half, _mm256_add_ps(va[g], vb[g]));
                        _mm256_storeu_ps(t.as_mut_ptr().add(g * LANES), tg);
                        _mm256_storeu_ps(
                            u.as_mut_ptr().add(g * LANES),
                            _mm256_add_ps(vu0[g], _mm256_mul_ps(vdu[g], tg)),
                        );
                        _mm256_storeu_ps(
                            v.as_mut_ptr().add(g * LANES),
                            _mm256_add_ps(vv0[g], _mm256_mul_ps(vdv[g], tg)),
                        );
                    }
                    let mut f = active;
                    while f != 0 {
                        let l = f.trailing_zeros() as usize;
                        f &= f - 1;
                        let o = &mut out[start + l];
                        *o = ReliefHit { uv: Vec2::new(u[l], v[l]), depth: t[l], layers: o.layers };
                    }
                }
                start = end;
            }
        }
    };
}

kernel!(refine_row, "avx2", loads);
kernel!(refine_row_avx512, "avx2,avx512f,avx512vl", gathers);
