//! The interface of an analytic relief shape: a base surface (the top surface of the relief)
//! with a UV mapping, its tangent frame and curvature, and the solid below it that the relief
//! carves.
//!
//! Conventions: world units, `f64`. A shape maps `(u, v)` to the base point `P(u, v)` with
//! outward unit normal `N`; the relief's surface is `P − N · depth(u, v) · height_scale · L`,
//! where `L` ([`ReliefShape::world_per_uv`]) is the world length of one UV unit (the mappings
//! here are isometric up to that scale where the relief is measured), so one unit of relief
//! depth is `height_scale · L` world units, as it is `height_scale` UV units in tangent space.
//! The solid is every point of the shape's extent that lies at least `depth · height_scale · L`
//! below the base surface along its normal ([`ReliefShape::locate`]); the shell is the part of
//! the extent within `height_scale · L` of the base surface.

// `!(x > 0.0)` refuses NaN with the rest, which these guards rely on.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use glam::{DVec2, DVec3};

/// The base surface's geometry at one UV.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// Position `P(u, v)`.
    pub position: DVec3,
    /// `∂P/∂u`.
    pub dp_du: DVec3,
    /// `∂P/∂v`.
    pub dp_dv: DVec3,
    /// Unit tangent along increasing u (defined also where `∂P/∂u` vanishes, as at a pole).
    pub tangent: DVec3,
    /// Unit tangent along increasing v.
    pub bitangent: DVec3,
    /// Outward unit normal.
    pub normal: DVec3,
    /// Normal curvatures along `tangent` and `bitangent` (the principal directions of every
    /// shape here), in 1/world units, positive where the surface bends away from its tangent
    /// plane on the side of its normal's opposite (convex, as a sphere seen from outside).
    pub curvature: DVec2,
}

/// A base surface with a UV mapping, carrying relief displaced inward along its normal.
pub trait ReliefShape: Sync {
    /// World units per UV unit: the scale of the inward displacement.
    fn world_per_uv(&self) -> f64;

    /// The UV rectangle the surface covers, `(min, max)`; infinite along a direction in which
    /// the mapping wraps around without an edge.
    fn uv_rect(&self) -> (DVec2, DVec2);

    /// The nearest intersection, at `t > 0`, of the ray `o + t·d` (`d` unit) with the base
    /// surface's outward-facing side: `(t, uv)`.
    fn intersect(&self, o: DVec3, d: DVec3) -> Option<(f64, DVec2)>;

    /// The geometry at `uv`.
    fn geometry(&self, uv: DVec2) -> Geometry;

    /// The parameter interval `[t0, t1]` (with `t0 ≥ 0`) in which the ray `o + t·d` is inside
    /// the shape's extent (the volume under the base surface, `thickness` deep for a patch,
    /// the whole interior for closed shapes); `None` when it never is.
    fn span(&self, o: DVec3, d: DVec3, thickness: f64) -> Option<(f64, f64)>;

    /// Where the world point `x` lies: the UV of its foot on the base surface (the branch of a
    /// wrapping coordinate nearest `hint`) and its distance below the base surface along the
    /// normal; `None` outside the shape's extent.
    fn locate(&self, x: DVec3, hint: DVec2) -> Option<(DVec2, f64)>;
}

/// `a` moved by a whole number of `period`s to lie nearest `hint` (the branch of a wrapping
/// coordinate).
#[inline]
pub(crate) fn unwrap_near(a: f64, hint: f64, period: f64) -> f64 {
    if !(hint.is_finite() && a.is_finite()) {
        return a;
    }
    a + ((hint - a) / period).round() * period
}

/// Orthonormal `(e1, e2)` completing unit `axis` to a right-handed frame `(e1, e2, axis)`.
pub(crate) fn frame_around(axis: DVec3) -> (DVec3, DVec3) {
    let helper = if axis.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let e1 = (helper - axis * helper.dot(axis)).normalize();
    (e1, axis.cross(e1))
}

/// The roots of `|o + t d − c|² = r²` along the unit direction `d`, in order.
pub(crate) fn sphere_roots(o: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<(f64, f64)> {
    let oc = o - c;
    let b = oc.dot(d);
    let q = oc.length_squared() - r * r;
    let disc = b * b - q;
    if !(disc >= 0.0) {
        return None;
    }
    let s = disc.sqrt();
    // The stable form: the larger-magnitude root from the sum, the other from the product.
    let t_far_or_near = -b - s.copysign(b);
    if t_far_or_near == 0.0 {
        return Some((0.0, 0.0));
    }
    let (a, c2) = (t_far_or_near, q / t_far_or_near);
    Some((a.min(c2), a.max(c2)))
}
