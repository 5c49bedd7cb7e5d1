//! How closely each path of the GPU ray tracer must agree with the CPU BVH, and which rays
//! are left out because rounding alone may change their answer.
//!
//! # Ambiguous rays (both paths)
//!
//! A ray is *ambiguous* when rounding alone may change its answer: a hit within a relative
//! `EDGE = 1e-4` of an edge of its triangle (smallest barycentric below it, on either side), a
//! second triangle along the ray within a relative `GAP = 1e-4` of the nearest, or (for
//! segments) a hit within a relative `GAP` of either end. Every other ray must hit the same
//! triangle of the same instance on both sides, or miss on both, and the any-hit answers must
//! be equal. The ambiguous share must stay below 2 %, so the test cannot pass by calling
//! everything ambiguous.
//!
//! # The compute path: the CPU's operations
//!
//! The compute path repeats the CPU's operations, so the hit point differs only by
//! roundings: the instance transform (three dot products against glam's column sums: at most
//! 4 roundings per coordinate on each side), the shear and projection (2), the edge functions
//! (2), the weighted sum for `t` (4) and the division (Vulkan allows 2.5 ulp, the CPU 0.5),
//! and a fused multiply-add wherever the GPU compiler contracts one (it may drop a rounding
//! the CPU makes, or the reverse). Adding them with both sides' errors gives fewer than 32
//! roundings of the coordinates' magnitude, so
//! `|t_gpu − t_cpu| · ‖d‖∞ ≤ 32 · 2⁻²⁴ · (‖o‖∞ + t · ‖d‖∞)`,
//! and the barycentrics, ratios of edge functions, agree within `EDGE`.
//!
//! # The query path: the driver's own arithmetic
//!
//! The driver inverts the instance transform itself, transforms the ray with its own order
//! of operations and runs its own triangle test (on lavapipe, the same watertight test with
//! its edge functions and distance in f64; elsewhere, whatever the hardware does). Both
//! sides then find the intersection of slightly different rays with the same triangle, each
//! with its own roundings, and the differences are not bounded by the hit point's magnitude
//! alone:
//!
//! - the arithmetic works on the vertices relative to the ray's origin, so its roundings are
//!   of `M = ‖o‖∞ + maxᵢ ‖vᵢ − o‖∞` (world vertices vᵢ), not of `‖o‖∞ + t·‖d‖∞`: a long
//!   triangle hit near one end carries the roundings of its far vertices;
//! - the edge functions are differences of products of such coordinates, so an error of a
//!   few roundings of `M` moves a barycentric by that much over the triangle's altitude: a
//!   small triangle seen from far away has barycentrics far less certain than `EDGE`;
//! - a displacement of the ray across the triangle's plane moves the hit along the ray by
//!   that much over the cosine of incidence, and the sheared projection shrinks the edge
//!   functions' denominator by the same cosine.
//!
//! So the unit is `u = 2⁻²⁴ · M / cos θ` (one rounding of `M`, as a distance along the ray),
//! and the bound counts them. Per side: the world-to-object transform (the matrix's own
//! inverse, a few roundings, and the transform, 3 or 4), the origin subtracted from the
//! vertices and the shear (3 to 4), the edge functions (2 on the CPU's f32 products, none in
//! the driver's f64), the distance (5 on the CPU, 1 in the driver's conversion to f32) and the
//! barycentrics' conversion and division (2). Both sides together stay under 32, so
//! `|t_query − t_cpu| · ‖d‖₂ ≤ 32 u` and, across the edges opposite vertices 1 and 2 (of
//! altitudes `h₁`, `h₂`), `|Δu| · h₁ ≤ 32 u` and `|Δv| · h₂ ≤ 32 u`. For the same reason the
//! ambiguity widens for the query path: a hit whose distance to an edge, or to an end of the
//! interval, is within `32 u`, or a second hit within `32 (u₁ + u₂)` along the ray, is
//! ambiguous too (at such a distance the driver's arithmetic may put the ray on the other
//! side). A triangle seen edge-on has an infinite unit: every ray that hits it is ambiguous.

use glam::Vec3;
use renderlab_gpu::rt::RtPath;
use renderlab_trace::{Hit, Ray, Tlas};

/// How closely a path must agree with the CPU (see the module docs for each value's reason).
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    /// Smallest barycentric below which a hit is ambiguous (both paths).
    pub edge: f32,
    /// Relative distance between hits, or to an end of the interval, within which a ray is
    /// ambiguous (both paths).
    pub gap: f32,
    /// What the unambiguous hits must meet.
    pub check: Check,
}

/// The two ways a path's hits are held to the CPU's.
#[derive(Clone, Copy, Debug)]
pub enum Check {
    /// The path repeats the CPU's operations: `t` within this many roundings of
    /// `‖o‖∞ + t·‖d‖∞`, the barycentrics within `edge`.
    Operations(f32),
    /// The path does its own arithmetic: the hit point (along the ray, and across each edge)
    /// within this many units of [`Frame::unit`]; hits within as many units of an edge, of
    /// another hit or of an end of the interval are ambiguous too.
    Geometry(f32),
}

const COMPUTE: Bounds = Bounds { edge: 1e-4, gap: 1e-4, check: Check::Operations(32.0) };
const QUERY: Bounds = Bounds { edge: 1e-4, gap: 1e-4, check: Check::Geometry(32.0) };

/// The bounds `path` is held to.
pub fn bounds(path: RtPath) -> Bounds {
    match path {
        RtPath::Compute => COMPUTE,
        RtPath::Query => QUERY,
    }
}

/// Each mesh's triangles by index in the mesh, in object space (from the CPU structure's
/// leaf blocks): what the query path's bounds are measured against.
pub struct Triangles(Vec<Vec<[Vec3; 3]>>);

/// Where a hit stands in [`Check::Geometry`]'s terms.
pub struct Frame {
    /// One rounding of the magnitude the arithmetic works at, `2⁻²⁴ · (‖o‖∞ + maxᵢ ‖vᵢ − o‖∞)`
    /// (world vertices vᵢ), over the cosine between the ray and the triangle's normal: how
    /// far a rounding moves the hit point along the ray (infinite for a triangle seen edge-on
    /// or without area).
    pub unit: f32,
    /// The triangle's altitudes from vertices 0, 1 and 2 (world units): a barycentric error
    /// `Δw` of vertex `j` moves the point `Δw · heights[j]` across the opposite edge.
    pub heights: [f32; 3],
}

impl Triangles {
    /// The triangles of every mesh of `tlas`.
    pub fn new(tlas: &Tlas) -> Triangles {
        Triangles(
            tlas.meshes()
                .iter()
                .map(|mesh| {
                    let mut tris = Vec::new();
                    for b in &mesh.indexed().blocks {
                        for (lane, &p) in b.prim.iter().enumerate() {
                            if p != u32::MAX {
                                if tris.len() <= p as usize {
                                    tris.resize(p as usize + 1, [Vec3::NAN; 3]);
                                }
                                tris[p as usize] = b.vertices(lane).map(Vec3::from);
                            }
                        }
                    }
                    tris
                })
                .collect(),
        )
    }

    /// The frame of `hit` on `ray`.
    pub fn frame(&self, tlas: &Tlas, ray: &Ray, hit: &Hit) -> Frame {
        let placed = &tlas.placed()[hit.instance as usize];
        let v = self.0[placed.mesh as usize][hit.primitive as usize]
            .map(|p| placed.object_to_world.transform_point3(p));
        let n = (v[1] - v[0]).cross(v[2] - v[0]);
        let area2 = n.length();
        let cos = (n.dot(ray.dir) / (area2 * ray.dir.length())).abs();
        let reach = v.iter().map(|p| (*p - ray.origin).abs().max_element()).fold(0.0, f32::max);
        let magnitude = ray.origin.abs().max_element() + reach;
        // `!(cos > …)` also catches the NaN of a triangle without area.
        let unit = if cos > 1e-6 { f32::EPSILON / 2.0 * magnitude / cos } else { f32::INFINITY };
        let heights = [0, 1, 2].map(|j| area2 / (v[(j + 2) % 3] - v[(j + 1) % 3]).length());
        Frame { unit, heights }
    }
}

/// Whether `h` lies within a relative `edge` of an edge of its triangle.
pub fn near_edge(h: &Hit, edge: f32) -> bool {
    h.barycentrics().iter().any(|&w| w < edge)
}

/// Whether `ray`'s answer may change by rounding alone: `hits` are the CPU's along it (and a
/// little beyond its end), `gpu` the path's closest hit.
pub fn ambiguous(
    b: &Bounds,
    tlas: &Tlas,
    tris: &Triangles,
    ray: &Ray,
    hits: &[Hit],
    gpu: Option<Hit>,
) -> bool {
    let end_close = |t: f32| {
        ray.t_max.is_finite() && (t - ray.t_max).abs() <= b.gap * ray.t_max.max(1e-3)
            || (t - ray.t_min.max(0.0)).abs() <= b.gap * t.max(1e-3)
    };
    let relative = hits.iter().take(2).any(|h| near_edge(h, b.edge))
        || hits.len() >= 2 && hits[1].t - hits[0].t <= b.gap * hits[0].t.max(1e-3)
        || hits.iter().any(|h| end_close(h.t))
        || gpu.is_some_and(|h| near_edge(&h, b.edge) || end_close(h.t));
    let Check::Geometry(r) = b.check else { return relative };
    let len = ray.dir.length();
    // Whether `h` is within the bound of an edge or an end, and its unit.
    let near = |h: &Hit| {
        let f = tris.frame(tlas, ray, h);
        let to_edge =
            h.barycentrics().iter().zip(f.heights).map(|(w, hj)| w * hj).fold(f32::INFINITY, f32::min);
        let to_end = (h.t - ray.t_min.max(0.0)).abs().min((h.t - ray.t_max).abs()) * len;
        (to_edge.min(to_end) <= r * f.unit, f.unit)
    };
    let cpu: Vec<(bool, f32)> = hits.iter().map(near).collect();
    relative
        || cpu.iter().any(|&(n, _)| n)
        || hits.len() >= 2 && (hits[1].t - hits[0].t) * len <= r * (cpu[0].1 + cpu[1].1)
        || gpu.is_some_and(|h| near(&h).0)
}
