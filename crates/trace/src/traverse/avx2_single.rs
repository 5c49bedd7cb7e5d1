//! The AVX2 kernel for one ray at a time: the AVX2 kernel's node and triangle tests, with the
//! ray in the form they read it in, made straight from the ray.
//!
//! The AVX2 kernel's own form ([`Prepared`]) is four rows of eight scalars, the shape in which
//! a packet's eight rays are set up together and transposed. A single ray's walk then unpacked
//! it: moved the row offsets to integer registers, shifted them, and broadcast the origin,
//! `1/dir` and the sheared frame into vector registers, most of them spilled again: on the
//! 1,728-triangle blob, 220 of a bounce ray's 719 instructions in the kernel ran once per ray,
//! most of them that set-up. Here the set-up writes
//! what the tests read: the quantities broadcast ([`Single`]), the rows' byte offsets, and the
//! triangle test's frame. The values are the same bits as `Prepared::single`'s (a test
//! compares every field), and the tests are the AVX2 kernel's own code (`slabs_with`,
//! `block_with`), so the results are the same bits as the AVX2 and scalar kernels'.
//!
//! Against the row form (AMD Zen 3, `scripts/paired_passes.py`, 3 or 4 rounds of 10 or 12
//! pairs): the 1,728-triangle blob's rays +4 to +19 % (primary / bounce / shadow 1.041 / 1.061
//! / 1.187), the blob's +1 to +3 %, the terrain's 0.996–1.013, the instanced blobs' +6 to +12
//! % (the instance's ray is set up in the same form); the 1,728-triangle blob's bounce rays
//! execute 703 instructions instead of 745. The sheared frame's axes then came from tables
//! and one gather of the ray's floats instead of a chain of branches and loads indexed by the
//! axes: 680 instructions, and +1 to +2 % on that blob's rays (primary / shadow / bounce
//! 1.018 / 1.009 / 1.010, 4 rounds of 12 pairs), 0.98–1.02 on the larger meshes.

#![cfg(target_arch = "x86_64")]

use crate::node::{TriBlock, WideNode};
use crate::ray::Ray;
use crate::traverse::avx2::{block_with, broadcast3, entries, Frame};
use crate::traverse::avx2_ray::{accepted, finite, frame_axes, Prepared};
use crate::traverse::backend::{Backend, BlockHits, RayQuery, FAR};
use glam::{Affine3A, Vec3A};
use std::arch::x86_64::*;

/// One ray as [`Avx2Single`] reads it.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct Single {
    /// The origin, broadcast per axis.
    org: [__m256; 3],
    /// `−1/dir`, broadcast per axis: a plane's distance is `(org − plane) · (−1/dir)`, with
    /// the plane's row as the subtraction's memory operand. That is the same value as
    /// `(plane − org) · (1/dir)`: swapping a difference's terms negates it exactly, and so
    /// does negating a factor of a product. The one difference in bits is where the origin
    /// lies on the plane: both differences are then `+0`, and the products zeros of opposite
    /// signs. The node test does not pass it on: the comparison of entry and exit does not
    /// see a zero's sign, and the entry is a maximum whose last operand is the interval's
    /// start, never `−0` ([`entries`]).
    neg_inv: [__m256; 3],
    /// `−inv · FAR`, the far planes' factor, broadcast per axis.
    neg_inv_far: [__m256; 3],
    /// The interval's start, broadcast.
    t_min: __m256,
    /// The byte offsets in a [`WideNode`] of the near planes' rows, per axis.
    near: [usize; 3],
    /// The byte offsets of the far planes' rows.
    far: [usize; 3],
    /// The triangle test's frame.
    frame: Frame,
    /// Every `1/dir` finite ([`Prepared::finite`]).
    finite: bool,
}

impl Single {
    /// The form of `ray` and its interval end, or `None` where [`RayQuery::new`] rejects it:
    /// the values of [`Prepared::single`], bit for bit. Inlined into its caller, whose target
    /// features it then has (as a function of its own it was not inlined, and its large
    /// result went through memory).
    ///
    /// # Safety
    /// The CPU has AVX2 and FMA, and the caller is compiled for them.
    #[inline(always)]
    unsafe fn new(ray: &Ray) -> Option<(Single, f32)> {
        let all = _mm256_loadu_ps(ray as *const Ray as *const f32);
        let (t_min, t1) = (accepted(ray, all)?, ray.t_max);
        // `1/dir` in lanes 3..6 (one division for the three), its signs those of `dir`.
        let inv = _mm256_div_ps(_mm256_set1_ps(1.0), all);
        let neg_inv = _mm256_xor_ps(inv, _mm256_set1_ps(-0.0));
        let neg_inv_far = _mm256_mul_ps(neg_inv, _mm256_set1_ps(FAR));
        let octant = (_mm256_movemask_ps(all) as u32 >> 3) & 7;
        let all_finite = (_mm256_movemask_ps(finite(inv)) as u32 >> 3) & 7 == 7;
        let axes = frame_axes(all, octant);
        // (dir[kx], dir[ky], dir[kz], dir[kz], org[kx], org[ky], org[kz], org[kz]).
        let p = _mm256_permutevar8x32_ps(all, _mm256_loadu_si256(axes.perm.as_ptr() as *const __m256i));
        let (d, o) = (_mm256_castps256_ps128(p), _mm256_extractf128_ps::<1>(p));
        // The shear (dir[kx], dir[ky], 1) / dir[kz], as `TriRay::new` divides.
        let shear = _mm_div_ps(_mm_blend_ps::<0b0100>(d, _mm_set1_ps(1.0)), _mm_shuffle_ps::<0xaa>(d, d));
        // (Macros, not closures: a closure is compiled without the target features.)
        macro_rules! lane {
            ($v:expr, $i:expr) => {
                _mm256_permutevar8x32_ps($v, _mm256_set1_epi32($i))
            };
        }
        macro_rules! each {
            ($v:expr) => {
                [
                    _mm_shuffle_ps::<0x00>($v, $v),
                    _mm_shuffle_ps::<0x55>($v, $v),
                    _mm_shuffle_ps::<0xaa>($v, $v),
                ]
            };
        }
        let ro = ray.origin.to_array();
        // Row `2a + n` holds axis `a`'s near planes where `n` is the sign bit of `dir[a]`.
        let n = [octant & 1, (octant >> 1) & 1, (octant >> 2) & 1].map(|b| b as usize);
        let single = Single {
            org: [_mm256_set1_ps(ro[0]), _mm256_set1_ps(ro[1]), _mm256_set1_ps(ro[2])],
            neg_inv: [lane!(neg_inv, 3), lane!(neg_inv, 4), lane!(neg_inv, 5)],
            neg_inv_far: [lane!(neg_inv_far, 3), lane!(neg_inv_far, 4), lane!(neg_inv_far, 5)],
            t_min: _mm256_set1_ps(t_min),
            near: [32 * n[0], 32 * (2 + n[1]), 32 * (4 + n[2])],
            far: [32 * (1 - n[0]), 32 * (3 - n[1]), 32 * (5 - n[2])],
            frame: Frame { tri_org: each!(o), shear: each!(shear), k: axes.k, t_min: _mm_set1_ps(t_min) },
            finite: all_finite,
        };
        Some((single, t1))
    }

    /// The form of an accepted query, the same values ([`Backend::prepare`], which the
    /// trait's generic packet set-up calls; the queries' packets run on the AVX2 kernel).
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn of(q: &RayQuery) -> Single {
        let p = Prepared::one(q);
        Single {
            org: broadcast3(p.org),
            neg_inv: broadcast3(p.inv.map(|x| -x)),
            neg_inv_far: broadcast3(p.inv_far.map(|x| -x)),
            t_min: _mm256_set1_ps(p.t_min),
            near: p.near.map(|r| 32 * r as usize),
            far: p.far.map(|r| 32 * r as usize),
            frame: Frame::of(&p),
            finite: p.finite != 0,
        }
    }

    /// The slab tests of `node`'s children, the AVX2 kernel's results bit for bit (entry
    /// distances and mask; `tests/packet.rs` checks them on rays that start on box planes).
    ///
    /// Each plane's distance is `(org − row) · (−1/dir)` ([`Single::neg_inv`]): a vector
    /// subtraction reads its second operand from memory, so the row's load is part of it,
    /// where `(row − org)` took a load of its own. Six instructions fewer a test (27 against 33; the blob's bounce rays
    /// 809 instructions a ray against 852), and against the loads apart
    /// (`scripts/paired_passes.py`, AMD Zen 3, 10 rounds of 20 pairs), primary / bounce /
    /// shadow rays: the terrain 1.005 / 1.013 / 1.011, the blob 1.016 / 1.015 / 1.009, the
    /// 1,728-triangle blob 1.023 / 0.998 / 0.989.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn node<const TREE: bool>(&self, node: &WideNode, t_max: f32) -> (u32, [f32; 8]) {
        // Rows are 32-byte aligned; the offsets are of rows 0..6.
        let base = node.bounds.as_ptr() as *const u8;
        // `(org − row) · (−1/dir)`: the row a memory operand of the subtraction.
        macro_rules! slab {
            ($a:expr, $off:expr, $f:expr) => {
                _mm256_mul_ps(
                    _mm256_sub_ps(self.org[$a], _mm256_load_ps(base.add($off) as *const f32)),
                    $f[$a],
                )
            };
        }
        let near = [
            slab!(0, self.near[0], self.neg_inv),
            slab!(1, self.near[1], self.neg_inv),
            slab!(2, self.near[2], self.neg_inv),
        ];
        let far = [
            slab!(0, self.far[0], self.neg_inv_far),
            slab!(1, self.far[1], self.neg_inv_far),
            slab!(2, self.far[2], self.neg_inv_far),
        ];
        let (near, hit) = entries::<TREE>(near, far, self.t_min, t_max);
        let mut dist = [0.0f32; 8];
        _mm256_storeu_ps(dist.as_mut_ptr(), near);
        (_mm256_movemask_ps(hit) as u32, dist)
    }
}

/// The AVX2 kernel for single rays (AVX2 and FMA): the single-ray queries' kernel where the
/// CPU has AVX2 and not AVX-512 ([`crate::traverse::dispatch`]). Its packet methods are the
/// trait's generic ones; packets run on [`crate::traverse::avx2::Avx2`].
#[derive(Clone, Copy, Debug)]
pub struct Avx2Single;

impl Backend for Avx2Single {
    type Prepared = Single;

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn prepare(q: &RayQuery) -> Single {
        Single::of(q)
    }

    #[inline(always)]
    unsafe fn prepare_ray(ray: &Ray) -> Option<(Single, f32)> {
        Single::new(ray)
    }

    /// The ray carried by `m` as `Prepared::transformed` carries it (the same bits).
    #[inline(always)]
    unsafe fn prepare_transformed(ray: &Ray, m: &Affine3A, t_max: f32) -> Option<(Single, f32)> {
        let origin = m.transform_point3a(Vec3A::from(ray.origin)).into();
        let dir = m.transform_vector3a(Vec3A::from(ray.dir)).into();
        Single::new(&Ray { origin, t_min: ray.t_min, dir, t_max })
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn node(p: &Single, node: &WideNode, t_max: f32) -> (u32, [f32; 8]) {
        p.node::<false>(node, t_max)
    }

    #[inline(always)]
    fn tree_safe(p: &Single) -> bool {
        p.finite
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn node_tree(p: &Single, node: &WideNode, t_max: f32) -> (u32, [f32; 8]) {
        p.node::<true>(node, t_max)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn block(p: &Single, block: &TriBlock, t_max: f32) -> BlockHits {
        block_with(&p.frame, block, t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use proptest::prelude::*;

    /// The lanes of a vector, as bits.
    fn bits8(x: __m256) -> [u32; 8] {
        // SAFETY: a plain reinterpretation of 32 bytes.
        unsafe { std::mem::transmute::<__m256, [u32; 8]>(x) }
    }

    fn bits4(x: __m128) -> [u32; 4] {
        // SAFETY: a plain reinterpretation of 16 bytes.
        unsafe { std::mem::transmute::<__m128, [u32; 4]>(x) }
    }

    /// Whether `s` holds `p`'s values, broadcast, bit for bit.
    fn same(s: &Single, p: &Prepared) -> Result<(), String> {
        let b8 = |v: __m256, x: f32, what: &str| {
            if bits8(v) == [x.to_bits(); 8] {
                Ok(())
            } else {
                Err(format!("{what}: {:?} against {x}", bits8(v)))
            }
        };
        let b4 = |v: __m128, x: f32, what: &str| {
            if bits4(v) == [x.to_bits(); 4] {
                Ok(())
            } else {
                Err(format!("{what}: {:?} against {x}", bits4(v)))
            }
        };
        for a in 0..3 {
            b8(s.org[a], p.org[a], "org")?;
            b8(s.neg_inv[a], -p.inv[a], "neg_inv")?;
            b8(s.neg_inv_far[a], -p.inv_far[a], "neg_inv_far")?;
            b4(s.frame.tri_org[a], p.tri_org[a], "tri_org")?;
            b4(s.frame.shear[a], p.shear[a], "shear")?;
        }
        b8(s.t_min, p.t_min, "t_min")?;
        b4(s.frame.t_min, p.t_min, "frame t_min")?;
        let offsets = (s.near, s.far, s.frame.k, s.finite);
        let expected = (
            p.near.map(|r| 32 * r as usize),
            p.far.map(|r| 32 * r as usize),
            p.k.map(|a| 16 * a as usize),
            p.finite != 0,
        );
        if offsets == expected {
            Ok(())
        } else {
            Err(format!("offsets {offsets:?} against {expected:?}"))
        }
    }

    /// [`Avx2Single`]'s forms of `ray` and of `ray` carried by `m` (its set-up is inlined
    /// into a caller with the kernel's features, as the walk is).
    #[target_feature(enable = "avx2,fma")]
    unsafe fn singles(ray: &Ray, m: &Affine3A, t_max: f32) -> [Option<(Single, f32)>; 2] {
        [Avx2Single::prepare_ray(ray), Avx2Single::prepare_transformed(ray, m, t_max)]
    }

    /// A coordinate: ordinary values, zeros of both signs, the smallest and largest, and the
    /// values a ray must be refused for.
    fn coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![
            6 => -100.0f32..100.0,
            1 => Just(0.0f32),
            1 => Just(-0.0f32),
            1 => prop_oneof![Just(1e-30f32), Just(-1e-38f32), Just(f32::MIN_POSITIVE), Just(3e38f32)],
            1 => prop_oneof![Just(f32::INFINITY), Just(f32::NEG_INFINITY), Just(f32::NAN)],
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// The single-ray form holds the AVX2 kernel's values bit for bit, refuses the rays
        /// that form refuses, and carries a ray into an instance the same way.
        #[test]
        fn the_single_ray_form_has_the_row_forms_bits(
            o in prop::array::uniform3(coordinate()),
            d in prop::array::uniform3(coordinate()),
            t in prop::array::uniform2(coordinate()),
            m in prop::array::uniform12(-3.0f32..3.0),
        ) {
            if !is_x86_feature_detected!("avx2") || !is_x86_feature_detected!("fma") {
                return Ok(());
            }
            let ray = Ray { origin: Vec3::from(o), dir: Vec3::from(d), t_min: t[0], t_max: t[1] };
            let m = Affine3A::from_cols_array(&m);
            // SAFETY: the CPU has AVX2 and FMA (checked above).
            let [ours, ours_m] = unsafe { singles(&ray, &m, t[1]) };
            // SAFETY: as above.
            let (theirs, theirs_m) = unsafe { (Prepared::single(&ray), Prepared::transformed(&ray, &m, t[1])) };
            for (a, b) in [(ours, theirs), (ours_m, theirs_m)] {
                match (a, b) {
                    (None, None) => {}
                    (Some((s, ts)), Some((p, tp))) => {
                        prop_assert_eq!(ts.to_bits(), tp.to_bits());
                        if let Err(e) = same(&s, &p) {
                            return Err(TestCaseError::fail(e));
                        }
                    }
                    (a, b) => prop_assert!(false, "accepted {} against {}", a.is_some(), b.is_some()),
                }
            }
            if let Some(q) = RayQuery::new(&ray) {
                // SAFETY: as above.
                let (s, p) = unsafe { (Single::of(&q), Prepared::one(&q)) };
                if let Err(e) = same(&s, &p) {
                    return Err(TestCaseError::fail(e));
                }
            }
        }
    }
}
