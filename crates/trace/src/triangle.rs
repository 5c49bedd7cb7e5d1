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
//! cannot fall between them; edge functions that round to exactly 0 are recomputed in f64,
//! where the products of f32 numbers are exact. Then `t = (U·az + V·bz + W·cz) / (U + V + W)`.
//!
//! Every operation is a separate IEEE multiply, add or subtract in a fixed order (Rust never
//! contracts them into fused multiply-adds), which is what lets the AVX2 kernel agree exactly.

use glam::{DVec3, Vec3};

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
    if e[0] == 0.0 || e[1] == 0.0 || e[2] == 0.0 {
        e = edge_functions_f64(ax, ay, bx, by, cx, cy);
    }
    let [u, v, w] = e;
    let neg = u < 0.0 || v < 0.0 || w < 0.0;
    let pos = u > 0.0 || v > 0.0 || w > 0.0;
    let det = u + v + w;
    let az = sz * a_z;
    let bz = sz * b_z;
    let cz = sz * c_z;
    let tt = u * az + v * bz + w * cz;
    let rcp = 1.0 / det;
    let t = tt * rcp;
    if (neg && pos) || det == 0.0 || !(t >= t_min && t <= t_max) {
        return None;
    }
    Some(TriHit { t, u: v * rcp, v: w * rcp })
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
