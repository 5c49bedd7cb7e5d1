//! The AVX2 kernel's form of a ray, made from one ray's [`RayQuery`] or from eight rays at
//! once in vector registers.
//!
//! The eight-ray setup computes, lane by lane, exactly what [`RayQuery::new`] and
//! [`crate::triangle::TriRay::new`] compute for one ray (the same divisions, comparisons and
//! choices, as selects), so both give the same bits. It reads the eight rays as an 8 × 8
//! matrix of floats (a [`Ray`] is eight `f32`), transposes it so that each register holds one
//! quantity of all eight rays, and transposes the results back into eight [`Prepared`] rays of
//! four rows of eight. A packet's setup is then a few vector operations per ray instead of
//! six scalar divisions and a chain of scalar branches.

#![cfg(target_arch = "x86_64")]

use crate::ray::Ray;
use crate::traverse::backend::{RayQuery, Rows, FAR, PACKET};
use glam::{Affine3A, Vec3A};
use std::arch::x86_64::*;
use std::mem::MaybeUninit;

/// A ray as the kernel reads it: scalars, broadcast into registers where used (a broadcast
/// from memory costs what a vector load does), so that a packet's rays take little space.
/// Four rows of eight 32-bit words (the padding is zero), the shape the eight-ray setup writes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct Prepared {
    pub(super) org: [f32; 3],
    pub(super) inv: [f32; 3],
    pub(super) t_min: f32,
    /// The direction's sign bits (bit `a`: `inv[a]` negative), which fix the rows the slab
    /// test reads.
    pub(super) octant: u32,
    pub(super) near: [u32; 3],
    pub(super) far: [u32; 3],
    /// 1 where every `1/dir` is finite: no slab distance can be NaN (`0·∞`), so the node
    /// test may take the maximum and minimum of its four terms as a tree of two levels
    /// (the same values: `max` and `min` do not round) instead of the chain that ignores NaNs.
    pub(super) finite: u32,
    pad1: u32,
    pub(super) k: [u32; 3],
    /// The origin's coordinates along `kx`, `ky`, `kz`.
    pub(super) tri_org: [f32; 3],
    pad2: [f32; 2],
    pub(super) shear: [f32; 3],
    /// `inv · FAR`: the far planes' factor ([`FAR`]).
    pub(super) inv_far: [f32; 3],
    pad3: [f32; 2],
}

const _: () = assert!(std::mem::size_of::<Prepared>() == 128 && std::mem::size_of::<Ray>() == 32);

impl Prepared {
    /// The kernel form of one ray.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn one(q: &RayQuery) -> Prepared {
        let [kx, ky, kz] = q.tri.k;
        // The origin permuted to (kx, ky, kz) in registers (indexing the array by `k` would
        // store and reload it).
        let o = _mm_setr_ps(q.tri.org[0], q.tri.org[1], q.tri.org[2], 0.0);
        let o = _mm_permutevar_ps(o, _mm_setr_epi32(kx as i32, ky as i32, kz as i32, 3));
        // (No closures: a closure here is compiled without the target features and called.)
        let [n0, n1, n2] = q.near;
        let [f0, f1, f2] = q.far;
        Prepared {
            org: q.org,
            inv: q.inv,
            t_min: q.t_min,
            octant: (n0 as u32 & 1) | (n1 as u32 & 1) << 1 | (n2 as u32 & 1) << 2,
            near: [n0 as u32, n1 as u32, n2 as u32],
            far: [f0 as u32, f1 as u32, f2 as u32],
            finite: q.inv.iter().all(|x| x.is_finite()) as u32,
            pad1: 0,
            k: [kx as u32, ky as u32, kz as u32],
            tri_org: [
                _mm_cvtss_f32(o),
                _mm_cvtss_f32(_mm_shuffle_ps::<0x55>(o, o)),
                _mm_cvtss_f32(_mm_shuffle_ps::<0xaa>(o, o)),
            ],
            pad2: [0.0; 2],
            shear: q.tri.shear,
            inv_far: q.inv_far,
            pad3: [0.0; 2],
        }
    }

    /// The kernel form of `ray` and its interval end, or `None` where [`RayQuery::new`]
    /// rejects it: the same values, bit for bit, as `Prepared::one(&RayQuery::new(ray)?)`,
    /// computed as the form's four rows in vector registers from one load of the ray's eight
    /// floats (one division for `1/dir`, one for the shear) and written with four stores.
    /// Against the form assembled field by field (both in one program, passes alternated, AMD
    /// Zen 3): rays that miss the mesh's root +7 to +10 %, the bunny's primary rays +3 to +4 %,
    /// its shadow and bounce rays within ±1 %.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn single(ray: &Ray) -> Option<(Prepared, f32)> {
        let all = _mm256_loadu_ps(ray as *const Ray as *const f32);
        let (t_min, t1) = (accepted(ray, all)?, ray.t_max);
        // `1/dir` in lanes 3..6 (the other lanes' quotients are not used); its signs are those
        // of `dir` (for ±0 and ±∞ too), read from the ray so the rows need not wait for it.
        let inv = _mm256_div_ps(_mm256_set1_ps(1.0), all);
        let signs = _mm256_movemask_ps(all) as u32;
        let octant = (signs >> 3) & 7;
        let all_finite = (_mm256_movemask_ps(finite(inv)) as u32 >> 3) & 7 == 7;
        let [kx, ky, kz] = frame_axes(all, octant).axis;
        let zero = _mm256_setzero_ps();
        // Row 0: org, inv, t_min, octant.
        let tail =
            _mm256_castsi256_ps(_mm256_setr_epi32(0, 0, 0, 0, 0, 0, t_min.to_bits() as i32, octant as i32));
        let r0 = _mm256_blend_ps::<0b1100_0000>(_mm256_blend_ps::<0b0011_1000>(all, inv), tail);
        // Row 1: the near and far rows (2a + n, 2a + 1 − n for sign n), finite, 0.
        let n = _mm256_permutevar8x32_epi32(
            _mm256_srli_epi32::<31>(_mm256_castps_si256(all)),
            _mm256_setr_epi32(3, 4, 5, 3, 4, 5, 0, 0),
        );
        let r1 = _mm256_add_epi32(
            _mm256_setr_epi32(0, 2, 4, 1, 3, 5, all_finite as i32, 0),
            _mm256_sign_epi32(n, _mm256_setr_epi32(1, 1, 1, -1, -1, -1, 0, 0)),
        );
        // Row 2: k, the origin along k, 0, 0.
        let k = _mm256_setr_epi32(kx, ky, kz, kx, ky, kz, 0, 0);
        let r2 = _mm256_blend_ps::<0b1100_0111>(
            _mm256_permutevar8x32_ps(all, k),
            _mm256_blend_ps::<0b1100_0000>(_mm256_castsi256_ps(k), zero),
        );
        // Row 3: the shear (d[kx], d[ky], 1) / d[kz], `inv · FAR`, 0, 0.
        let num = _mm256_blend_ps::<0b0000_0100>(
            _mm256_permutevar8x32_ps(all, _mm256_setr_epi32(3 + kx, 3 + ky, 0, 0, 0, 0, 0, 0)),
            _mm256_set1_ps(1.0),
        );
        let shear = _mm256_div_ps(num, _mm256_permutevar8x32_ps(all, _mm256_set1_epi32(3 + kz)));
        let inv_far = _mm256_mul_ps(inv, _mm256_set1_ps(FAR));
        let r3 = _mm256_blend_ps::<0b1100_0000>(_mm256_blend_ps::<0b0011_1000>(shear, inv_far), zero);
        let mut p = MaybeUninit::<Prepared>::uninit();
        let dst = p.as_mut_ptr() as *mut f32;
        _mm256_store_ps(dst, r0);
        _mm256_store_ps(dst.add(8), _mm256_castsi256_ps(r1));
        _mm256_store_ps(dst.add(16), r2);
        _mm256_store_ps(dst.add(24), r3);
        Some((p.assume_init(), t1))
    }

    /// [`Prepared::single`] of `ray` carried by `m` ([`Ray::transformed`]) with its interval
    /// ending at `t_max`: the same bits, with the carried ray assembled in registers and
    /// written with one store, which the setup's one load then reads directly (written field
    /// by field, the load waits for the stores to complete).
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn transformed(ray: &Ray, m: &Affine3A, t_max: f32) -> Option<(Prepared, f32)> {
        let o = __m128::from(m.transform_point3a(Vec3A::from(ray.origin)));
        let d = __m128::from(m.transform_vector3a(Vec3A::from(ray.dir)));
        // (ox, oy, oz, dx) and (dy, dz, t_min, t_max): the ray's eight floats.
        let lo = _mm_blend_ps::<0b1000>(o, _mm_shuffle_ps::<0x00>(d, d));
        let hi = _mm_shuffle_ps::<0x49>(d, _mm_setr_ps(ray.t_min, t_max, 0.0, 0.0));
        let mut carried = MaybeUninit::<Ray>::uninit();
        _mm256_storeu_ps(carried.as_mut_ptr() as *mut f32, _mm256_set_m128(hi, lo));
        Prepared::single(carried.assume_init_ref())
    }

    /// The kernel forms of eight rays: lane `i` of `out` and `t_max[i]` (the ray's interval
    /// end) are written for every ray `i` that [`RayQuery::new`] accepts, whose bits the
    /// result has; the other lanes get `t_max` −∞ and a form that is never read.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn eight(
        rays: &[Ray; 8],
        out: &mut [MaybeUninit<Prepared>; 8],
        t_max: &mut [f32; 8],
        as_rows: Option<(&mut MaybeUninit<Rows>, usize)>,
    ) -> u32 {
        let src = rays.as_ptr() as *const f32;
        let mut rows = [_mm256_setzero_ps(); 8];
        for (i, r) in rows.iter_mut().enumerate() {
            *r = _mm256_loadu_ps(src.add(8 * i));
        }
        let [ox, oy, oz, dx, dy, dz, t0, t1] = transpose(rows);
        let zero = _mm256_setzero_ps();
        // `t_min > 0 ? t_min : 0`; the ray is kept as `RayQuery::new` keeps it.
        let t_min = _mm256_blendv_ps(zero, t0, _mm256_cmp_ps::<_CMP_GT_OQ>(t0, zero));
        let nonzero = _mm256_or_ps(
            _mm256_cmp_ps::<_CMP_NEQ_OQ>(dx, zero),
            _mm256_or_ps(_mm256_cmp_ps::<_CMP_NEQ_OQ>(dy, zero), _mm256_cmp_ps::<_CMP_NEQ_OQ>(dz, zero)),
        );
        let mut valid =
            _mm256_and_ps(_mm256_cmp_ps::<_CMP_ORD_Q>(t0, t0), _mm256_cmp_ps::<_CMP_LE_OQ>(t_min, t1));
        for x in [ox, oy, oz, dx, dy, dz] {
            valid = _mm256_and_ps(valid, finite(x));
        }
        valid = _mm256_and_ps(valid, nonzero);
        let one = _mm256_set1_ps(1.0);
        let inv = [_mm256_div_ps(one, dx), _mm256_div_ps(one, dy), _mm256_div_ps(one, dz)];
        let ((near_x, far_x), (near_y, far_y), (near_z, far_z)) =
            (planes::<0>(inv[0]), planes::<2>(inv[1]), planes::<4>(inv[2]));
        // The sheared frame: `kz` the axis of the largest |dir| (the first of equals, as
        // `TriRay::new`), `kx`, `ky` the next two cyclically, swapped when `dir[kz] < 0`.
        let (ax, ay, az) = (abs(dx), abs(dy), abs(dz));
        let is_x = _mm256_and_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(ax, ay), _mm256_cmp_ps::<_CMP_GT_OQ>(ax, az));
        let is_y = _mm256_cmp_ps::<_CMP_GT_OQ>(ay, az);
        let (a0, a1, a2) = (axis(0), axis(1), axis(2));
        let kz = pick(is_x, is_y, a0, a1, a2);
        let (kx, ky) = (pick(is_x, is_y, a1, a2, a0), pick(is_x, is_y, a2, a0, a1));
        let d_kz = pick(is_x, is_y, dx, dy, dz);
        let (d_kx, d_ky) = (pick(is_x, is_y, dy, dz, dx), pick(is_x, is_y, dz, dx, dy));
        let o_kz = pick(is_x, is_y, ox, oy, oz);
        let (o_kx, o_ky) = (pick(is_x, is_y, oy, oz, ox), pick(is_x, is_y, oz, ox, oy));
        let flip = _mm256_cmp_ps::<_CMP_LT_OQ>(d_kz, zero);
        let (kx, ky) = swap(flip, kx, ky);
        let (d_kx, d_ky) = swap(flip, d_kx, d_ky);
        let (o_kx, o_ky) = swap(flip, o_kx, o_ky);
        // `1 / dir[kz]` is the same division as `inv[kz]`.
        let shear =
            [_mm256_div_ps(d_kx, d_kz), _mm256_div_ps(d_ky, d_kz), pick(is_x, is_y, inv[0], inv[1], inv[2])];
        // 1 (as an integer's bits) in the lanes whose `1/dir` is finite on every axis.
        let all_finite = _mm256_and_ps(
            _mm256_and_ps(finite(inv[0]), _mm256_and_ps(finite(inv[1]), finite(inv[2]))),
            _mm256_castsi256_ps(_mm256_set1_epi32(1)),
        );
        let far_factor = _mm256_set1_ps(FAR);
        let inv_far = [
            _mm256_mul_ps(inv[0], far_factor),
            _mm256_mul_ps(inv[1], far_factor),
            _mm256_mul_ps(inv[2], far_factor),
        ];
        let first = [ox, oy, oz, inv[0], inv[1], inv[2], t_min, octant(inv)];
        if let Some((out_rows, h)) = as_rows {
            // The first row of each form, one quantity of the eight rays to a register, is
            // what the packet's rows hold (lanes `8·h ..`).
            let base = out_rows.as_mut_ptr() as *mut f32;
            for (i, x) in first.iter().enumerate() {
                _mm256_storeu_ps(base.add(PACKET * i + 8 * h), *x);
            }
        }
        let groups = [
            transpose(first),
            transpose([near_x, near_y, near_z, far_x, far_y, far_z, all_finite, zero]),
            transpose([kx, ky, kz, o_kx, o_ky, o_kz, zero, zero]),
            transpose([shear[0], shear[1], shear[2], inv_far[0], inv_far[1], inv_far[2], zero, zero]),
        ];
        for (lane, dst) in out.iter_mut().enumerate() {
            // `Prepared` is four aligned rows of eight words.
            let dst = dst.as_mut_ptr() as *mut __m256;
            for (row, g) in groups.iter().enumerate() {
                _mm256_store_ps(dst.add(row) as *mut f32, g[lane]);
            }
        }
        _mm256_storeu_ps(t_max.as_mut_ptr(), _mm256_blendv_ps(_mm256_set1_ps(f32::NEG_INFINITY), t1, valid));
        _mm256_movemask_ps(valid) as u32
    }
}

/// `|x|` per lane.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn abs(x: __m256) -> __m256 {
    _mm256_andnot_ps(_mm256_set1_ps(-0.0), x)
}

/// The lanes where `x` is finite (`|x| < ∞`, as `f32::is_finite`). (Inlined into callers with
/// the kernel's features, like the two below.)
#[inline(always)]
pub(super) unsafe fn finite(x: __m256) -> __m256 {
    _mm256_cmp_ps::<_CMP_LT_OQ>(abs(x), _mm256_set1_ps(f32::INFINITY))
}

/// The interval's start where [`RayQuery::new`] accepts `ray` (loaded as the eight lanes
/// `all`): origin and direction finite (lanes 0..6), some direction component non-zero
/// (lanes 3..6), `t_min` not NaN and the interval not empty (a NaN end counts as empty).
#[inline(always)]
pub(super) unsafe fn accepted(ray: &Ray, all: __m256) -> Option<f32> {
    let (t0, t1) = (ray.t_min, ray.t_max);
    let finite_in = _mm256_movemask_ps(finite(all)) as u32 & 0x3f;
    let nonzero = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_NEQ_OQ>(all, _mm256_setzero_ps())) as u32 & 0x38;
    let t_min = if t0 > 0.0 { t0 } else { 0.0 };
    let nonempty = t_min <= t1;
    (!t0.is_nan() && finite_in == 0x3f && nonzero != 0 && nonempty).then_some(t_min)
}

/// The frame's axis `kz` ([`frame_axes`]) for each outcome of the three comparisons
/// of |dir| (bit 0: |x| > |y|, bit 1: |x| > |z|, bit 2: |y| > |z|): x where it beats both,
/// else y where it beats z, else z.
const KZ: [u8; 8] = {
    let mut t = [0u8; 8];
    let mut gt = 0;
    while gt < 8 {
        t[gt] = if gt & 3 == 3 {
            0
        } else if gt & 4 != 0 {
            1
        } else {
            2
        };
        gt += 1;
    }
    t
};

/// A sheared frame's axes `[kx, ky, kz]`, the lanes that gather `(dir[kx], dir[ky], dir[kz],
/// dir[kz], org[kx], org[ky], org[kz], org[kz])` from a ray's eight floats, and the byte
/// offsets of the `kx`, `ky`, `kz` rows of a vertex in a [`crate::node::TriBlock`].
pub(super) struct Axes {
    pub(super) axis: [i32; 3],
    pub(super) perm: [i32; 8],
    pub(super) k: [usize; 3],
}

/// The frame's axes for each `kz` and sign of `dir[kz]` (entry `2·kz + negative`): `kx`, `ky`
/// the next two axes cyclically, swapped where `dir[kz]` is negative ([`frame_axes`]).
const FRAMES: [Axes; 6] = {
    let mut t = [const { Axes { axis: [0; 3], perm: [0; 8], k: [0; 3] } }; 6];
    let mut i = 0;
    while i < 6 {
        let kz = i / 2;
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if i % 2 == 1 {
            (kx, ky) = (ky, kx);
        }
        let [x, y, z] = [kx as i32, ky as i32, kz as i32];
        t[i] = Axes {
            axis: [x, y, z],
            perm: [3 + x, 3 + y, 3 + z, 3 + z, x, y, z, z],
            k: [16 * kx, 16 * ky, 16 * kz],
        };
        i += 1;
    }
    t
};

/// The sheared frame's axes of the ray whose eight floats are `all` and whose direction's sign
/// bits are `octant`, as `TriRay::new` chooses them: `kz` the axis of the largest |dir| (the
/// first of equals), `kx`, `ky` the next two cyclically, swapped when `dir[kz] < 0` (its sign
/// bit: `dir[kz]` is not zero). Three comparisons of |dir| in one register and two small
/// tables, with no branch (a chain of branches and loads indexed by the axes ran 24 more
/// instructions a ray).
///
/// # Safety
/// The CPU has AVX2, and the caller is compiled for it.
#[inline(always)]
pub(super) unsafe fn frame_axes(all: __m256, octant: u32) -> &'static Axes {
    // Bit 0: |x| > |y|, bit 1: |x| > |z|, bit 2: |y| > |z|.
    let ad = _mm256_and_ps(all, _mm256_castsi256_ps(_mm256_set1_epi32(0x7fff_ffff)));
    let gt = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(
        _mm256_permutevar8x32_ps(ad, _mm256_setr_epi32(3, 3, 4, 4, 4, 4, 4, 4)),
        _mm256_permutevar8x32_ps(ad, _mm256_setr_epi32(4, 5, 5, 5, 5, 5, 5, 5)),
    )) as usize
        & 7;
    let kz = *KZ.get_unchecked(gt) as usize;
    FRAMES.get_unchecked(2 * kz + ((octant as usize >> kz) & 1))
}

/// The rows of the near and far planes of the axis whose minima are row `MIN`, by the sign of
/// `inv` as [`RayQuery::new`] chooses them, as integers in float registers.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn planes<const MIN: i32>(inv: __m256) -> (__m256, __m256) {
    let neg = _mm256_srli_epi32::<31>(_mm256_castps_si256(inv));
    let near = _mm256_add_epi32(_mm256_set1_epi32(MIN), neg);
    let far = _mm256_sub_epi32(_mm256_set1_epi32(MIN + 1), neg);
    (_mm256_castsi256_ps(near), _mm256_castsi256_ps(far))
}

/// [`Prepared::octant`] per lane, as an integer in a float register.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn octant(inv: [__m256; 3]) -> __m256 {
    let x = _mm256_srli_epi32::<31>(_mm256_castps_si256(inv[0]));
    let y = _mm256_slli_epi32::<1>(_mm256_srli_epi32::<31>(_mm256_castps_si256(inv[1])));
    let z = _mm256_slli_epi32::<2>(_mm256_srli_epi32::<31>(_mm256_castps_si256(inv[2])));
    let bits = _mm256_or_si256(x, _mm256_or_si256(y, z));
    _mm256_castsi256_ps(bits)
}

/// The axis number `a` in every lane, as an integer in a float register.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn axis(a: i32) -> __m256 {
    _mm256_castsi256_ps(_mm256_set1_epi32(a))
}

/// Per lane `is_x ? x : (is_y ? y : z)`.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn pick(is_x: __m256, is_y: __m256, x: __m256, y: __m256, z: __m256) -> __m256 {
    _mm256_blendv_ps(_mm256_blendv_ps(z, y, is_y), x, is_x)
}

/// Per lane `flip ? (b, a) : (a, b)`.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn swap(flip: __m256, a: __m256, b: __m256) -> (__m256, __m256) {
    (_mm256_blendv_ps(a, b, flip), _mm256_blendv_ps(b, a, flip))
}

/// Transposes an 8 × 8 matrix of floats held one row to a register.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn transpose(r: [__m256; 8]) -> [__m256; 8] {
    let t = [
        _mm256_unpacklo_ps(r[0], r[1]),
        _mm256_unpackhi_ps(r[0], r[1]),
        _mm256_unpacklo_ps(r[2], r[3]),
        _mm256_unpackhi_ps(r[2], r[3]),
        _mm256_unpacklo_ps(r[4], r[5]),
        _mm256_unpackhi_ps(r[4], r[5]),
        _mm256_unpacklo_ps(r[6], r[7]),
        _mm256_unpackhi_ps(r[6], r[7]),
    ];
    let s = [
        _mm256_shuffle_ps::<0x44>(t[0], t[2]),
        _mm256_shuffle_ps::<0xee>(t[0], t[2]),
        _mm256_shuffle_ps::<0x44>(t[1], t[3]),
        _mm256_shuffle_ps::<0xee>(t[1], t[3]),
        _mm256_shuffle_ps::<0x44>(t[4], t[6]),
        _mm256_shuffle_ps::<0xee>(t[4], t[6]),
        _mm256_shuffle_ps::<0x44>(t[5], t[7]),
        _mm256_shuffle_ps::<0xee>(t[5], t[7]),
    ];
    [
        _mm256_permute2f128_ps::<0x20>(s[0], s[4]),
        _mm256_permute2f128_ps::<0x20>(s[1], s[5]),
        _mm256_permute2f128_ps::<0x20>(s[2], s[6]),
        _mm256_permute2f128_ps::<0x20>(s[3], s[7]),
        _mm256_permute2f128_ps::<0x31>(s[0], s[4]),
        _mm256_permute2f128_ps::<0x31>(s[1], s[5]),
        _mm256_permute2f128_ps::<0x31>(s[2], s[6]),
        _mm256_permute2f128_ps::<0x31>(s[3], s[7]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Rays at the edges of what `RayQuery::new` and `TriRay::new` decide: zero and negative
    /// zero components, ties between the largest components, each sign of `dir[kz]`, non-finite
    /// values, negative, NaN and empty intervals.
    fn rays() -> Vec<Ray> {
        let mut rays = Vec::new();
        let comps = [0.0, -0.0, 1.0, -1.0, 0.5, -2.0, 1e-30, f32::INFINITY, f32::NAN];
        for &x in &comps {
            for &y in &comps {
                for &z in &comps {
                    rays.push(Ray::new(Vec3::new(0.25, -3.0, 7.5), Vec3::new(x, y, z)));
                }
            }
        }
        let d = Vec3::new(0.3, -0.7, 0.2);
        for (t_min, t_max) in [
            (-1.0, 2.0),
            (f32::NAN, 1.0),
            (1.0, f32::NAN),
            (3.0, 2.0),
            (2.0, 2.0),
            (-0.0, 0.0),
            (0.5, f32::INFINITY),
        ] {
            rays.push(Ray::segment(Vec3::new(1.0, 2.0, 3.0), d, t_min, t_max));
        }
        for o in [
            Vec3::new(f32::NAN, 0.0, 0.0),
            Vec3::new(0.0, f32::NEG_INFINITY, 0.0),
            Vec3::new(-1e30, 4.0, 1e-30),
        ] {
            rays.push(Ray::new(o, d));
        }
        while rays.len() % 8 != 0 {
            rays.push(Ray::new(Vec3::ONE, Vec3::new(-1.0, -1.0, -1.0)));
        }
        rays
    }

    fn words(p: &Prepared) -> [u32; 32] {
        // SAFETY: `Prepared` is 32 plain 32-bit words.
        unsafe { std::mem::transmute(*p) }
    }

    #[test]
    fn a_ray_set_up_in_vectors_is_the_query_set_up_bit_for_bit() {
        if !(is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")) {
            return;
        }
        for ray in rays() {
            // SAFETY: the CPU has AVX2 and FMA (checked above).
            let single = unsafe { Prepared::single(&ray) };
            match RayQuery::new(&ray) {
                Some(q) => {
                    let (p, t_max) = single.unwrap_or_else(|| panic!("rejected {ray:?}"));
                    // SAFETY: as above.
                    let one = unsafe { Prepared::one(&q) };
                    assert_eq!(words(&p), words(&one), "{ray:?}");
                    assert_eq!(t_max.to_bits(), q.t_max.to_bits());
                }
                None => assert!(single.is_none(), "accepted {ray:?}"),
            }
        }
    }

    #[test]
    fn a_ray_carried_in_registers_is_the_carried_ray_set_up_bit_for_bit() {
        if !(is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")) {
            return;
        }
        let maps = [
            Affine3A::IDENTITY,
            Affine3A::from_scale_rotation_translation(
                Vec3::new(0.5, 2.0, 1.5),
                glam::Quat::from_rotation_y(0.7) * glam::Quat::from_rotation_x(-0.3),
                Vec3::new(3.0, -1.0, 0.25),
            ),
            // Flattens z: carried directions may lose a component or vanish.
            Affine3A::from_scale(Vec3::new(1.0, 1.0, 0.0)),
            Affine3A::from_translation(Vec3::new(f32::INFINITY, 0.0, 0.0)),
        ];
        for m in &maps {
            for ray in rays() {
                for t_max in [ray.t_max, 0.5, 0.0, f32::NAN] {
                    let mut carried = ray.transformed(m);
                    carried.t_max = t_max;
                    // SAFETY: the CPU has AVX2 and FMA (checked above).
                    let (a, b) =
                        unsafe { (Prepared::transformed(&ray, m, t_max), Prepared::single(&carried)) };
                    match (a, b) {
                        (Some((p, ta)), Some((q, tb))) => {
                            assert_eq!(words(&p), words(&q), "{ray:?} by {m:?}");
                            assert_eq!(ta.to_bits(), tb.to_bits());
                        }
                        (None, None) => {}
                        _ => panic!("{ray:?} by {m:?}: carried {a:?} set up as {b:?}"),
                    }
                }
            }
        }
    }

    #[test]
    fn eight_rays_set_up_together_are_one_ray_set_up_alone_bit_for_bit() {
        if !(is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")) {
            return;
        }
        let rays = rays();
        for group in rays.chunks_exact(8) {
            let group: &[Ray; 8] = group.try_into().unwrap();
            let mut out = [const { MaybeUninit::uninit() }; 8];
            let mut t_max = [0.0; 8];
            // SAFETY: the CPU has AVX2 and FMA (checked above).
            let valid = unsafe { Prepared::eight(group, &mut out, &mut t_max, None) };
            for (i, ray) in group.iter().enumerate() {
                let q = RayQuery::new(ray);
                assert_eq!(valid >> i & 1 == 1, q.is_some(), "{ray:?}");
                match q {
                    Some(q) => {
                        // SAFETY: as above; lane `i` is valid, so written.
                        let (one, eight) = unsafe { (Prepared::one(&q), out[i].assume_init()) };
                        assert_eq!(words(&one), words(&eight), "{ray:?}");
                        assert_eq!(t_max[i].to_bits(), q.t_max.to_bits());
                    }
                    None => assert_eq!(t_max[i], f32::NEG_INFINITY),
                }
            }
        }
    }
}
