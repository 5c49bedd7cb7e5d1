//! The interface between the generic walk and its kernels: what a kernel computes for one
//! wide node (which children the ray enters, and at what distance) and for one leaf block
//! (which triangles it hits, where).
//!
//! Slab test. For each axis the ray enters a child's slab at `(near − o)·inv` and leaves it at
//! `(far − o)·inv`, where `inv = 1/dir` and near/far are the min or max plane by the sign of
//! `inv`. A zero direction component gives `inv = ±∞`; a ray lying exactly in a slab's plane
//! then gives `0·∞ = NaN`, and the min/max below are ordered so that a NaN distance is ignored
//! (each is `x86`'s `maxps(a, b)`: `if a > b { a } else { b }`, which returns `b` when `a` is
//! NaN), i.e. the ray counts as inside that slab.
//!
//! Rounding is made conservative as Ize proposes ("Robust BVH ray traversal", JCGT 2013):
//! rounding can add a box the ray misses, never drop one it hits, so a ray aimed exactly at a
//! vertex or edge reaches every triangle there and the watertight test decides. Ize scales
//! the far distance by `1 + 2γ₃`; here the factor is carried by the ray instead, so that the
//! node test's chain of dependent operations has no multiply after its minimum: the far
//! planes' distances use `inv_far = fl(inv · FAR)` ([`FAR`], `1 + 2γ₅`) and the interval's
//! end is `fl(t_max · IZE)`. With `N` and `F` a box's exact entry and exit distances for
//! the exact direction, the computed entry distance (three roundings: `1/dir`, the
//! subtraction, the product) is at most `N·(1 + γ₃)` and the computed exit distance (four:
//! those and `inv · FAR`) at least `F·FAR·(1 − γ₄)`, which is at least `F·(1 + γ₃)`; so
//! `N ≤ F` implies that the computed entry is at most the computed exit, and likewise
//! against the interval's end scaled by `IZE`.

use crate::node::{TriBlock, WideNode, EMPTY, LEAF_BIT, WIDTH};
use crate::ray::Ray;
use crate::triangle::TriRay;

pub use crate::lanes::{max_ps, min_ps};
use glam::{Affine3A, Vec3};
use std::mem::MaybeUninit;

/// `1 + 2γ₃` with `γₙ = nε / (1 − nε)`, `ε = 2⁻²⁴`: Ize's factor for the far slab distance.
/// (1 only to measure what the factor costs; then rounding may drop a box a ray touches.)
pub const IZE: f32 = if cfg!(feature = "measure-no-ize") {
    1.0
} else {
    1.0 + 2.0 * (3.0 * 5.960_464_5e-8 / (1.0 - 3.0 * 5.960_464_5e-8))
};

/// `1 + 2γ₅`: the factor on `1/dir` for a ray's far planes (see the module's text). (1 only
/// to measure what the factors cost, with [`IZE`].)
pub const FAR: f32 = if cfg!(feature = "measure-no-ize") {
    1.0
} else {
    1.0 + 2.0 * (5.0 * 5.960_464_5e-8 / (1.0 - 5.0 * 5.960_464_5e-8))
};

/// Rays a packet query traces together (a multiple of 8, at most 32: ray masks are `u32`).
pub const PACKET: usize = 32;

/// A packet's rays one quantity to a row, a lane per ray: origin x, y, z, `1/dir` x, y, z,
/// the interval's start, and the octant ([`crate::traverse::avx2_ray::Prepared`]'s, as an
/// integer's bits). What a kernel that tests many rays against one child at a time reads
/// ([`Backend::ROWS`]); the lanes of rays not in the packet may hold anything and are never
/// read.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub struct Rows(pub [[f32; PACKET]; 8]);

/// The rows of [`WideNode::bounds`] holding the near and the far plane of each axis for a
/// direction of octant `octant` (bit `a` set where the direction's component `a` is
/// negative): the minima's row `2a` and the maxima's `2a + 1`, swapped for a negative axis.
#[inline(always)]
pub fn planes_of(octant: u32) -> ([usize; 3], [usize; 3]) {
    let sign = |a: usize| ((octant >> a) & 1) as usize;
    ([0, 1, 2].map(|a| 2 * a + sign(a)), [0, 1, 2].map(|a| 2 * a + 1 - sign(a)))
}

/// Undecided children ([`PacketBounds::decide`]) up to which a node of inner children is taken
/// for the whole packet, conservatively.
pub const LOOSE: u32 = 2;

/// What bounds a packet's rays' slab tests: the range over the packet's rays of each quantity
/// the test reads (`1/dir`, the interval's start, and its end as it was set up, which hits only
/// lower) for rays from one origin whose directions share their signs and have no zero
/// component: a pinhole camera's rays, say. From it interval arithmetic bounds every ray's
/// entry and exit distance of each child box, so one test of a node's eight children serves
/// all the rays where it decides them ([`PacketBounds::decide`]), in place of a test per ray.
///
/// Only for rays from one origin: for rays from many points (bounce and shadow rays) the
/// bounds decide few children and, measured, the test cost more than it saved.
#[derive(Clone, Copy, Debug)]
pub struct PacketBounds {
    /// The rays' origin.
    pub org: [f32; 3],
    /// Least and greatest `1/dir` per axis (one sign per axis, finite).
    pub inv: [[f32; 2]; 3],
    /// Least and greatest interval start.
    pub t_min: [f32; 2],
    /// Greatest interval end.
    pub t_max: f32,
    /// The row of the near plane per axis, shared by all the rays.
    pub near: [usize; 3],
    /// The row of the far plane per axis.
    pub far: [usize; 3],
}

impl PacketBounds {
    /// The bounds of rays from `org` whose `1/dir`, interval starts and ends range over `inv`,
    /// `t_min` (least and greatest per axis) and up to `t_max`; `None` where the ranges of
    /// `1/dir` do not keep one sign per axis or are not finite. (The kernel finds that the
    /// rays share their origin before it asks.)
    pub fn new(org: [f32; 3], inv: [[f32; 2]; 3], t_min: [f32; 2], t_max: f32) -> Option<PacketBounds> {
        let signed = inv.iter().all(|&[lo, hi]| lo.is_finite() && hi.is_finite() && (hi < 0.0 || lo > 0.0));
        let octant = (0..3).fold(0, |o, a| o | ((inv[a][1] < 0.0) as u32) << a);
        let (near, far) = planes_of(octant);
        signed.then_some(PacketBounds { org, inv, t_min, t_max, near, far })
    }

    /// The children of `node` taken for every ray of a set whose interval ends are at least
    /// `t_low`, and per child a distance at or below every ray's entry distance; `None` where
    /// the rays must be tested one by one.
    ///
    /// A child is *decided* when every ray enters it or none does; the mask then holds the ones
    /// every ray enters, exactly what each ray's own test says. Over the range of `1/dir`,
    /// `(plane − o)·inv` is greatest and least at its ends (and `inv · FAR` ranges over the
    /// ends' products), and each operation rounds monotonically, so the ends' rounded values
    /// bound every ray's rounded value. Where at
    /// most [`LOOSE`] children are undecided and none of the node's children is a leaf, the mask
    /// also holds the undecided ones, which the rays then enter conservatively (some may not
    /// reach them, and are dropped by their own tests further down, before any leaf); the
    /// hits stay those of the single-ray walk, whose leaf tests each ray still reaches only
    /// through its own box test of the leaf.
    #[inline(always)]
    pub fn decide(&self, node: &WideNode, t_low: f32) -> Option<(u32, [f32; WIDTH])> {
        let (mut every, mut none) = (0u32, 0u32);
        let mut dist = [f32::INFINITY; WIDTH];
        for (c, d) in dist.iter_mut().enumerate() {
            let range = |a: usize, row: usize, [i0, i1]: [f32; 2]| {
                let x = node.bounds[row][c] - self.org[a];
                let (p0, p1) = (x * i0, x * i1);
                (p0.min(p1), p0.max(p1))
            };
            let near = |a: usize| range(a, self.near[a], self.inv[a]);
            let far = |a: usize| range(a, self.far[a], self.inv[a].map(|i| i * FAR));
            let (nx, ny, nz) = (near(0), near(1), near(2));
            let (fx, fy, fz) = (far(0), far(1), far(2));
            let near_low = nx.0.max(ny.0).max(nz.0.max(self.t_min[0]));
            let near_high = nx.1.max(ny.1).max(nz.1.max(self.t_min[1]));
            let far_low = fx.0.min(fy.0).min(fz.0.min(t_low * IZE));
            let far_high = fx.1.min(fy.1).min(fz.1.min(self.t_max * IZE));
            none |= ((near_low > far_high) as u32) << c;
            every |= ((near_high <= far_low) as u32) << c;
            *d = near_low;
        }
        let undecided = !(every | none) & 0xff;
        let leaves = node.children.iter().filter(|&&c| c & LEAF_BIT != 0 && c != EMPTY).count();
        (undecided == 0 || (undecided.count_ones() <= LOOSE && leaves == 0)).then_some((!none & 0xff, dist))
    }
}

/// What a packet's node test finds.
#[derive(Clone, Copy, Debug)]
pub struct PacketNode {
    /// Bit `c` set for each child that some ray enters.
    pub children: u32,
    /// Per child, the rays that enter it (bit `r`: ray `r`).
    pub rays: [u32; WIDTH],
    /// Per child, the least entry distance among the rays that enter it (+∞ where none does).
    pub dist: [f32; WIDTH],
}

impl PacketNode {
    /// The result from each ray's child mask, eight rays to a `u64` (bit `c` of byte `r % 8`
    /// of `rows[r / 8]`: ray `r` enters child `c`), and the distances.
    #[inline(always)]
    pub fn from_rows(rows: &[u64; PACKET / 8], dist: [f32; WIDTH]) -> PacketNode {
        let mut rays = [0u32; WIDTH];
        let mut any = 0u64;
        for (h, &x) in rows.iter().enumerate() {
            any |= x;
            let t = transpose8(x);
            for (c, r) in rays.iter_mut().enumerate() {
                *r |= (((t >> (8 * c)) & 0xff) as u32) << (8 * h);
            }
        }
        let children = (0..8).fold(0u64, |acc, b| acc | (any >> (8 * b))) as u32 & 0xff;
        PacketNode { children, rays, dist }
    }
}

/// What every kernel needs of a ray: its slab-test and triangle-test forms.
#[derive(Clone, Copy, Debug)]
pub struct RayQuery {
    /// The origin.
    pub org: [f32; 3],
    /// `1/dir` per axis (±∞ for a zero component).
    pub inv: [f32; 3],
    /// Row of [`WideNode::bounds`] holding each axis's near plane.
    pub near: [usize; 3],
    /// Row holding each axis's far plane.
    pub far: [usize; 3],
    /// The interval's start (at least 0).
    pub t_min: f32,
    /// The interval's end as the ray was given.
    pub t_max: f32,
    /// `inv · FAR` per axis: the far planes' factor ([`FAR`]).
    pub inv_far: [f32; 3],
    /// The sheared frame of the watertight test.
    pub tri: TriRay,
}

impl RayQuery {
    /// The query for `ray`, or `None` when the ray can hit nothing: a non-finite origin or
    /// direction, a zero direction, or an empty or NaN interval.
    #[inline(always)]
    pub fn new(ray: &Ray) -> Option<RayQuery> {
        let t_min = if ray.t_min > 0.0 { ray.t_min } else { 0.0 };
        if ray.t_min.is_nan()
            || !(ray.origin.is_finite() && ray.dir.is_finite() && ray.dir != Vec3::ZERO && t_min <= ray.t_max)
        {
            return None;
        }
        let d = ray.dir.to_array();
        let inv = d.map(|x| 1.0 / x);
        let (near, far) = planes_of((0..3).fold(0, |o, a| o | (inv[a].is_sign_negative() as u32) << a));
        Some(RayQuery {
            org: ray.origin.to_array(),
            inv,
            near,
            far,
            t_min,
            t_max: ray.t_max,
            inv_far: inv.map(|x| x * FAR),
            tri: TriRay::new(ray.origin, ray.dir),
        })
    }
}

/// The triangles of one block a ray hits within its interval.
#[derive(Clone, Copy, Debug, Default)]
pub struct BlockHits {
    /// Bit `lane` is set for each lane hit.
    pub mask: u32,
    /// Distance per lane (meaningful where the mask is set).
    pub t: [f32; 4],
    /// Weight of the second vertex per lane.
    pub u: [f32; 4],
    /// Weight of the third vertex per lane.
    pub v: [f32; 4],
}

/// A kernel: the slab test of a wide node and the watertight test of a leaf block.
///
/// # Safety
/// The methods may use CPU features the implementation names; callers must have checked that
/// the CPU has them (see [`crate::kernel::Kernel::available`]).
pub trait Backend {
    /// The ray in the kernel's own form (broadcast into registers, say).
    type Prepared: Copy;

    /// The ray's kernel form.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    unsafe fn prepare(q: &RayQuery) -> Self::Prepared;

    /// The kernel form of `ray` and its interval end, or `None` when [`RayQuery::new`]
    /// rejects it (the ray can hit nothing). Kernels may override it with a faster form of
    /// the same results.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    #[inline(always)]
    unsafe fn prepare_ray(ray: &Ray) -> Option<(Self::Prepared, f32)> {
        RayQuery::new(ray).map(|q| (Self::prepare(&q), q.t_max))
    }

    /// [`Backend::prepare_ray`] of `ray` carried by `m` ([`Ray::transformed`], as into an
    /// instance's object space) with its interval ending at `t_max`. Kernels may override it
    /// with a faster form of the same results.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    #[inline(always)]
    unsafe fn prepare_transformed(ray: &Ray, m: &Affine3A, t_max: f32) -> Option<(Self::Prepared, f32)> {
        let mut carried = ray.transformed(m);
        carried.t_max = t_max;
        Self::prepare_ray(&carried)
    }

    /// The kernel forms of eight rays (a packet's setup): lane `i` of `out` and `t_max[i]` (the
    /// ray's interval end) are written for each ray `i` that [`RayQuery::new`] accepts, and
    /// the result has bit `i` set; the other lanes get `t_max` −∞ and nothing that is read.
    /// Kernels may override it with a faster form of the same results.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    #[inline(always)]
    unsafe fn prepare8(
        rays: &[Ray; 8],
        out: &mut [MaybeUninit<Self::Prepared>; 8],
        t_max: &mut [f32; 8],
    ) -> u32 {
        let mut valid = 0;
        for (i, ray) in rays.iter().enumerate() {
            t_max[i] = f32::NEG_INFINITY;
            if let Some(q) = RayQuery::new(ray) {
                out[i].write(Self::prepare(&q));
                t_max[i] = q.t_max;
                valid |= 1 << i;
            }
        }
        valid
    }

    /// Whether the kernel's packet node test reads the packet's [`Rows`]: then the packet
    /// writes them as it takes its rays ([`Backend::prepare8_rows`], [`Backend::row`]).
    const ROWS: bool = false;

    /// Whether the kernel's packet node test ([`Backend::node_packet_rows`]) reads the rows of
    /// every packet (kernels with [`Backend::ROWS`]); otherwise only packets of rays from one
    /// origin keep rows, for their bounds. Read once per packet.
    #[inline(always)]
    fn rows_always() -> bool {
        false
    }

    /// [`Backend::prepare8`], also writing lanes `8·h .. 8·h + 8` of `rows` for the rays it
    /// accepts (kernels with [`Backend::ROWS`]; the others leave `rows` alone).
    ///
    /// # Safety
    /// The CPU has the kernel's features; `h < PACKET / 8`.
    #[inline(always)]
    unsafe fn prepare8_rows(
        rays: &[Ray; 8],
        out: &mut [MaybeUninit<Self::Prepared>; 8],
        t_max: &mut [f32; 8],
        rows: &mut MaybeUninit<Rows>,
        h: usize,
    ) -> u32 {
        let _ = (rows, h);
        Self::prepare8(rays, out, t_max)
    }

    /// The bounds of the slab tests of a packet's rays `valid` ([`PacketBounds`]), where the
    /// kernel finds them (kernels with [`Backend::ROWS`], from the rows); `None` otherwise.
    ///
    /// # Safety
    /// The CPU has the kernel's features; the lanes of `valid` of `rows` are written.
    #[inline(always)]
    unsafe fn bounds(rows: &MaybeUninit<Rows>, valid: u32, t_max: &[f32; PACKET]) -> Option<PacketBounds> {
        let _ = (rows, valid, t_max);
        None
    }

    /// The least interval end of the rays of `rays`.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    #[inline(always)]
    unsafe fn t_low(t_max: &[f32; PACKET], rays: u32) -> f32 {
        let (mut low, mut r) = (f32::INFINITY, rays);
        while r != 0 {
            low = low.min(t_max[r.trailing_zeros() as usize]);
            r &= r - 1;
        }
        low
    }

    /// The children of `node` that `b` decides for every ray of a set whose interval ends are
    /// at least `t_low` ([`PacketBounds::decide`]). Kernels may override it with a faster form
    /// of the same results.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    #[inline(always)]
    unsafe fn whole(b: &PacketBounds, node: &WideNode, t_low: f32) -> Option<(u32, [f32; WIDTH])> {
        b.decide(node, t_low)
    }

    /// Writes lane `r` of `rows` for the ray `p` (kernels with [`Backend::ROWS`]).
    ///
    /// # Safety
    /// The CPU has the kernel's features; `r < PACKET`.
    #[inline(always)]
    unsafe fn row(p: &Self::Prepared, rows: &mut MaybeUninit<Rows>, r: usize) {
        let _ = (p, rows, r);
    }

    /// Bit `i` of the mask is set when the ray enters child `i` before `t_max`; `dist[i]` is
    /// the distance at which it does (at least `t_min`).
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    unsafe fn node(p: &Self::Prepared, node: &WideNode, t_max: f32) -> (u32, [f32; 8]);

    /// Whether [`Backend::node_tree`] may test nodes for the ray `p`: where none of its slab
    /// distances can be NaN (every `1/dir` finite). The walk asks once per ray.
    #[inline(always)]
    fn tree_safe(p: &Self::Prepared) -> bool {
        let _ = p;
        false
    }

    /// [`Backend::node`] for a ray that [`Backend::tree_safe`] accepts: the same results, which
    /// a kernel may compute with a shorter chain of dependent operations (the maximum and
    /// minimum of the slab distances as a tree, not a chain ordered to ignore NaNs).
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    #[inline(always)]
    unsafe fn node_tree(p: &Self::Prepared, node: &WideNode, t_max: f32) -> (u32, [f32; 8]) {
        Self::node(p, node, t_max)
    }

    /// The block's triangles hit within `[t_min, t_max]`.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    unsafe fn block(p: &Self::Prepared, block: &TriBlock, t_max: f32) -> BlockHits;

    /// The rays of `rays` whose interval still reaches distance `dist`: ray `r` when
    /// `dist <= t_max[r] · IZE` (the single-ray walk's test of a popped entry). Kernels may
    /// override it with a faster form of the same results.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    #[inline(always)]
    unsafe fn reaching(t_max: &[f32; PACKET], rays: u32, dist: f32) -> u32 {
        reaching_each(t_max, rays, dist)
    }

    /// A packet's test of a wide node: each ray `r` of `active` runs [`Backend::node`] with
    /// its own `t_max[r]`; which rays enter each child, and the least distance at which they
    /// do. Kernels may override it with a faster form of the same results. Only the lanes of
    /// `active` are read (the others may be uninitialised).
    ///
    /// # Safety
    /// The CPU has the kernel's features; every lane of `active` is initialised.
    #[inline(always)]
    unsafe fn node_packet(
        p: &[MaybeUninit<Self::Prepared>; PACKET],
        node: &WideNode,
        active: u32,
        t_max: &[f32; PACKET],
    ) -> PacketNode {
        let mut rows = [0u64; PACKET / 8];
        let mut dist = [f32::INFINITY; WIDTH];
        let mut a = active;
        while a != 0 {
            let r = a.trailing_zeros() as usize;
            a &= a - 1;
            let (mask, d) = Self::node(p.get_unchecked(r).assume_init_ref(), node, *t_max.get_unchecked(r));
            *rows.get_unchecked_mut(r / 8) |= (mask as u64) << (8 * (r % 8));
            for c in 0..WIDTH {
                if (mask >> c) & 1 != 0 && d[c] < dist[c] {
                    dist[c] = d[c];
                }
            }
        }
        PacketNode::from_rows(&rows, dist)
    }

    /// [`Backend::node_packet`] for a packet whose [`Rows`] are written (for the lanes of
    /// `active`) when the kernel has [`Backend::ROWS`]: the same results. Kernels may override
    /// it with a form that reads the rows.
    ///
    /// # Safety
    /// As for [`Backend::node_packet`].
    #[inline(always)]
    unsafe fn node_packet_rows(
        p: &[MaybeUninit<Self::Prepared>; PACKET],
        rows: &MaybeUninit<Rows>,
        node: &WideNode,
        active: u32,
        t_max: &[f32; PACKET],
    ) -> PacketNode {
        let _ = rows;
        Self::node_packet(p, node, active, t_max)
    }
}

/// [`Backend::reaching`] one ray at a time, testing only the rays of `rays`: the scalar
/// kernel's form, and every kernel's for a thinned-out packet (a few rays).
#[inline(always)]
pub fn reaching_each(t_max: &[f32; PACKET], rays: u32, dist: f32) -> u32 {
    let (mut keep, mut r) = (rays, rays);
    while r != 0 {
        let i = r.trailing_zeros() as usize;
        r &= r - 1;
        // `i < 32 = PACKET`: a bit of a `u32`.
        let reaches = dist <= t_max[i] * IZE;
        keep &= !((!reaches as u32) << i);
    }
    keep
}

/// Transposes an 8 × 8 bit matrix held in a `u64` (bit `c` of byte `r` goes to bit `r` of byte
/// `c`), by three exchanges of off-diagonal blocks (Warren, "Hacker's Delight", 7-3).
#[inline(always)]
pub fn transpose8(mut x: u64) -> u64 {
    let t = (x ^ (x >> 7)) & 0x00AA_00AA_00AA_00AA;
    x ^= t ^ (t << 7);
    let t = (x ^ (x >> 14)) & 0x0000_CCCC_0000_CCCC;
    x ^= t ^ (t << 14);
    let t = (x ^ (x >> 28)) & 0x0000_0000_F0F0_F0F0;
    x ^ t ^ (t << 28)
}

/// Asks the CPU to start loading the `lines` cache lines from `p` on (a hint: never faults).
#[inline(always)]
pub fn prefetch_lines(p: *const u8, lines: usize) {
    #[cfg(target_arch = "x86_64")]
    for i in 0..lines {
        // SAFETY: prefetching is a hint that never faults, whatever the address.
        unsafe {
            std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(
                p.wrapping_add(64 * i) as *const i8
            )
        };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (p, lines);
}

/// Asks the CPU to start loading every cache line of `x` (a node or leaf block about to be
/// visited), so that the walk does not wait for it when it gets there. Does nothing on other
/// architectures.
#[inline(always)]
pub fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        let p = x as *const T as *const i8;
        let mut at = 0;
        while at < std::mem::size_of::<T>() {
            // SAFETY: prefetching is a hint that never faults; the address is inside `x`.
            unsafe { std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(p.add(at)) };
            at += 64;
        }
    }
}
