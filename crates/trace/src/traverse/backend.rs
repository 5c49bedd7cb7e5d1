//! The interface between the generic walk and its kernels: what a kernel computes for one
//! wide node (which children the ray enters, and at what distance) and for one leaf block
//! (which triangles it hits, where).
//!
//! Slab test. For each axis the ray enters a child's slab at `(near − o)·inv` and leaves it at
//! `(far − o)·inv`, where `inv = 1/dir` and near/far are the min or max plane by the sign of
//! `inv`. A zero direction component gives `inv = ±∞`; a ray lying exactly in a slab's plane
//! then gives `0·∞ = NaN`, and the min/max below are ordered so that a NaN distance is ignored
//! (each is `x86`'s `maxps(a, b)`: `if a > b { a } else { b }`, which returns `b` when `a` is
//! NaN), i.e. the ray counts as inside that slab. The far distance is scaled by
//! `1 + 2γ₃` (Ize, "Robust BVH ray traversal", JCGT 2013), which makes the test conservative:
//! rounding can add a box the ray misses, never drop one it hits. So a ray aimed exactly at a
//! vertex or edge reaches every triangle there, and the watertight test decides.

use crate::node::{TriBlock, WideNode};
use crate::ray::Ray;
use crate::triangle::TriRay;
use glam::Vec3;

/// `1 + 2γ₃` with `γₙ = nε / (1 − nε)`, `ε = 2⁻²⁴`: Ize's factor for the far slab distance.
pub const IZE: f32 = 1.0 + 2.0 * (3.0 * 5.960_464_5e-8 / (1.0 - 3.0 * 5.960_464_5e-8));

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
    /// The sheared frame of the watertight test.
    pub tri: TriRay,
}

impl RayQuery {
    /// The query for `ray`, or `None` when the ray can hit nothing: a non-finite origin or
    /// direction, a zero direction, or an empty or NaN interval.
    pub fn new(ray: &Ray) -> Option<RayQuery> {
        let t_min = if ray.t_min > 0.0 { ray.t_min } else { 0.0 };
        if ray.t_min.is_nan()
            || !(ray.origin.is_finite() && ray.dir.is_finite() && ray.dir != Vec3::ZERO && t_min <= ray.t_max)
        {
            return None;
        }
        let d = ray.dir.to_array();
        let inv = d.map(|x| 1.0 / x);
        let near = [0, 1, 2].map(|a| 2 * a + inv[a].is_sign_negative() as usize);
        let far = [0, 1, 2].map(|a| 2 * a + 1 - inv[a].is_sign_negative() as usize);
        Some(RayQuery {
            org: ray.origin.to_array(),
            inv,
            near,
            far,
            t_min,
            t_max: ray.t_max,
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
    type Prepared;

    /// The ray's kernel form.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    unsafe fn prepare(q: &RayQuery) -> Self::Prepared;

    /// Bit `i` of the mask is set when the ray enters child `i` before `t_max`; `dist[i]` is
    /// the distance at which it does (at least `t_min`).
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    unsafe fn node(p: &Self::Prepared, node: &WideNode, t_max: f32) -> (u32, [f32; 8]);

    /// The block's triangles hit within `[t_min, t_max]`.
    ///
    /// # Safety
    /// The CPU has the kernel's features.
    unsafe fn block(p: &Self::Prepared, block: &TriBlock, t_max: f32) -> BlockHits;
}

/// `maxps(a, b)`: `b` unless `a > b` (so a NaN `a` is ignored).
#[inline(always)]
pub fn max_ps(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

/// `minps(a, b)`: `b` unless `a < b` (so a NaN `a` is ignored).
#[inline(always)]
pub fn min_ps(a: f32, b: f32) -> f32 {
    if a < b {
        a
    } else {
        b
    }
}
