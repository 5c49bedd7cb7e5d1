//! A plane seen through a pinhole camera: the exact projective map from continuous pixel
//! coordinates to surface coordinates ([`PlanarView`]), the part of the plane that exists
//! ([`Region`]) and the analytic Jacobian of that map at a pixel ([`Footprint`]).
//!
//! The screen→surface map is one projective matrix ([`Projective`], `f64`), and the Jacobian
//! `∂(u,v)/∂(x,y)` follows in closed form from the rational map: `∂u/∂x = (A·W − U·G)/W²` for
//! `[U, V, W] = [x, y, 1]·m`. Pixel `(i, j)` covers the square `[i, i+1) × [j, j+1)` of
//! continuous screen coordinates; filters are evaluated at its centre.

// `!(x > t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::mapping::{MappingError, Projective, QuadScene};
use glam::{DVec2, DVec3};

/// Which part of the plane a scene shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Region {
    /// The unit square of surface coordinates (a quad).
    UnitSquare,
    /// The whole plane in front of the eye up to a camera depth `max_depth`. The plane is
    /// `n·p = c` in camera space; rays are `p = z·((x − cx)/f, (y − cy)/f, 1)`.
    Plane {
        /// Plane normal (camera space).
        n: DVec3,
        /// Plane offset.
        c: f64,
        /// Principal point x (pixels).
        cx: f64,
        /// Principal point y (pixels).
        cy: f64,
        /// Focal length (pixels).
        f: f64,
        /// Largest depth shown.
        max_depth: f64,
    },
}

/// A plane seen through a pinhole camera: the exact map from continuous pixel coordinates to
/// surface coordinates, and the part of the plane that exists.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarView {
    /// Pixel coordinates → surface coordinates.
    pub to_uv: Projective,
    /// What is surface.
    pub region: Region,
}

/// The mapped point of one pixel and its Jacobian (surface units per pixel).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    /// Surface coordinate.
    pub uv: DVec2,
    /// `∂(u,v)/∂x`.
    pub duv_dx: DVec2,
    /// `∂(u,v)/∂y`.
    pub duv_dy: DVec2,
}

impl PlanarView {
    /// A ground-like plane through camera-space point `origin` spanned by `eu`, `ev` (camera
    /// units per surface unit), seen by a camera with focal length `f` and principal point
    /// `(cx, cy)` (pixels; y down), shown up to depth `max_depth`. Errors for non-finite input,
    /// parallel axes, or an eye in the plane.
    pub fn plane(
        origin: DVec3,
        eu: DVec3,
        ev: DVec3,
        f: f64,
        (cx, cy): (f64, f64),
        max_depth: f64,
    ) -> Result<Self, MappingError> {
        let finite = origin.is_finite() && eu.is_finite() && ev.is_finite() && f.is_finite();
        if !(finite && cx.is_finite() && cy.is_finite()) || max_depth.is_nan() {
            return Err(MappingError::NonFinite { what: "plane or camera" });
        }
        if !(f > 0.0) {
            return Err(MappingError::NonFinite { what: "focal length" });
        }
        let n = eu.cross(ev);
        if !(n.length() > 1e-12 * eu.length() * ev.length()) {
            return Err(MappingError::Collinear([1, 2, 3]));
        }
        let c = n.dot(origin);
        if !(c.abs() > 1e-9 * n.length() * origin.length().max(1e-300)) || origin.length() == 0.0 {
            return Err(MappingError::EyeInPlane);
        }
        let k = |e: DVec3| [f * e.x + cx * e.z, f * e.y + cy * e.z, e.z];
        let uv_to_px = Projective { m: [k(eu), k(ev), k(origin)] };
        let to_uv = uv_to_px.inverse()?;
        Ok(PlanarView { to_uv, region: Region::Plane { n, c, cx, cy, f, max_depth } })
    }

    /// The thesis-style quad `scene` (validated: degenerate quads, an eye in the plane and
    /// corners behind the eye are errors), its screen plane mapped to pixels by
    /// `screen = a·pixel + b`.
    pub fn quad(scene: &QuadScene, a: f64, b: DVec2) -> Result<Self, MappingError> {
        if !(a.is_finite() && a > 0.0 && b.is_finite()) {
            return Err(MappingError::NonFinite { what: "pixel-to-screen transform" });
        }
        let screen_to_uv = scene.mapping()?;
        let px_to_screen = Projective { m: [[a, 0.0, 0.0], [0.0, a, 0.0], [b.x, b.y, 1.0]] };
        Ok(PlanarView { to_uv: px_to_screen.then(&screen_to_uv), region: Region::UnitSquare })
    }

    /// An axis-aligned view: pixel `(x, y)` ↦ `(x/w, y/h)` over the unit square, a 1:1 mapping
    /// of a `w × h` texture.
    pub fn screen_aligned(w: f64, h: f64) -> Self {
        PlanarView {
            to_uv: Projective { m: [[1.0 / w, 0.0, 0.0], [0.0, 1.0 / h, 0.0], [0.0, 0.0, 1.0]] },
            region: Region::UnitSquare,
        }
    }

    /// Surface coordinate seen at continuous pixel position `(x, y)`, or `None` where there is
    /// no surface (background, beyond the horizon or the clip depth, behind the eye).
    #[inline]
    pub fn hit(&self, x: f64, y: f64) -> Option<DVec2> {
        let uv = self.to_uv.map(x, y)?;
        match self.region {
            Region::UnitSquare => ((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)).then_some(uv),
            Region::Plane { n, c, cx, cy, f, max_depth } => {
                let d = DVec3::new((x - cx) / f, (y - cy) / f, 1.0);
                let z = c / n.dot(d);
                (z > 0.0 && z <= max_depth).then_some(uv)
            }
        }
    }

    /// The footprint at `(x, y)` (analytic Jacobian), or `None` where there is no surface.
    #[inline]
    pub fn footprint(&self, x: f64, y: f64) -> Option<Footprint> {
        let uv = self.hit(x, y)?;
        let m = &self.to_uv.m;
        let h = self.to_uv.map_homogeneous(x, y);
        let w2 = h.z * h.z;
        let d =
            |r: usize| DVec2::new((m[r][0] * h.z - h.x * m[r][2]) / w2, (m[r][1] * h.z - h.y * m[r][2]) / w2);
        let fp = Footprint { uv, duv_dx: d(0), duv_dy: d(1) };
        (fp.duv_dx.is_finite() && fp.duv_dy.is_finite()).then_some(fp)
    }
}

/// A rectangle of pixels (for zoomed crops).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width.
    pub w: u32,
    /// Height.
    pub h: u32,
}
