//! The AVX-512 kernel: the AVX2 kernel's ray form, node test and triangle test, with a packet
//! node test that can take sixteen rays at a time against one child (a 512-bit register per
//! quantity, a lane per ray) where the AVX2 kernel takes one ray at a time against the eight
//! children. Per child and ray the lane runs the AVX2 kernel's operations in the same order
//! (`(plane − o)·inv`, the same `maxps`/`minps` operand order, Ize's factor, `≤`), so every
//! box decision and entry distance is bit for bit the single-ray test's.
//!
//! Ray by ray, a node of a full packet costs 32 tests of eight lanes each and the transposes
//! of their masks; child by child it costs at most eight children times two sixteen-lane
//! tests, and each child's ray mask comes out of a compare directly. That pays where the core
//! executes 512-bit operations at full width (Intel's AVX-512 cores: the blob's primary-ray
//! packets +13 to +49 % on a Xeon), not where it splits them in two (AMD's Zen 4: −7 %), so it
//! runs where [`crate::kernel::child_by_child`] says. It needs the rays as rows ([`Rows`],
//! written at the packet's setup) and all of the packet's active rays in one octant (they then
//! read the same planes of the node); otherwise, and for packets thinned out to fewer than
//! [`CHILD_BY_CHILD`] rays, the AVX2 kernel's ray-by-ray test runs.
//!
//! The rows also give a packet of rays from one origin its [`PacketBounds`] and the least
//! interval end of its active rays (masked reductions over the rows, where the AVX2 kernel
//! blends), for the test of a node for the packet as a whole ([`Backend::whole`], the AVX2
//! kernel's).

#![cfg(target_arch = "x86_64")]

use crate::node::{TriBlock, WideNode, EMPTY, WIDTH};
use crate::ray::Ray;
use crate::traverse::avx2::Avx2;
use crate::traverse::avx2_ray::Prepared;
use crate::traverse::backend::{
    planes_of, Backend, BlockHits, PacketBounds, PacketNode, RayQuery, Rows, FAR, IZE, PACKET,
};
use glam::Affine3A;
use std::arch::x86_64::*;
use std::mem::MaybeUninit;

/// Methods that run the AVX2 kernel's own code, here compiled with AVX-512's 32 registers.
macro_rules! as_avx2 {
    ($(fn $name:ident($($arg:ident: $ty:ty),* $(,)?) -> $ret:ty;)*) => {$(
        #[inline]
        #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
        unsafe fn $name($($arg: $ty),*) -> $ret {
            Avx2::$name($($arg),*)
        }
    )*};
}

/// Active rays from which a packet's node is tested child by child.
pub const CHILD_BY_CHILD: u32 = 8;

/// The AVX-512 kernel (AVX2 and FMA with AVX-512 F and VL).
#[derive(Clone, Copy, Debug)]
pub struct Avx512;

impl Backend for Avx512 {
    type Prepared = Prepared;

    const ROWS: bool = true;

    /// Where the node test runs child by child, it reads the rows of every packet.
    #[inline(always)]
    fn rows_always() -> bool {
        crate::kernel::child_by_child()
    }

    #[inline(always)]
    fn tree_safe(p: &Prepared) -> bool {
        Avx2::tree_safe(p)
    }

    as_avx2! {
        fn prepare(q: &RayQuery) -> Prepared;
        fn prepare_ray(ray: &Ray) -> Option<(Prepared, f32)>;
        fn prepare_transformed(ray: &Ray, m: &Affine3A, t_max: f32) -> Option<(Prepared, f32)>;
        fn prepare8(rays: &[Ray; 8], out: &mut [MaybeUninit<Prepared>; 8], t_max: &mut [f32; 8]) -> u32;
        fn prepare8_rows(
            rays: &[Ray; 8],
            out: &mut [MaybeUninit<Prepared>; 8],
            t_max: &mut [f32; 8],
            rows: &mut MaybeUninit<Rows>,
            h: usize,
        ) -> u32;
        fn row(p: &Prepared, rows: &mut MaybeUninit<Rows>, r: usize) -> ();
        fn node(p: &Prepared, node: &WideNode, t_max: f32) -> (u32, [f32; 8]);
        fn node_tree(p: &Prepared, node: &WideNode, t_max: f32) -> (u32, [f32; 8]);
        fn block(p: &Prepared, block: &TriBlock, t_max: f32) -> BlockHits;
        fn reaching(t_max: &[f32; PACKET], rays: u32, dist: f32) -> u32;
        fn node_packet(
            p: &[MaybeUninit<Prepared>; PACKET],
            node: &WideNode,
            active: u32,
            t_max: &[f32; PACKET]
        ) -> PacketNode;
    }

    #[inline]
    #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
    unsafe fn whole(b: &PacketBounds, node: &WideNode, t_low: f32) -> Option<(u32, [f32; WIDTH])> {
        Avx2::whole_in_line(b, node, t_low)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
    unsafe fn bounds(rows: &MaybeUninit<Rows>, valid: u32, t_max: &[f32; PACKET]) -> Option<PacketBounds> {
        let rows = rows.as_ptr() as *const f32;
        let halves = [valid as u16, (valid >> 16) as u16];
        // Rays from several origins have no bounds: found first, in a few compares.
        let lead = valid.trailing_zeros() as usize;
        let mut org = [0.0f32; 3];
        for (q, o) in org.iter_mut().enumerate() {
            *o = *rows.add(PACKET * q + lead);
            for (h, &k) in halves.iter().enumerate() {
                let x = _mm512_maskz_loadu_ps(k, rows.add(PACKET * q + 16 * h));
                if _mm512_mask_cmp_ps_mask::<_CMP_NEQ_UQ>(k, x, _mm512_set1_ps(*o)) != 0 {
                    return None;
                }
            }
        }
        // The least and greatest `1/dir` per axis and interval start over the rays (rows 3 to
        // 6; no closure: it would be compiled without the target features).
        let mut range = [[f32::INFINITY, f32::NEG_INFINITY]; 4];
        for (i, r) in range.iter_mut().enumerate() {
            for (h, &k) in halves.iter().enumerate() {
                let x = _mm512_maskz_loadu_ps(k, rows.add(PACKET * (3 + i) + 16 * h));
                r[0] = r[0].min(_mm512_mask_reduce_min_ps(k, x));
                r[1] = r[1].max(_mm512_mask_reduce_max_ps(k, x));
            }
        }
        let t_high = _mm512_reduce_max_ps(_mm512_max_ps(
            _mm512_maskz_loadu_ps(halves[0], t_max.as_ptr()),
            _mm512_maskz_loadu_ps(halves[1], t_max.as_ptr().add(16)),
        ));
        PacketBounds::new(org, [range[0], range[1], range[2]], range[3], t_high)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
    unsafe fn t_low(t_max: &[f32; PACKET], rays: u32) -> f32 {
        let (k0, k1) = (rays as u16, (rays >> 16) as u16);
        let inf = _mm512_set1_ps(f32::INFINITY);
        _mm512_reduce_min_ps(_mm512_min_ps(
            _mm512_mask_loadu_ps(inf, k0, t_max.as_ptr()),
            _mm512_mask_loadu_ps(inf, k1, t_max.as_ptr().add(16)),
        ))
    }

    #[inline]
    #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
    unsafe fn node_packet_rows(
        p: &[MaybeUninit<Prepared>; PACKET],
        rows: &MaybeUninit<Rows>,
        node: &WideNode,
        active: u32,
        t_max: &[f32; PACKET],
    ) -> PacketNode {
        if crate::kernel::child_by_child() && active.count_ones() >= CHILD_BY_CHILD {
            if let Some(n) = Avx512::node_by_child(rows, node, active, t_max) {
                return n;
            }
        }
        Avx2::node_packet(p, node, active, t_max)
    }
}

impl Avx512 {
    /// The packet's node test child by child, sixteen rays at a time: the same results as
    /// [`Backend::node_packet`], or `None` when the active rays do not share their octant.
    ///
    /// # Safety
    /// The CPU has AVX2, FMA, AVX-512 F and VL; the lanes of `active` of `rows` are written
    /// ([`Backend::prepare8_rows`], [`Backend::row`]).
    #[inline]
    #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
    pub unsafe fn node_by_child(
        rows: &MaybeUninit<Rows>,
        node: &WideNode,
        active: u32,
        t_max: &[f32; PACKET],
    ) -> Option<PacketNode> {
        if active == 0 {
            return None;
        }
        let rows = rows.as_ptr() as *const f32;
        // The first active ray's octant; the others must share it.
        let lead = active.trailing_zeros() as usize;
        let octant = (*rows.add(PACKET * 7 + lead)).to_bits();
        let halves = [active as u16, (active >> 16) as u16];
        for (h, &k) in halves.iter().enumerate() {
            let oct = _mm512_maskz_loadu_epi32(k, rows.add(PACKET * 7 + 16 * h) as *const i32);
            if _mm512_mask_cmpneq_epi32_mask(k, oct, _mm512_set1_epi32(octant as i32)) != 0 {
                return None;
            }
        }
        Some(child_by_child(rows, node, halves, t_max, octant))
    }
}

/// The packet's node test child by child: for each child in use, the sixteen-lane slab test of
/// each half of the packet that has active rays (`halves`: the active lanes of each), whose
/// rays all have octant `octant`.
#[inline]
#[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
unsafe fn child_by_child(
    rows: *const f32,
    node: &WideNode,
    halves: [u16; 2],
    t_max: &[f32; PACKET],
    octant: u32,
) -> PacketNode {
    let (near, far) = planes_of(octant);
    // Each half's rays: origin, `1/dir`, interval start, the far planes' `1/dir · FAR` and
    // the interval's end times `IZE` (only active lanes read).
    let mut rays = [[_mm512_setzero_ps(); 11]; 2];
    let (far_factor, ize) = (_mm512_set1_ps(FAR), _mm512_set1_ps(IZE));
    for (h, &k) in halves.iter().enumerate() {
        if k != 0 {
            for (i, x) in rays[h].iter_mut().take(7).enumerate() {
                *x = _mm512_maskz_loadu_ps(k, rows.add(PACKET * i + 16 * h));
            }
            for a in 0..3 {
                rays[h][7 + a] = _mm512_mul_ps(rays[h][3 + a], far_factor);
            }
            rays[h][10] = _mm512_mul_ps(_mm512_maskz_loadu_ps(k, t_max.as_ptr().add(16 * h)), ize);
        }
    }
    let inf = _mm512_set1_ps(f32::INFINITY);
    let mut out = PacketNode { children: 0, rays: [0; WIDTH], dist: [f32::INFINITY; WIDTH] };
    let refs = _mm256_loadu_si256(node.children.as_ptr() as *const __m256i);
    let unused =
        _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(refs, _mm256_set1_epi32(EMPTY as i32))));
    let mut used = !(unused as u32) & 0xff;
    while used != 0 {
        let c = used.trailing_zeros() as usize;
        used &= used - 1;
        let plane = |row: usize| *node.bounds.get_unchecked(row).get_unchecked(c);
        let (n0, n1, n2) = (plane(near[0]), plane(near[1]), plane(near[2]));
        let (f0, f1, f2) = (plane(far[0]), plane(far[1]), plane(far[2]));
        let mut least = inf;
        let mut entered = 0u32;
        for (h, &k) in halves.iter().enumerate() {
            if k == 0 {
                continue;
            }
            let [ox, oy, oz, ix, iy, iz, t0, jx, jy, jz, t1] = rays[h];
            // (Macros rather than closures keep every intrinsic inside this function's target
            // features.)
            macro_rules! slab {
                ($plane:expr, $o:expr, $i:expr) => {
                    _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps($plane), $o), $i)
                };
            }
            let t_near = _mm512_max_ps(
                slab!(n0, ox, ix),
                _mm512_max_ps(slab!(n1, oy, iy), _mm512_max_ps(slab!(n2, oz, iz), t0)),
            );
            let t_far = _mm512_min_ps(
                slab!(f0, ox, jx),
                _mm512_min_ps(slab!(f1, oy, jy), _mm512_min_ps(slab!(f2, oz, jz), t1)),
            );
            let hit = _mm512_mask_cmp_ps_mask::<_CMP_LE_OQ>(k, t_near, t_far);
            entered |= (hit as u32) << (16 * h);
            least = _mm512_min_ps(_mm512_mask_blend_ps(hit, inf, t_near), least);
        }
        if entered != 0 {
            out.children |= 1 << c;
            *out.rays.get_unchecked_mut(c) = entered;
            *out.dist.get_unchecked_mut(c) = _mm512_reduce_min_ps(least);
        }
    }
    out
}
