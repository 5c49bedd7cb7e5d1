//! The lanes of the two cone kernels on the packed map (relaxed cone stepping and
//! cone-newton): the rays of a row as columns ([`RaySoa`], set up eight at a time by
//! [`setup_rays`]), eight rays' constants in one vector ([`RayLanes`]), and eight rays'
//! state ([`crate::march::cone_lanes::State`] in lanes) with the refill that gives a
//! finished lane the row's next ray in a fresh state (`lane_group!`).

use super::{LANES, RANKS};
use crate::march::cone_lanes::Ray;
use crate::trace::{ReliefHit, ReliefInputs, MIN_VIEW_Z};
use glam::{Vec2, Vec3};
use std::arch::x86_64::*;

/// The rays of a row as structure of arrays (each padded by [`LANES`] entries), for
/// loading into lanes: the fields of [`Ray`].
#[derive(Default)]
pub(crate) struct RaySoa {
    pub(crate) px: Vec<f32>,
    pub(crate) py: Vec<f32>,
    pub(crate) tu: Vec<f32>,
    pub(crate) tv: Vec<f32>,
    pub(crate) s: Vec<f32>,
    pub(crate) eps: Vec<f32>,
    pub(crate) u0: Vec<f32>,
    pub(crate) v0: Vec<f32>,
    pub(crate) du: Vec<f32>,
    pub(crate) dv: Vec<f32>,
    /// Each ray's result depth, written by [`RayLanes::stage`] (entry `n`, past the last
    /// ray, takes the writes of lanes without a ray).
    pub(crate) t: Vec<f32>,
}

impl RaySoa {
    /// [`Ray::hit`] of ray `i`.
    #[inline(always)]
    pub(crate) fn hit(&self, i: usize, t: f32, layers: u32) -> ReliefHit {
        Ray {
            uv0: Vec2::new(self.u0[i], self.v0[i]),
            dp: Vec2::new(self.du[i], self.dv[i]),
            ..Ray::default()
        }
        .hit(t, layers)
    }

    fn set(&mut self, i: usize, r: &Ray) {
        self.px[i] = r.px;
        self.py[i] = r.py;
        self.tu[i] = r.tu;
        self.tv[i] = r.tv;
        self.s[i] = r.s;
        self.eps[i] = r.eps;
        self.u0[i] = r.uv0.x;
        self.v0[i] = r.uv0.y;
        self.du[i] = r.dp.x;
        self.dv[i] = r.dp.y;
    }
}

/// [`Ray::with_tolerance`] for every ray, eight at a time: the same operations in the same
/// order.
#[inline]
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn setup_rays(
    tol: f32,
    max_eps: f32,
    inp: &ReliefInputs,
    rays: &[(Vec2, Vec3)],
    soa: &mut RaySoa,
) {
    let n = rays.len();
    let len = n.div_ceil(LANES) * LANES + LANES;
    for c in [
        &mut soa.px,
        &mut soa.py,
        &mut soa.tu,
        &mut soa.tv,
        &mut soa.s,
        &mut soa.eps,
        &mut soa.u0,
        &mut soa.v0,
        &mut soa.du,
        &mut soa.dv,
        &mut soa.t,
    ] {
        // Only the entries gained are written: the loop below writes every entry up to the
        // last whole vector, and the padding after it keeps the finite values of an earlier
        // row, which `RayLanes::refill` loads but never gives to a lane.
        c.resize(len, 0.0);
    }
    let (w, h) = (inp.height.width() as f32, inp.height.height() as f32);
    let (wv, hv) = (_mm256_set1_ps(w), _mm256_set1_ps(h));
    let abs_mask = _mm256_set1_ps(-0.0);
    let inf = _mm256_set1_ps(f32::INFINITY);
    let finite = |x: __m256| _mm256_cmp_ps::<_CMP_LT_OQ>(_mm256_andnot_ps(abs_mask, x), inf);
    for start in (0..n).step_by(LANES) {
        let mut comp = [[0.0f32; LANES]; 5];
        for (l, &(uv, v)) in rays[start..n.min(start + LANES)].iter().enumerate() {
            comp[0][l] = uv.x;
            comp[1][l] = uv.y;
            comp[2][l] = v.x;
            comp[3][l] = v.y;
            comp[4][l] = v.z;
        }
        let ld = |c: &[f32; LANES]| _mm256_loadu_ps(c.as_ptr());
        let (ux, uy, vx, vy, vz) = (ld(&comp[0]), ld(&comp[1]), ld(&comp[2]), ld(&comp[3]), ld(&comp[4]));
        // uv_per_depth
        let vz = _mm256_max_ps(vz, _mm256_set1_ps(MIN_VIEW_Z));
        let scale = _mm256_set1_ps(inp.height_scale);
        let dx = _mm256_mul_ps(_mm256_div_ps(_mm256_xor_ps(vx, abs_mask), vz), scale);
        let dy = _mm256_mul_ps(_mm256_div_ps(_mm256_xor_ps(vy, abs_mask), vz), scale);
        let dp_ok = _mm256_and_ps(finite(dx), finite(dy));
        let (dx, dy) = (_mm256_and_ps(dx, dp_ok), _mm256_and_ps(dy, dp_ok));
        let uv_ok = _mm256_and_ps(finite(ux), finite(uy));
        let (ux, uy) = (_mm256_and_ps(ux, uv_ok), _mm256_and_ps(uy, uv_ok));
        let half = _mm256_set1_ps(0.5);
        let px = _mm256_sub_ps(_mm256_mul_ps(ux, wv), half);
        let py = _mm256_sub_ps(_mm256_mul_ps(uy, hv), half);
        let s = _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)));
        let tpd = _mm256_mul_ps(s, _mm256_set1_ps(w.max(h)));
        let eps = _mm256_div_ps(_mm256_set1_ps(tol), _mm256_max_ps(tpd, _mm256_set1_ps(1e-3)));
        let eps = _mm256_min_ps(_mm256_max_ps(eps, _mm256_set1_ps(1e-6)), _mm256_set1_ps(max_eps));
        let st = |v: &mut Vec<f32>, x: __m256| _mm256_storeu_ps(v.as_mut_ptr().add(start), x);
        st(&mut soa.px, px);
        st(&mut soa.py, py);
        st(&mut soa.tu, _mm256_mul_ps(dx, wv));
        st(&mut soa.tv, _mm256_mul_ps(dy, hv));
        st(&mut soa.s, s);
        st(&mut soa.eps, eps);
        st(&mut soa.u0, ux);
        st(&mut soa.v0, uy);
        st(&mut soa.du, dx);
        st(&mut soa.dv, dy);
        // Far-away entries (folded into the first tiles by `Ray::new`): the scalar code.
        let big = _mm256_set1_ps(1.0e6);
        let far = _mm256_or_ps(
            _mm256_cmp_ps::<_CMP_GT_OQ>(_mm256_andnot_ps(abs_mask, px), big),
            _mm256_cmp_ps::<_CMP_GT_OQ>(_mm256_andnot_ps(abs_mask, py), big),
        );
        let mut far = _mm256_movemask_ps(far) as u32;
        while far != 0 {
            let l = far.trailing_zeros() as usize;
            far &= far - 1;
            if start + l < n {
                let (uv, v) = rays[start + l];
                soa.set(start + l, &Ray::with_tolerance(tol, max_eps, inp, uv, v));
            }
        }
    }
}

thread_local! {
    /// Each thread's ray columns, reused from row to row so that a frame allocates nothing.
    pub(crate) static COLUMNS: std::cell::Cell<RaySoa> = std::cell::Cell::new(RaySoa::default());
}

/// The vector `interp`.
#[inline]
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn interp_v(a: __m256, fa: __m256, b: __m256, fb: __m256) -> __m256 {
    let den = _mm256_sub_ps(fb, fa);
    let q = _mm256_div_ps(_mm256_sub_ps(_mm256_mul_ps(a, fb), _mm256_mul_ps(b, fa)), den);
    let q = _mm256_min_ps(_mm256_max_ps(q, a), b);
    let mid = _mm256_mul_ps(_mm256_set1_ps(0.5), _mm256_add_ps(a, b));
    _mm256_blendv_ps(mid, q, _mm256_cmp_ps::<_CMP_GT_OQ>(den, _mm256_set1_ps(1e-12)))
}

/// The rays' columns in one vector of lanes, shared by the cone kernels' lane groups.
#[derive(Clone, Copy)]
pub(crate) struct RayLanes {
    pub(crate) px: __m256,
    pub(crate) py: __m256,
    pub(crate) tu: __m256,
    pub(crate) tv: __m256,
    pub(crate) s: __m256,
    pub(crate) eps: __m256,
    /// Index of each lane's ray in the row.
    pub(crate) owner: __m256i,
    /// Lanes holding a ray (bit per lane).
    pub(crate) active: u32,
}

impl RayLanes {
    /// No rays.
    #[inline]
    #[target_feature(enable = "avx2")]
    pub(crate) unsafe fn empty() -> Self {
        let z = _mm256_setzero_ps();
        Self { px: z, py: z, tu: z, tv: z, s: z, eps: z, owner: _mm256_setzero_si256(), active: 0 }
    }

    /// Loads the next rays (from `next` on, at most `n`) into the lanes set in `free` (a bit
    /// per lane); lanes left without a ray become inactive. Returns the lanes that took a ray
    /// (all bits set in each) and the new `next`; the caller resets their state.
    #[inline]
    #[target_feature(enable = "avx2")]
    pub(crate) unsafe fn refill(
        &mut self,
        free: u32,
        next: usize,
        n: usize,
        soa: &RaySoa,
    ) -> (__m256i, usize) {
        let rank = _mm256_loadu_si256(RANKS[free as usize].as_ptr() as *const __m256i);
        let idx = _mm256_add_epi32(_mm256_set1_epi32(next as i32), rank);
        let bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
        let is_free = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(free as i32), bits), bits);
        let in_range = _mm256_cmpgt_epi32(_mm256_set1_epi32(n as i32), idx);
        let take = _mm256_and_si256(is_free, in_range);
        let take_ps = _mm256_castsi256_ps(take);
        // The free lanes take rays next, next + 1, …: eight consecutive values, permuted by
        // rank (the arrays are padded so the load stays inside them).
        let gather = |src: __m256, v: &Vec<f32>| {
            debug_assert!(next + LANES <= v.len());
            let vals = _mm256_loadu_ps(v.as_ptr().add(next));
            _mm256_blendv_ps(src, _mm256_permutevar8x32_ps(vals, rank), take_ps)
        };
        self.px = gather(self.px, &soa.px);
        self.py = gather(self.py, &soa.py);
        self.tu = gather(self.tu, &soa.tu);
        self.tv = gather(self.tv, &soa.tv);
        self.s = gather(self.s, &soa.s);
        self.eps = gather(self.eps, &soa.eps);
        // Free lanes left without a ray point past the last ray, where `stage` may write.
        let owner = _mm256_blendv_epi8(self.owner, _mm256_set1_epi32(n as i32), is_free);
        self.owner = _mm256_blendv_epi8(owner, idx, take);
        self.active = (self.active & !free) | _mm256_movemask_ps(take_ps) as u32;
        (take, (next + free.count_ones() as usize).min(n))
    }

    /// Writes every lane's `result` to its ray's entry of `t` (without a branch per
    /// finished lane): a ray's last write is its result, made in the step it finishes.
    ///
    /// # Safety
    ///
    /// Every lane's `owner` must index `t` (as [`RayLanes::refill`] sets them: a ray of the
    /// row, or the entry past the last one, for a `t` of [`RaySoa`]'s padded length), and the
    /// CPU must support AVX2.
    #[inline]
    #[target_feature(enable = "avx2")]
    pub(crate) unsafe fn stage(&self, result: __m256, t: &mut [f32]) {
        let mut res = [0.0f32; LANES];
        let mut own = [0i32; LANES];
        _mm256_storeu_ps(res.as_mut_ptr(), result);
        _mm256_storeu_si256(own.as_mut_ptr() as *mut __m256i, self.owner);
        for (&o, &r) in own.iter().zip(&res) {
            debug_assert!((o as usize) < t.len());
            // SAFETY: the caller's guarantee (no bounds check in the march's inner loop).
            *t.get_unchecked_mut(o as usize) = r;
        }
    }

    /// Writes the hits of the lanes in `finished` (their depths in `result`) for their rays.
    #[inline]
    #[target_feature(enable = "avx2")]
    pub(crate) unsafe fn write_hits(
        &self,
        finished: u32,
        result: __m256,
        layers: u32,
        soa: &RaySoa,
        out: &mut [ReliefHit],
    ) {
        let mut res = [0.0f32; LANES];
        let mut own = [0i32; LANES];
        _mm256_storeu_ps(res.as_mut_ptr(), result);
        _mm256_storeu_si256(own.as_mut_ptr() as *mut __m256i, self.owner);
        let mut f = finished;
        while f != 0 {
            let l = f.trailing_zeros() as usize;
            f &= f - 1;
            let i = own[l] as usize;
            out[i] = soa.hit(i, res[l], layers);
        }
    }
}

/// Declares, in a cone kernel's file, `Group` (one vector of rays: the constants of each
/// lane's ray and its variable state, the fields of
/// [`State`](crate::march::cone_lanes::State), with `side` where the march keeps Illinois's
/// memory there) and `refill(march, group, free, next, n, columns)`, which loads the next rays
/// (from `next` on, at most `n`) into the lanes set in `free` (a bit per lane), each in the
/// state `start(march)`, leaves lanes without a ray inactive and returns the new `next`.
/// Stamped into each kernel's file (as the kernels are for each build), so that each kernel's
/// code is compiled as if written there.
macro_rules! lane_group {
    ($march:ty, $start:path $(, $side:ident)?) => {
        /// One vector of rays: the constants of each lane's ray and its variable state
        /// ([`crate::march::cone_lanes::State`]).
        #[derive(Clone, Copy)]
        struct Group {
            /// The lanes' rays.
            ray: RayLanes,
            t: __m256,
            a: __m256,
            fa: __m256,
            b: __m256,
            fb: __m256,
            k: __m256i,
            phase: __m256i,
            $($side: __m256i,)?
        }

        /// Loads the next rays (from `next` on, at most `n`) into the lanes of `g` set in
        /// `free` (a bit per lane), with a fresh state; lanes left without a ray become
        /// inactive. Returns the new `next`.
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn refill(m: &$march, g: &mut Group, free: u32, next: usize, n: usize, soa: &RaySoa) -> usize {
            if free == 0 {
                return next;
            }
            let (take, next) = g.ray.refill(free, next, n, soa);
            let take_ps = _mm256_castsi256_ps(take);
            let st = $start(m);
            let set = |old: __m256, v: f32| _mm256_blendv_ps(old, _mm256_set1_ps(v), take_ps);
            g.t = set(g.t, st.t);
            g.a = set(g.a, st.a);
            g.fa = set(g.fa, st.fa);
            g.b = set(g.b, st.b);
            g.fb = set(g.fb, st.fb);
            g.k = _mm256_blendv_epi8(g.k, _mm256_set1_epi32(st.k), take);
            g.phase = _mm256_blendv_epi8(g.phase, _mm256_set1_epi32(st.phase), take);
            $(g.$side = _mm256_blendv_epi8(g.$side, _mm256_set1_epi32(st.$side), take);)?
            next
        }
    };
}
pub(crate) use lane_group;
