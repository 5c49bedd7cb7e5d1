//! The vector kernel of Newton-finished cone stepping
//! ([`crate::march::cone_newton`]): eight rays in the eight lanes of one vector ([`GROUPS`]
//! vectors in turn). Each step gathers the texels of all lanes at once, and a lane whose ray
//! is finished takes the next ray of the row at once, so no lane idles while others still
//! step. Each ray's constants are set up eight at a time before the march. Every lane
//! performs the scalar step's IEEE operations in the same order, so the results are
//! bit-identical to the scalar kernel's.

use super::gather::{gather_cell, packed_sample};
use super::{LANES, RANKS};
use crate::maps::packed::{PackedRelief, DEPTH_STEP};
use crate::march::cone_newton::{
    NewtonCone, Ray, State, CONE, MAX_EPS, MIN_SLOPE, MIN_STEP, REFINE_0, REFINE_A, REFINE_B,
};
use crate::trace::{ReliefHit, ReliefInputs, MIN_VIEW_Z};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use std::arch::x86_64::*;

/// Vectors of rays the kernel steps together: each round issues every group's fetch first and
/// then computes every group's step, so that the groups' gathers are in flight at once (the
/// march is bound by the gathers' latency). Measured on AMD Zen 3: this order made the trace
/// 10–25 % faster than stepping the groups one after another; three or four groups gained
/// nothing over two.
pub const GROUPS: usize = 2;

/// One vector of rays: the constants of each lane's ray and its variable state.
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
}

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

/// One group's fetch, made before its step: the depth sampled (`c`), which lanes cone-step,
/// whether any refines, and the packed sample there (`packed_sample`'s values).
#[derive(Clone, Copy)]
struct Fetched {
    c: __m256,
    is_cone: __m256,
    any_refine: bool,
    depth: __m256,
    ratio: __m256,
    dx0: __m256,
    dx1: __m256,
    dy: __m256,
    fy: __m256,
}

impl Fetched {
    #[inline]
    #[target_feature(enable = "avx2")]
    unsafe fn zero() -> Self {
        let z = _mm256_setzero_ps();
        Self { c: z, is_cone: z, any_refine: false, depth: z, ratio: z, dx0: z, dx1: z, dy: z, fy: z }
    }
}

/// Loads the next rays (from `next` on, at most `n`) into the lanes of `g` set in `free`
/// (a bit per lane), with a fresh state; lanes left without a ray become inactive.
/// Returns the new `next`.
#[inline]
#[target_feature(enable = "avx2")]
unsafe fn refill(fc: &NewtonCone, g: &mut Group, free: u32, next: usize, n: usize, soa: &RaySoa) -> usize {
    if free == 0 {
        return next;
    }
    let (take, next) = g.ray.refill(free, next, n, soa);
    let take_ps = _mm256_castsi256_ps(take);
    let st = State::new(fc);
    let set = |old: __m256, v: f32| _mm256_blendv_ps(old, _mm256_set1_ps(v), take_ps);
    g.t = set(g.t, st.t);
    g.a = set(g.a, st.a);
    g.fa = set(g.fa, st.fa);
    g.b = set(g.b, st.b);
    g.fb = set(g.fb, st.fb);
    g.k = _mm256_blendv_epi8(g.k, _mm256_set1_epi32(st.k), take);
    g.phase = _mm256_blendv_epi8(g.phase, _mm256_set1_epi32(st.phase), take);
    next
}

/// Stamps out the kernel for a set of target features (the same intrinsics; with AVX-512
/// the compiler has 32 vector registers, so the lanes' state need not spill).
macro_rules! kernel {
    ($name:ident, $features:literal) => {
        /// Traces `rays` eight at a time, refilling finished lanes (see the module documentation).
        #[target_feature(enable = $features)]
        pub(crate) unsafe fn $name<C: Counter>(
            fc: &NewtonCone,
            inp: &ReliefInputs,
            map: &PackedRelief,
            rays: &[(Vec2, Vec3)],
            out: &mut [ReliefHit],
            counter: &mut C,
        ) {
            let n = rays.len().min(out.len());
            let (mxk, myk) = map.masks().expect("power-of-two map");
            let base = map.texels().as_ptr() as *const i32;
            let stride = map.stride() as i32;
            // Every ray's constants, computed up front eight at a time (`Ray::new` in vectors).
            let mut soa = COLUMNS.take();
            setup_rays(fc.tol, MAX_EPS, inp, &rays[..n], &mut soa);
            let zero = _mm256_setzero_ps();
            let empty = Group {
                ray: RayLanes::empty(),
                t: zero,
                a: zero,
                fa: zero,
                b: zero,
                fb: zero,
                k: _mm256_setzero_si256(),
                phase: _mm256_setzero_si256(),
            };
            let mut ts = std::mem::take(&mut soa.t);
            let mut groups = [empty; GROUPS];
            let mut next = 0usize;
            for g in groups.iter_mut() {
                next = refill(fc, g, 0xff, next, n, &soa);
            }

            let ps = |x: f32| _mm256_set1_ps(x);
            let one = ps(1.0);
            let min_slope = ps(MIN_SLOPE);
            let jump = ps(fc.jump);
            let sign = ps(-0.0);
            let cone_i = _mm256_set1_epi32(CONE);
            let refine_a_i = _mm256_set1_epi32(REFINE_A);
            let refine_b_i = _mm256_set1_epi32(REFINE_B);
            let refine_0_i = _mm256_set1_epi32(REFINE_0);
            let one_i = _mm256_set1_epi32(1);
            let steps_m1 = _mm256_set1_epi32(fc.steps as i32 - 1);
            let secant_m1 = _mm256_set1_epi32(fc.secant as i32 - 1);
            let no_secant = if fc.secant == 0 { _mm256_castsi256_ps(_mm256_set1_epi32(-1)) } else { zero };
            let mask_x = _mm256_set1_epi32(mxk);
            let mask_y = _mm256_set1_epi32(myk);
            let stride_v = _mm256_set1_epi32(stride);
            let lane_order = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
            let depth_step = ps(DEPTH_STEP);

            // Every group's fetch is issued before any group's step is computed, so that the
            // out-of-order core has the groups' gathers in flight together (a step is too long
            // for its window to reach the next group's fetch otherwise).
            let mut fetched = [Fetched::zero(); GROUPS];
            while groups.iter().any(|g| g.ray.active != 0) {
                for (grp, fe) in groups.iter().zip(fetched.iter_mut()) {
                    if grp.ray.active == 0 {
                        continue;
                    }
                    let RayLanes { px, py, tu, tv, .. } = grp.ray;
                    let Group { t, a, fa, b, fb, phase, .. } = *grp;
                    let is_cone = _mm256_castsi256_ps(_mm256_cmpeq_epi32(phase, cone_i));
                    // Lanes that refine need the false-position point (one division); skip it
                    // when none does.
                    let any_refine = _mm256_movemask_ps(is_cone) != 0xff;
                    let c = if any_refine { _mm256_blendv_ps(interp_v(a, fa, b, fb), t, is_cone) } else { t };
                    let x = _mm256_add_ps(px, _mm256_mul_ps(tu, c));
                    let y = _mm256_add_ps(py, _mm256_mul_ps(tv, c));
                    let (depth, ratio, dx0, dx1, dy, fy) =
                        packed_sample!(base, stride, x, y, mask_x, mask_y, stride_v, lane_order);
                    *fe = Fetched { c, is_cone, any_refine, depth, ratio, dx0, dx1, dy, fy };
                }
                for (grp, fe) in groups.iter_mut().zip(&fetched) {
                    if grp.ray.active == 0 {
                        continue;
                    }
                    counter.count(grp.ray.active.count_ones());
                    let RayLanes { tu, tv, s, eps, .. } = grp.ray;
                    let Group { t, a, fa, b, fb, k, phase, .. } = *grp;
                    let Fetched { c, is_cone, any_refine, depth, ratio, dx0, dx1, dy, fy } = *fe;
                    let ddx = _mm256_mul_ps(
                        _mm256_add_ps(dx0, _mm256_mul_ps(_mm256_sub_ps(dx1, dx0), fy)),
                        depth_step,
                    );
                    let ddy = _mm256_mul_ps(dy, depth_step);

                    let f = _mm256_sub_ps(c, depth);
                    let fp =
                        _mm256_sub_ps(one, _mm256_add_ps(_mm256_mul_ps(ddx, tu), _mm256_mul_ps(ddy, tv)));
                    let gap = _mm256_xor_ps(f, sign);
                    let fp_ok = _mm256_cmp_ps::<_CMP_GE_OQ>(fp, min_slope);
                    let pos = _mm256_cmp_ps::<_CMP_GE_OQ>(f, zero);
                    let k1 = _mm256_add_epi32(k, one_i);
                    let rcp = _mm256_div_ps(one, fp);

                    // Cone phase.
                    let newton = _mm256_andnot_ps(
                        pos,
                        _mm256_and_ps(fp_ok, _mm256_cmp_ps::<_CMP_LE_OQ>(gap, _mm256_mul_ps(eps, fp))),
                    );
                    let out_of_steps = _mm256_castsi256_ps(_mm256_cmpgt_epi32(k1, steps_m1));
                    let oos = _mm256_andnot_ps(_mm256_or_ps(pos, newton), out_of_steps);
                    let stepping = _mm256_andnot_ps(_mm256_or_ps(_mm256_or_ps(pos, newton), oos), is_cone);
                    let abs_f = _mm256_andnot_ps(sign, f);
                    let conv =
                        _mm256_cmp_ps::<_CMP_LE_OQ>(abs_f, _mm256_mul_ps(eps, _mm256_max_ps(fp, min_slope)));
                    let c_le0 = _mm256_cmp_ps::<_CMP_LE_OQ>(c, zero);
                    let crossed_done = _mm256_and_ps(pos, _mm256_or_ps(_mm256_or_ps(c_le0, conv), no_secant));
                    let newton_back = _mm256_sub_ps(c, _mm256_mul_ps(f, rcp));
                    let out_back =
                        _mm256_blendv_ps(c, _mm256_min_ps(_mm256_max_ps(newton_back, a), c), fp_ok);
                    let out_crossed = _mm256_andnot_ps(c_le0, _mm256_blendv_ps(c, out_back, conv));
                    let qn = _mm256_mul_ps(gap, rcp);
                    let out_newton = _mm256_min_ps(_mm256_add_ps(c, qn), one);
                    let oos_scale = _mm256_blendv_ps(one, rcp, _mm256_cmp_ps::<_CMP_GT_OQ>(fp, one));
                    let out_oos = _mm256_min_ps(_mm256_add_ps(c, _mm256_mul_ps(gap, oos_scale)), one);
                    let cone_step = _mm256_div_ps(_mm256_mul_ps(ratio, gap), _mm256_add_ps(s, ratio));
                    let cone_step = _mm256_blendv_ps(gap, cone_step, _mm256_cmp_ps::<_CMP_GT_OQ>(s, zero));
                    let reach = _mm256_mul_ps(_mm256_mul_ps(eps, fp), jump);
                    let near = _mm256_and_ps(fp_ok, _mm256_cmp_ps::<_CMP_LE_OQ>(gap, reach));
                    let cone_step = _mm256_blendv_ps(cone_step, _mm256_max_ps(cone_step, qn), near);
                    let t_next = _mm256_min_ps(_mm256_add_ps(c, _mm256_max_ps(cone_step, ps(MIN_STEP))), one);
                    let cone_done = _mm256_or_ps(crossed_done, _mm256_or_ps(newton, oos));
                    let cone_out =
                        _mm256_blendv_ps(_mm256_blendv_ps(out_oos, out_newton, newton), out_crossed, pos);

                    let new_t = _mm256_blendv_ps(t, t_next, stepping);
                    let pos_i = _mm256_castps_si256(pos);
                    let cone_a = _mm256_blendv_ps(a, c, stepping);
                    let cone_fa = _mm256_blendv_ps(fa, f, stepping);
                    let cone_b = _mm256_blendv_ps(b, c, pos);
                    let cone_fb = _mm256_blendv_ps(fb, f, pos);
                    let cone_k = _mm256_andnot_si256(pos_i, k1);
                    let cone_phase = _mm256_blendv_epi8(cone_i, refine_0_i, pos_i);
                    let (new_a, new_fa, new_b, new_fb, new_k, new_phase, done, result) = if any_refine {
                        // Refinement phase (only when some lane refines).
                        let out_conv =
                            _mm256_blendv_ps(c, _mm256_min_ps(_mm256_max_ps(newton_back, a), b), fp_ok);
                        let was_a = _mm256_castsi256_ps(_mm256_cmpeq_epi32(phase, refine_a_i));
                        let was_b = _mm256_castsi256_ps(_mm256_cmpeq_epi32(phase, refine_b_i));
                        let half = ps(0.5);
                        let ra = _mm256_blendv_ps(c, a, pos);
                        let rfa =
                            _mm256_blendv_ps(f, _mm256_blendv_ps(fa, _mm256_mul_ps(fa, half), was_b), pos);
                        let rb = _mm256_blendv_ps(b, c, pos);
                        let rfb =
                            _mm256_blendv_ps(_mm256_blendv_ps(fb, _mm256_mul_ps(fb, half), was_a), f, pos);
                        let rphase = _mm256_blendv_epi8(refine_a_i, refine_b_i, pos_i);
                        let last = _mm256_castsi256_ps(_mm256_cmpgt_epi32(k1, secant_m1));
                        let refine_done = _mm256_or_ps(conv, last);
                        let refine_out = _mm256_blendv_ps(interp_v(ra, rfa, rb, rfb), out_conv, conv);
                        // Merge the phases.
                        let sel = |cone: __m256, refine: __m256| _mm256_blendv_ps(refine, cone, is_cone);
                        let is_cone_i = _mm256_castps_si256(is_cone);
                        (
                            sel(cone_a, ra),
                            sel(cone_fa, rfa),
                            sel(cone_b, rb),
                            sel(cone_fb, rfb),
                            _mm256_blendv_epi8(k1, cone_k, is_cone_i),
                            _mm256_blendv_epi8(rphase, cone_phase, is_cone_i),
                            sel(cone_done, refine_done),
                            sel(cone_out, refine_out),
                        )
                    } else {
                        (cone_a, cone_fa, cone_b, cone_fb, cone_k, cone_phase, cone_done, cone_out)
                    };

                    // The new state is assembled and refilled as a value and stored once:
                    // blending into the stored group would become masked stores, which are
                    // slow on some CPUs (AMD Zen).
                    let mut ng = Group {
                        ray: grp.ray,
                        t: new_t,
                        a: new_a,
                        fa: new_fa,
                        b: new_b,
                        fb: new_fb,
                        k: new_k,
                        phase: new_phase,
                    };
                    let finished = _mm256_movemask_ps(done) as u32 & ng.ray.active;
                    // SAFETY: `refill` set every owner to a ray of the row or to `n`, and `ts`
                    // has `RaySoa`'s padded length (more than `n` entries).
                    ng.ray.stage(result, &mut ts);
                    if finished != 0 {
                        next = refill(fc, &mut ng, finished, next, n, &soa);
                    }
                    *grp = ng;
                }
            }
            for (i, (o, &t)) in out[..n].iter_mut().zip(&ts).enumerate() {
                *o = soa.hit(i, t, fc.steps);
            }
            soa.t = ts;
            COLUMNS.set(soa);
        }
    };
}

kernel!(trace_row, "avx2");
kernel!(trace_row_avx512, "avx2,avx512f,avx512vl");
