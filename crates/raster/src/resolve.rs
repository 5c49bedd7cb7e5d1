//! Turning a visible triangle at a pixel into a [`SurfacePoint`]: perspective-correct
//! attributes, their exact screen derivatives and the tangent frame.

use crate::frame::tangent_frame;
use crate::setup::{TriangleSetup, INV_W, NORMAL, POSITION, TANGENT, UV};
use glam::{DVec2, DVec3, Vec2, Vec3};
use renderlab_core::{ShadePoint, SurfacePoint};

/// What is constant over a frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrameConstants {
    /// Eye position.
    pub eye: DVec3,
    /// Unit vector toward the light (zero if the scene's is degenerate).
    pub to_light: Vec3,
    /// Whether the streaming raster's points need their view and light directions (see
    /// `RowRaster::without_view`).
    pub view: bool,
}

/// The surface of `setup` at the centre of pixel `(x, y)`. `None` if the values there are not
/// finite (only possible for nearly degenerate triangles).
///
/// With `h = a/w` and `q = 1/w` planes in screen space, `a = h/q` and
/// `∂a/∂x = (∂h/∂x − a·∂q/∂x)/q` exactly (likewise for y); normal and tangent need no
/// division since they are normalised, and none at all on triangles whose vertices share
/// one normal and tangent (the frame is then constant and set up once).
#[inline]
pub(crate) fn resolve(s: &TriangleSetup, x: u32, y: u32, frame: &FrameConstants) -> Option<SurfacePoint> {
    resolve_with(s, x, y, frame, |p| p)
}

/// The [`ShadePoint`] of `setup` at pixel `(x, y)`: the same values as [`resolve`]'s, for the
/// same pixels, without building the rest of the surface point.
#[inline]
pub(crate) fn resolve_shade(s: &TriangleSetup, x: u32, y: u32, frame: &FrameConstants) -> Option<ShadePoint> {
    resolve_with(s, x, y, frame, |p| ShadePoint::from(&p))
}

/// [`resolve`]'s computation, handing the surface point to `out` (inlined, so that fields
/// `out` drops are never stored).
#[inline(always)]
fn resolve_with<P>(
    s: &TriangleSetup,
    x: u32,
    y: u32,
    frame: &FrameConstants,
    out: impl FnOnce(SurfacePoint) -> P,
) -> Option<P> {
    let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
    let plane = |k: usize| s.dx[k] * px + s.dy[k] * py + s.c[k];
    let q = plane(INV_W);
    if q.is_nan() || q <= 0.0 {
        return None;
    }
    let w = 1.0 / q;
    let uv = DVec2::new(plane(UV), plane(UV + 1)) * w;
    let duv_dx = (DVec2::new(s.dx[UV], s.dx[UV + 1]) - uv * s.dx[INV_W]) * w;
    let duv_dy = (DVec2::new(s.dy[UV], s.dy[UV + 1]) - uv * s.dy[INV_W]) * w;
    let position = DVec3::new(plane(POSITION), plane(POSITION + 1), plane(POSITION + 2)) * w;
    // The difference in f64, the rest in f32 (one f32 square root and reciprocal).
    let to_eye = (frame.eye - position).as_vec3();
    let depth = to_eye.length();
    let view = to_eye * depth.recip();

    let tbn = match s.flat_frame {
        Some(tbn) => tbn,
        None => {
            let f = |k: usize| plane(k) as f32;
            let n = Vec3::new(f(NORMAL), f(NORMAL + 1), f(NORMAL + 2));
            let t = Vec3::new(f(TANGENT), f(TANGENT + 1), f(TANGENT + 2));
            tangent_frame(n, t, f(TANGENT + 3), s.face_normal)
        }
    };
    let to_tangent = tbn.transpose();

    let p = SurfacePoint {
        uv: uv.as_vec2(),
        duv_dx: duv_dx.as_vec2(),
        duv_dy: duv_dy.as_vec2(),
        tbn,
        view_ts: to_tangent * view,
        light_ts: to_tangent * frame.to_light,
        position: position.as_vec3(),
        depth,
        object: s.object,
        material: s.material,
    };
    let finite = |v: Vec2| v.is_finite();
    (finite(p.uv)
        && finite(p.duv_dx)
        && finite(p.duv_dy)
        && p.position.is_finite()
        && p.view_ts.is_finite()
        && p.depth.is_finite())
    .then(|| out(p))
}
