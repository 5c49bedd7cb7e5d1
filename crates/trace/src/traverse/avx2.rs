//! The AVX2 kernel: a wide node's eight slab tests in one 256-bit register per plane, a leaf's
//! four watertight triangle tests in one 128-bit register per quantity (its ray form and
//! setup are in [`crate::traverse::avx2_ray`]); a packet's node test runs the node test for
//! each of its rays (the node's rows loaded once for all rays whose directions share their
//! signs) and keeps the masks and least distances in registers. A packet of rays from one
//! origin also keeps them as rows ([`Rows`]), from which it gets its [`PacketBounds`] for the
//! test of a node for the whole packet ([`Backend::whole`]): on a Zen 3 core the blob's
//! primary-ray packets went from 11.1–12.7 to 13.7–18.0 M rays/s. Each lane performs exactly
//! the scalar kernel's operations (fused multiply-adds where the scalar test calls `mul_add`,
//! separate operations elsewhere, `maxps`/`minps` operand order as the scalar
//! `max_ps`/`min_ps`), so both kernels produce the same bits. The kernel needs AVX2 and FMA.

#![cfg(target_arch = "x86_64")]

use crate::node::{TriBlock, WideNode, EMPTY, WIDTH};
use crate::ray::Ray;
use crate::traverse::avx2_ray::Prepared;
use crate::traverse::backend::{
    Backend, BlockHits, PacketBounds, PacketNode, RayQuery, Rows, FAR, IZE, LOOSE, PACKET,
};
use crate::triangle::{edge_functions_f64, EXACT_EDGES, FUSED};
use glam::Affine3A;
use std::arch::x86_64::*;
use std::mem::MaybeUninit;

/// Whether the block test computes every lane's distance even when no lane is inside its
/// triangle (on only to measure what the early exit saves).
const EAGER: bool = cfg!(feature = "measure-eager-division");

/// The AVX2 kernel.
#[derive(Clone, Copy, Debug)]
pub struct Avx2;

impl Backend for Avx2 {
    type Prepared = Prepared;

    /// The rows give a packet of rays from one origin its [`PacketBounds`] ([`Backend::bounds`]).
    const ROWS: bool = true;

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn prepare8_rows(
        rays: &[Ray; 8],
        out: &mut [MaybeUninit<Prepared>; 8],
        t_max: &mut [f32; 8],
        rows: &mut MaybeUninit<Rows>,
        h: usize,
    ) -> u32 {
        Prepared::eight(rays, out, t_max, Some((rows, h)))
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn row(p: &Prepared, rows: &mut MaybeUninit<Rows>, r: usize) {
        // The form's first 32 bytes are the eight quantities of the rows, in their order.
        let first = p as *const Prepared as *const f32;
        let base = rows.as_mut_ptr() as *mut f32;
        for i in 0..8 {
            *base.add(PACKET * i + r) = *first.add(i);
        }
    }

    /// Out of line: once per packet, and kept out of the packet walk's code.
    #[inline(never)]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn bounds(rows: &MaybeUninit<Rows>, valid: u32, t_max: &[f32; PACKET]) -> Option<PacketBounds> {
        let rows = rows.as_ptr() as *const f32;
        // Each group of eight lanes: its rays of `valid` as a lane mask (all ones where set).
        let lanes = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
        // (No closures here: they would be compiled without the target features.)
        let mut groups = [(0u32, _mm256_setzero_ps()); PACKET / 8];
        for (g, (k, m)) in groups.iter_mut().enumerate() {
            *k = (valid >> (8 * g)) & 0xff;
            let bits = _mm256_and_si256(_mm256_set1_epi32(*k as i32), lanes);
            *m = _mm256_castsi256_ps(_mm256_cmpeq_epi32(bits, lanes));
        }
        // Rays from several origins have no bounds: found first, in a few compares.
        let lead = valid.trailing_zeros() as usize;
        let mut org = [0.0f32; 3];
        for (q, o) in org.iter_mut().enumerate() {
            *o = *rows.add(PACKET * q + lead);
            for (g, &(k, m)) in groups.iter().enumerate() {
                // Masked loads: the lanes outside `valid` are not read (they may be unwritten).
                let x = _mm256_maskload_ps(rows.add(PACKET * q + 8 * g), _mm256_castps_si256(m));
                let differ = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_NEQ_UQ>(x, _mm256_set1_ps(*o))) as u32;
                if differ & k != 0 {
                    return None;
                }
            }
        }
        // The least and greatest `1/dir` per axis and interval start over the rays (rows 3 to
        // 6), and the greatest interval end; lanes outside `valid` count as ±∞.
        let (inf, ninf) = (_mm256_set1_ps(f32::INFINITY), _mm256_set1_ps(f32::NEG_INFINITY));
        let mut range = [[f32::INFINITY, f32::NEG_INFINITY]; 4];
        for (i, r) in range.iter_mut().enumerate() {
            let (mut lo, mut hi) = (inf, ninf);
            for (g, &(_, m)) in groups.iter().enumerate() {
                let x = _mm256_maskload_ps(rows.add(PACKET * (3 + i) + 8 * g), _mm256_castps_si256(m));
                lo = _mm256_min_ps(lo, _mm256_blendv_ps(inf, x, m));
                hi = _mm256_max_ps(hi, _mm256_blendv_ps(ninf, x, m));
            }
            *r = [reduce(lo, false), reduce(hi, true)];
        }
        let mut hi = ninf;
        for (g, &(_, m)) in groups.iter().enumerate() {
            hi = _mm256_max_ps(hi, _mm256_blendv_ps(ninf, _mm256_loadu_ps(t_max.as_ptr().add(8 * g)), m));
        }
        PacketBounds::new(org, [range[0], range[1], range[2]], range[3], reduce(hi, true))
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn prepare(q: &RayQuery) -> Prepared {
        Prepared::one(q)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn prepare_ray(ray: &Ray) -> Option<(Prepared, f32)> {
        Prepared::single(ray)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn prepare_transformed(ray: &Ray, m: &Affine3A, t_max: f32) -> Option<(Prepared, f32)> {
        Prepared::transformed(ray, m, t_max)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn prepare8(rays: &[Ray; 8], out: &mut [MaybeUninit<Prepared>; 8], t_max: &mut [f32; 8]) -> u32 {
        Prepared::eight(rays, out, t_max, None)
    }

    /// Out of line here: inlined, it measured the packet walk's rays from many points 10 % slower
    /// (their walk's code placed and allocated around a test they never run).
    #[inline(never)]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn whole(b: &PacketBounds, node: &WideNode, t_low: f32) -> Option<(u32, [f32; WIDTH])> {
        Avx2::whole_in_line(b, node, t_low)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn node(p: &Prepared, node: &WideNode, t_max: f32) -> (u32, [f32; 8]) {
        let (near, hit) = slabs::<false>(p, node, t_max);
        let mut dist = [0.0f32; 8];
        _mm256_storeu_ps(dist.as_mut_ptr(), near);
        (_mm256_movemask_ps(hit) as u32, dist)
    }

    #[inline(always)]
    fn tree_safe(p: &Prepared) -> bool {
        p.finite != 0
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn node_tree(p: &Prepared, node: &WideNode, t_max: f32) -> (u32, [f32; 8]) {
        let (near, hit) = slabs::<true>(p, node, t_max);
        let mut dist = [0.0f32; 8];
        _mm256_storeu_ps(dist.as_mut_ptr(), near);
        (_mm256_movemask_ps(hit) as u32, dist)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn node_packet(
        p: &[MaybeUninit<Prepared>; PACKET],
        node: &WideNode,
        active: u32,
        t_max: &[f32; PACKET],
    ) -> PacketNode {
        let inf = _mm256_set1_ps(f32::INFINITY);
        let mut least = inf;
        let mut rows = [0u64; PACKET / 8];
        if active == 0 {
            return PacketNode::from_rows(&rows, [f32::INFINITY; WIDTH]);
        }
        // The rows the first ray reads, loaded once for every ray of its octant (in a coherent
        // packet, all of them).
        let lead = p.get_unchecked(active.trailing_zeros() as usize).assume_init_ref();
        let shared = planes(lead, node);
        // Rays of another octant wait for a second pass, so that the first keeps the shared
        // rows in registers.
        let (mut a, mut others) = (active, 0u32);
        while a != 0 {
            let r = a.trailing_zeros() as usize;
            a &= a - 1;
            let q = p.get_unchecked(r).assume_init_ref();
            if q.octant != lead.octant {
                others |= 1 << r;
                continue;
            }
            let (near, hit) = slabs_of::<false>(q, &shared, *t_max.get_unchecked(r));
            *rows.get_unchecked_mut(r / 8) |= (_mm256_movemask_ps(hit) as u32 as u64) << (8 * (r % 8));
            least = _mm256_min_ps(_mm256_blendv_ps(inf, near, hit), least);
        }
        while others != 0 {
            let r = others.trailing_zeros() as usize;
            others &= others - 1;
            let (near, hit) =
                slabs::<false>(p.get_unchecked(r).assume_init_ref(), node, *t_max.get_unchecked(r));
            *rows.get_unchecked_mut(r / 8) |= (_mm256_movemask_ps(hit) as u32 as u64) << (8 * (r % 8));
            least = _mm256_min_ps(_mm256_blendv_ps(inf, near, hit), least);
        }
        let mut dist = [0.0f32; WIDTH];
        _mm256_storeu_ps(dist.as_mut_ptr(), least);
        PacketNode::from_rows(&rows, dist)
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn reaching(t_max: &[f32; PACKET], rays: u32, dist: f32) -> u32 {
        let (d, ize) = (_mm256_set1_ps(dist), _mm256_set1_ps(IZE));
        let mut keep = 0u32;
        for h in 0..PACKET / 8 {
            let t = _mm256_mul_ps(_mm256_loadu_ps(t_max.as_ptr().add(8 * h)), ize);
            keep |= (_mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(d, t)) as u32) << (8 * h);
        }
        rays & keep
    }

    #[inline]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn block(p: &Prepared, block: &TriBlock, t_max: f32) -> BlockHits {
        block_with(&Frame::of(p), block, t_max)
    }
}

/// What the triangle test reads of a ray, in registers: its origin along `kx`, `ky`, `kz` and
/// its shear, broadcast, the byte offsets of the `kx`, `ky`, `kz` rows within a vertex's
/// three rows of a [`TriBlock`], and the interval's start, broadcast.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub(crate) tri_org: [__m128; 3],
    pub(crate) shear: [__m128; 3],
    pub(crate) k: [usize; 3],
    pub(crate) t_min: __m128,
}

impl Frame {
    /// The frame of the ray `p`.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    pub(crate) unsafe fn of(p: &Prepared) -> Frame {
        let (o, s) = (p.tri_org, p.shear);
        Frame {
            tri_org: [_mm_set1_ps(o[0]), _mm_set1_ps(o[1]), _mm_set1_ps(o[2])],
            shear: [_mm_set1_ps(s[0]), _mm_set1_ps(s[1]), _mm_set1_ps(s[2])],
            k: [16 * p.k[0] as usize, 16 * p.k[1] as usize, 16 * p.k[2] as usize],
            t_min: _mm_set1_ps(p.t_min),
        }
    }
}

/// The watertight test of a block's four triangles for the ray whose frame is `frame`
/// ([`Backend::block`]).
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn block_with(frame: &Frame, block: &TriBlock, t_max: f32) -> BlockHits {
    let [kx, ky, kz] = frame.k;
    let [sx, sy, sz] = frame.shear;
    let tri_org = frame.tri_org;
    // Rows are 16-byte aligned ([`TriBlock`] is `align(16)`, rows are 16 bytes); `k` holds
    // offsets of rows 0..3 of a vertex.
    let base = block.v.as_ptr() as *const u8;
    macro_rules! rel {
        ($j:expr) => {
            (
                _mm_sub_ps(_mm_load_ps(base.add(48 * $j + kx) as *const f32), tri_org[0]),
                _mm_sub_ps(_mm_load_ps(base.add(48 * $j + ky) as *const f32), tri_org[1]),
                _mm_sub_ps(_mm_load_ps(base.add(48 * $j + kz) as *const f32), tri_org[2]),
            )
        };
    }
    let (a_x, a_y, a_z) = rel!(0);
    let (b_x, b_y, b_z) = rel!(1);
    let (c_x, c_y, c_z) = rel!(2);
    let ax = _mm_sub_ps(a_x, _mm_mul_ps(sx, a_z));
    let ay = _mm_sub_ps(a_y, _mm_mul_ps(sy, a_z));
    let bx = _mm_sub_ps(b_x, _mm_mul_ps(sx, b_z));
    let by = _mm_sub_ps(b_y, _mm_mul_ps(sy, b_z));
    let cx = _mm_sub_ps(c_x, _mm_mul_ps(sx, c_z));
    let cy = _mm_sub_ps(c_y, _mm_mul_ps(sy, c_z));
    let mut u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
    let mut v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
    let mut w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
    let zero = _mm_setzero_ps();
    let mut inside = inside(u, v, w);
    if !EAGER && _mm_movemask_ps(inside) == 0 {
        return BlockHits::default();
    }
    if EXACT_EDGES {
        let on_edge =
            _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero));
        let on_edge = _mm_movemask_ps(_mm_and_ps(on_edge, inside));
        if on_edge != 0 {
            (u, v, w) = exact_edges(on_edge, [ax, ay, bx, by, cx, cy], [u, v, w]);
            inside = self::inside(u, v, w);
        }
    }
    let det = _mm_add_ps(_mm_add_ps(u, v), w);
    let az = _mm_mul_ps(sz, a_z);
    let bz = _mm_mul_ps(sz, b_z);
    let cz = _mm_mul_ps(sz, c_z);
    let tt = fmadd(w, cz, fmadd(v, bz, _mm_mul_ps(u, az)));
    let rcp = _mm_div_ps(_mm_set1_ps(1.0), det);
    let t = _mm_mul_ps(tt, rcp);
    let in_range = _mm_and_ps(_mm_cmpge_ps(t, frame.t_min), _mm_cmple_ps(t, _mm_set1_ps(t_max)));
    let ok = _mm_and_ps(inside, _mm_and_ps(_mm_cmpneq_ps(det, zero), in_range));
    let mask = _mm_movemask_ps(ok) as u32;
    let mut hits = BlockHits { mask, ..BlockHits::default() };
    if mask != 0 {
        _mm_storeu_ps(hits.t.as_mut_ptr(), t);
        _mm_storeu_ps(hits.u.as_mut_ptr(), _mm_mul_ps(v, rcp));
        _mm_storeu_ps(hits.v.as_mut_ptr(), _mm_mul_ps(w, rcp));
    }
    hits
}

/// The slab tests of a node's eight children: the entry distances and which children the
/// ray enters before `t_max`.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn slabs<const TREE: bool>(p: &Prepared, node: &WideNode, t_max: f32) -> (__m256, __m256) {
    slabs_of::<TREE>(p, &planes(p, node), t_max)
}

/// The node's rows that ray `p` reads, in the order near x, y, z, far x, y, z (the same for
/// every ray of one octant, [`Prepared::octant`]).
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn planes(p: &Prepared, node: &WideNode) -> [__m256; 6] {
    // Rows are 32-byte aligned ([`WideNode`] is `align(32)`, rows are 32 bytes); the row
    // indices are 0..6 by construction of [`RayQuery`].
    let row = |r: u32| node.bounds.get_unchecked(r as usize).as_ptr();
    let [n0, n1, n2, f0, f1, f2] =
        [row(p.near[0]), row(p.near[1]), row(p.near[2]), row(p.far[0]), row(p.far[1]), row(p.far[2])];
    [
        _mm256_load_ps(n0),
        _mm256_load_ps(n1),
        _mm256_load_ps(n2),
        _mm256_load_ps(f0),
        _mm256_load_ps(f1),
        _mm256_load_ps(f2),
    ]
}

/// [`slabs`] with the ray's rows of the node already loaded ([`planes`]).
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn slabs_of<const TREE: bool>(p: &Prepared, planes: &[__m256; 6], t_max: f32) -> (__m256, __m256) {
    let (org, inv, inv_far) = (broadcast3(p.org), broadcast3(p.inv), broadcast3(p.inv_far));
    slabs_with::<TREE>(&org, &inv, &inv_far, _mm256_set1_ps(p.t_min), planes, t_max)
}

/// Each of three scalars broadcast to a register.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn broadcast3(x: [f32; 3]) -> [__m256; 3] {
    [_mm256_set1_ps(x[0]), _mm256_set1_ps(x[1]), _mm256_set1_ps(x[2])]
}

/// The slab tests of the rows `planes` (near x, y, z, far x, y, z) for a ray whose origin,
/// `1/dir`, `inv · FAR` and interval start are broadcast: the entry distances and which
/// children the ray enters before `t_max`.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn slabs_with<const TREE: bool>(
    org: &[__m256; 3],
    inv: &[__m256; 3],
    inv_far: &[__m256; 3],
    t0: __m256,
    planes: &[__m256; 6],
    t_max: f32,
) -> (__m256, __m256) {
    // (Macros rather than closures keep every intrinsic inside this function's target
    // features.)
    macro_rules! slab {
        ($a:expr, $plane:expr, $inv:expr) => {
            _mm256_mul_ps(_mm256_sub_ps($plane, org[$a]), $inv[$a])
        };
    }
    let (n0, n1, n2) = (slab!(0, planes[0], inv), slab!(1, planes[1], inv), slab!(2, planes[2], inv));
    let (f0, f1, f2) =
        (slab!(0, planes[3], inv_far), slab!(1, planes[4], inv_far), slab!(2, planes[5], inv_far));
    entries::<TREE>([n0, n1, n2], [f0, f1, f2], t0, t_max)
}

/// The entry distances (the largest of the near planes' distances and `t0`) and the
/// children entered (those whose entry is at most their exit, the smallest of the far planes'
/// distances and `t_max · IZE`), from the six planes' distances.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn entries<const TREE: bool>(
    [n0, n1, n2]: [__m256; 3],
    [f0, f1, f2]: [__m256; 3],
    t0: __m256,
    t_max: f32,
) -> (__m256, __m256) {
    let t1 = _mm256_set1_ps(t_max * IZE);
    // Two levels where no term can be NaN ([`Prepared::finite`], the walk's choice), else the
    // chain whose order ignores NaN terms; the same values either way.
    let (near, far) = if TREE {
        (
            _mm256_max_ps(_mm256_max_ps(n0, n1), _mm256_max_ps(n2, t0)),
            _mm256_min_ps(_mm256_min_ps(f0, f1), _mm256_min_ps(f2, t1)),
        )
    } else {
        (
            _mm256_max_ps(n0, _mm256_max_ps(n1, _mm256_max_ps(n2, t0))),
            _mm256_min_ps(f0, _mm256_min_ps(f1, _mm256_min_ps(f2, t1))),
        )
    };
    (near, _mm256_cmp_ps::<_CMP_LE_OQ>(near, far))
}

/// `a·b + c`, fused as [`crate::triangle::fused`].
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn fmadd(a: __m128, b: __m128, c: __m128) -> __m128 {
    if FUSED {
        _mm_fmadd_ps(a, b, c)
    } else {
        _mm_add_ps(_mm_mul_ps(a, b), c)
    }
}

/// The lanes whose edge functions share a sign: `min(u, v, w) ≥ 0` or `max(u, v, w) ≤ 0`, as
/// [`crate::triangle::inside`].
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn inside(u: __m128, v: __m128, w: __m128) -> __m128 {
    let zero = _mm_setzero_ps();
    _mm_or_ps(
        _mm_cmpge_ps(_mm_min_ps(u, _mm_min_ps(v, w)), zero),
        _mm_cmple_ps(_mm_max_ps(u, _mm_max_ps(v, w)), zero),
    )
}

/// Recomputes the edge functions of the lanes in `lanes` in f64, as the scalar test does.
#[cold]
#[inline(never)]
#[target_feature(enable = "avx2,fma")]
unsafe fn exact_edges(lanes: i32, proj: [__m128; 6], uvw: [__m128; 3]) -> (__m128, __m128, __m128) {
    let mut p = [[0.0f32; 4]; 6];
    for (dst, src) in p.iter_mut().zip(proj) {
        _mm_storeu_ps(dst.as_mut_ptr(), src);
    }
    let mut e = [[0.0f32; 4]; 3];
    for (dst, src) in e.iter_mut().zip(uvw) {
        _mm_storeu_ps(dst.as_mut_ptr(), src);
    }
    for lane in 0..4 {
        if lanes & (1 << lane) != 0 {
            let [u, v, w] =
                edge_functions_f64(p[0][lane], p[1][lane], p[2][lane], p[3][lane], p[4][lane], p[5][lane]);
            (e[0][lane], e[1][lane], e[2][lane]) = (u, v, w);
        }
    }
    (_mm_loadu_ps(e[0].as_ptr()), _mm_loadu_ps(e[1].as_ptr()), _mm_loadu_ps(e[2].as_ptr()))
}

impl Avx2 {
    /// [`Backend::whole`]'s test, to be inlined (the AVX-512 kernel's, which keeps it in line).
    ///
    /// # Safety
    /// The CPU has AVX2 and FMA.
    #[inline]
    #[target_feature(enable = "avx2,fma")]
    pub(crate) unsafe fn whole_in_line(
        b: &PacketBounds,
        node: &WideNode,
        t_low: f32,
    ) -> Option<(u32, [f32; WIDTH])> {
        // `PacketBounds::decide` with the eight children in the lanes: the same operations.
        let mut near = [[_mm256_setzero_ps(); 2]; 3];
        let mut far = [[_mm256_setzero_ps(); 2]; 3];
        for a in 0..3 {
            let o = _mm256_set1_ps(b.org[a]);
            let [i0, i1] = b.inv[a];
            for (out, row, [i0, i1]) in
                [(&mut near[a], b.near[a], [i0, i1]), (&mut far[a], b.far[a], [i0 * FAR, i1 * FAR])]
            {
                let x = _mm256_sub_ps(_mm256_load_ps(node.bounds.get_unchecked(row).as_ptr()), o);
                let (p0, p1) = (_mm256_mul_ps(x, _mm256_set1_ps(i0)), _mm256_mul_ps(x, _mm256_set1_ps(i1)));
                *out = [_mm256_min_ps(p0, p1), _mm256_max_ps(p0, p1)];
            }
        }
        let near_low = _mm256_max_ps(
            _mm256_max_ps(near[0][0], near[1][0]),
            _mm256_max_ps(near[2][0], _mm256_set1_ps(b.t_min[0])),
        );
        let near_high = _mm256_max_ps(
            _mm256_max_ps(near[0][1], near[1][1]),
            _mm256_max_ps(near[2][1], _mm256_set1_ps(b.t_min[1])),
        );
        let far_low = _mm256_min_ps(
            _mm256_min_ps(far[0][0], far[1][0]),
            _mm256_min_ps(far[2][0], _mm256_set1_ps(t_low * IZE)),
        );
        let far_high = _mm256_min_ps(
            _mm256_min_ps(far[0][1], far[1][1]),
            _mm256_min_ps(far[2][1], _mm256_set1_ps(b.t_max * IZE)),
        );
        let none = _mm256_cmp_ps::<_CMP_GT_OQ>(near_low, far_high);
        let every = _mm256_cmp_ps::<_CMP_LE_OQ>(near_high, far_low);
        let undecided = !_mm256_movemask_ps(_mm256_or_ps(none, every)) as u32 & 0xff;
        if undecided != 0 {
            // Leaf references have the top bit set (and so does `EMPTY`).
            let refs = _mm256_loadu_si256(node.children.as_ptr() as *const __m256i);
            let empty = _mm256_cmpeq_epi32(refs, _mm256_set1_epi32(EMPTY as i32));
            let leaves =
                _mm256_movemask_ps(_mm256_andnot_ps(_mm256_castsi256_ps(empty), _mm256_castsi256_ps(refs)));
            if undecided.count_ones() > LOOSE || leaves != 0 {
                return None;
            }
        }
        let mut dist = [0.0f32; WIDTH];
        _mm256_storeu_ps(dist.as_mut_ptr(), near_low);
        Some((!_mm256_movemask_ps(none) as u32 & 0xff, dist))
    }
}

/// The least (or, with `max`, the greatest) of the eight lanes of `x` (none NaN).
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn reduce(x: __m256, max: bool) -> f32 {
    let (lo, hi) = (_mm256_castps256_ps128(x), _mm256_extractf128_ps::<1>(x));
    if max {
        let x = _mm_max_ps(lo, hi);
        let x = _mm_max_ps(x, _mm_movehl_ps(x, x));
        _mm_cvtss_f32(_mm_max_ps(x, _mm_shuffle_ps::<1>(x, x)))
    } else {
        let x = _mm_min_ps(lo, hi);
        let x = _mm_min_ps(x, _mm_movehl_ps(x, x));
        _mm_cvtss_f32(_mm_min_ps(x, _mm_shuffle_ps::<1>(x, x)))
    }
}
