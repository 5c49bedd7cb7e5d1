//! The watertight ray–triangle test of Woop, Benthin and Wald ("Watertight Ray/Triangle
//! Intersection", JCGT 2013), in the scalar form that the vector kernel reproduces bit for bit.
//!
//! The ray is made the +z axis of a sheared frame: the axis of the direction's largest
//! component becomes z (`kz`), the other two (`kx`, `ky`, swapped when `dir[kz] < 0` so that
//! winding is kept) are sheared by `S = (dx/dz, dy/dz, 1/dz)`. Each vertex, taken relative to the
//! ray origin, projects to 2D as `(a[kx] − Sx·a[kz], a[ky] − Sy·a[kz])`, and the ray hits the
//! triangle iff the 2D origin lies inside the projected triangle: the three edge functions
//! `U, V, W` (twice the signed areas opposite each vertex) share a sign. An edge shared by two
//! triangles projects to the *same* 2D segment in both, computed from the same rounded
//! numbers, so a ray through it gets edge functions of opposite signs for the two triangles and
//! cannot fall between them. Rounding is monotone, so an edge function computed in f32 has the
//! exact sign or is 0; only edge functions that round to exactly 0, on a ray that the other two
//! place inside the triangle, are recomputed in f64, where the products of f32 numbers are
//! exact. Then `t = (U·az + V·bz + W·cz) / (U + V + W)`.
//!
//! Cost is paid where it is needed: a ray outside the projected triangle (almost every test)
//! stops after the six edge products and a sign test (`min(U, V, W) ≥ 0` or
//! `max(U, V, W) ≤ 0`), before the f64 check, the distance and the division.
//!
//! Fused multiply-adds: the distance's sum `U·az + V·bz + W·cz` is two fused operations. The
//! edge functions are not fused (`cx·by − cy·bx` fused would round the two products
//! differently for the two triangles of an edge, and the edge would leak), and neither is the
//! projection `a[kx] − Sx·a[kz]`: fusing it (per vertex, so still watertight) moved the hybrid
//! renderer's shadow-term test against its reference past its bound, which is not understood
//! yet, so it stays two operations. Every operation is an IEEE operation in a fixed order,
//! separate or fused as written (`f32::mul_add`, exactly rounded on every CPU), since Rust never
//! contracts on its own: that is what lets the AVX2 kernel agree exactly.

use crate::lanes::{max_ps, min_ps};
use glam::{DVec3, Vec3};

/// Whether the distance's sum uses fused multiply-adds (off only to measure what fusion
/// saves).
pub const FUSED: bool = !cfg!(feature = "measure-unfused");

/// Whether edge functions that round to 0 are recomputed in f64 (off only to measure what the
/// recomputation costs; off, rays exactly through an edge may leak).
pub const EXACT_EDGES: bool = !cfg!(feature = "measure-no-exact-edges");

/// What the test needs of a ray, computed once per ray (and once per instance it enters).
#[derive(Clone, Copy, Debug)]
pub struct TriRay {
    /// The ray origin.
    pub org: [f32; 3],
    /// The permuted axes `[kx, ky, kz]`.
    pub k: [usize; 3],
    /// The shear `[Sx, Sy, Sz]`.
    pub shear: [f32; 3],
}

impl TriRay {
    /// The sheared frame of a ray with a non-zero, finite direction.
    #[inline(always)]
    pub fn new(org: Vec3, dir: Vec3) -> TriRay {
        let a = dir.abs();
        let kz = if a.x > a.y && a.x > a.z {
            0
        } else if a.y > a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        let d = dir.to_array();
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        TriRay { org: org.to_array(), k: [kx, ky, kz], shear: [d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]] }
    }
}

/// A hit's distance and barycentrics (weights of the second and third vertex).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriHit {
    /// Distance along the ray.
    pub t: f32,
    /// Weight of the second vertex.
    pub u: f32,
    /// Weight of the third vertex.
    pub v: f32,
}

/// The edge functions `U, V, W` in f64, rounded to f32: the products of two f32 numbers are
/// exact in f64, so a sign that f32 rounded to zero is decided correctly.
#[inline(never)]
#[cold]
pub fn edge_functions_f64(ax: f32, ay: f32, bx: f32, by: f32, cx: f32, cy: f32) -> [f32; 3] {
    let (ax, ay, bx, by, cx, cy) = (ax as f64, ay as f64, bx as f64, by as f64, cx as f64, cy as f64);
    [(cx * by - cy * bx) as f32, (ax * cy - ay * cx) as f32, (bx * ay - by * ax) as f32]
}

/// The test for one triangle: the hit in `[t_min, t_max]`, if any. Triangles with a NaN
/// vertex never hit (every comparison with NaN fails).
#[inline(always)]
pub fn intersect(
    r: &TriRay,
    v0: [f32; 3],
    v1: [f32; 3],
    v2: [f32; 3],
    t_min: f32,
    t_max: f32,
) -> Option<TriHit> {
    let [kx, ky, kz] = r.k;
    let [sx, sy, sz] = r.shear;
    let o = r.org;
    let (a_x, a_y, a_z) = (v0[kx] - o[kx], v0[ky] - o[ky], v0[kz] - o[kz]);
    let (b_x, b_y, b_z) = (v1[kx] - o[kx], v1[ky] - o[ky], v1[kz] - o[kz]);
    let (c_x, c_y, c_z) = (v2[kx] - o[kx], v2[ky] - o[ky], v2[kz] - o[kz]);
    let ax = a_x - sx * a_z;
    let ay = a_y - sy * a_z;
    let bx = b_x - sx * b_z;
    let by = b_y - sy * b_z;
    let cx = c_x - sx * c_z;
    let cy = c_y - sy * c_z;
    let mut e = [cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax];
    if !inside(e) {
        return None;
    }
    if EXACT_EDGES && (e[0] == 0.0 || e[1] == 0.0 || e[2] == 0.0) {
        e = edge_functions_f64(ax, ay, bx, by, cx, cy);
        if !inside(e) {
            return None;
        }
    }
    let [u, v, w] = e;
    let det = u + v + w;
    let az = sz * a_z;
    let bz = sz * b_z;
    let cz = sz * c_z;
    let tt = fused(w, cz, fused(v, bz, u * az));
    let rcp = 1.0 / det;
    let t = tt * rcp;
    if det == 0.0 || !(t >= t_min && t <= t_max) {
        return None;
    }
    Some(TriHit { t, u: v * rcp, v: w * rcp })
}

/// `a·b + c` with one rounding (two with the measuring feature that turns fusion off).
#[inline(always)]
pub fn fused(a: f32, b: f32, c: f32) -> f32 {
    if FUSED {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// Whether the edge functions share a sign (zeros count as either): `min ≥ 0` or `max ≤ 0`,
/// with `maxps`/`minps` semantics as the vector kernel (false when all are NaN).
#[inline(always)]
pub fn inside([u, v, w]: [f32; 3]) -> bool {
    min_ps(u, min_ps(v, w)) >= 0.0 || max_ps(u, max_ps(v, w)) <= 0.0
}

/// Whether a triangle can ever be hit: all vertices finite and not collinear (the cross product
/// of two edges, in f64, is not zero). The build leaves the others out of the hierarchy, and
/// the brute-force reference skips them too: a degenerate triangle has no well-defined
/// barycentrics, and a NaN vertex no position.
pub fn is_hittable(v0: Vec3, v1: Vec3, v2: Vec3) -> bool {
    if !(v0.is_finite() && v1.is_finite() && v2.is_finite()) {
        return false;
    }
    let (a, b, c) = (v0.as_dvec3(), v1.as_dvec3(), v2.as_dvec3());
    (b - a).cross(c - a) != DVec3::ZERO
}
