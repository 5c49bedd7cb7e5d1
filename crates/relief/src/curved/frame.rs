//! The frame input of an analytic shape seen by a camera: per pixel, the base surface's
//! [`SurfacePoint`] (where the pixel's ray meets it) and its [`PatchInfo`].
//!
//! The UV Jacobian is exact to first order (ray differentials): the pixel's ray direction `D`
//! moves by `∂D/∂x` per pixel, the hit point by `t·(∂D/∂x − D·(N·∂D/∂x)/(N·D))` in the tangent
//! plane, and UV by that step's components along `∂P/∂u` and `∂P/∂v` (orthogonal on every
//! shape here) divided by their squared lengths.
//!
//! Where the mapping stretches (`s_u = |∂P/∂u| / L`, `s_v = |∂P/∂v| / L` differ from 1, as
//! toward a sphere's poles), the view direction is given in the frame scaled by the stretch,
//! `view_ts ∝ (V·T / s_u, V·B / s_v, V·N)`, so that the techniques' UV offset per unit depth
//! `−V.xy / V.z · height_scale` is the one the world-space ray makes (the unnormalised tangent
//! frame engines use for parallax); the light stays in the orthonormal frame. The curvature
//! in 1/UV along T is `κ_T · L · s_u²` (the sag `½ κ (Δu · s_u · L)²` over the relief's UV
//! unit `L`), likewise along B. On isometric mappings (`s = 1`) both are the plain ones.

use super::shape::{Geometry, ReliefShape};
use crate::render::shade::PatchInfo;
use glam::{DVec2, DVec3, Mat3, Vec3};
use rayon::prelude::*;
use renderlab_core::{Camera, SurfacePoint};

/// A frame's input built from a shape: one entry per pixel, row-major.
#[derive(Clone, Debug)]
pub struct ShapeFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The base surface per pixel (`None` where the ray misses it).
    pub points: Vec<Option<SurfacePoint>>,
    /// The patch per pixel (default where the ray misses).
    pub patches: Vec<PatchInfo>,
}

/// The camera's world-space ray through pixel position `(px, py)` and its derivatives per
/// pixel step along x and y: `(D, ∂D/∂x, ∂D/∂y)`, all in `f64` (as [`Camera::ray_direction`]).
pub fn ray_with_differentials(camera: &Camera, px: f64, py: f64) -> (DVec3, DVec3, DVec3) {
    let (w, h) = (camera.width as f64, camera.height as f64);
    let tan = (camera.fov_y_deg as f64).to_radians() * 0.5;
    let tan = tan.tan();
    let aspect = w / h;
    let forward = camera.forward.as_dvec3();
    let right = forward.cross(camera.up.as_dvec3()).normalize();
    let up = right.cross(forward);
    let ndc_x = 2.0 * px / w - 1.0;
    let ndc_y = 1.0 - 2.0 * py / h;
    let v = forward + right * (ndc_x * tan * aspect) + up * (ndc_y * tan);
    let len = v.length();
    let d = v / len;
    let derive = |dv: DVec3| (dv - d * d.dot(dv)) / len;
    (d, derive(right * (2.0 * tan * aspect / w)), derive(up * (-2.0 * tan / h)))
}

/// The mapping's stretch at `g`: `(|∂P/∂u|, |∂P/∂v|) / L`, floored at `1e-3` (where `∂P/∂u`
/// vanishes, as at a pole).
pub fn stretch<S: ReliefShape>(shape: &S, g: &Geometry) -> DVec2 {
    let l = shape.world_per_uv();
    DVec2::new(g.dp_du.length(), g.dp_dv.length()).max(DVec2::splat(1e-3 * l)) / l
}

/// The pixel's patch information for `shape` at `g`.
pub fn patch_info<S: ReliefShape>(shape: &S, g: &Geometry) -> PatchInfo {
    let l = shape.world_per_uv();
    let (lo, hi) = shape.uv_rect();
    let s = stretch(shape, g);
    PatchInfo {
        curvature: (g.curvature * l * s * s).as_vec2(),
        uv_min: lo.as_vec2(),
        uv_max: hi.as_vec2(),
        world_per_uv: l as f32,
    }
}

/// The surface point of `shape` at `uv`, reached by the ray `d` from the eye at distance `t`,
/// with UV derivatives from the ray's differentials `ddx`, `ddy`; `light` is the unit
/// direction toward the light.
#[allow(clippy::too_many_arguments)] // the ray, its differentials and where it met the shape.
pub fn surface_point<S: ReliefShape>(
    shape: &S,
    uv: DVec2,
    t: f64,
    d: DVec3,
    ddx: DVec3,
    ddy: DVec3,
    light: DVec3,
) -> (SurfacePoint, PatchInfo) {
    let g = shape.geometry(uv);
    let n = g.normal;
    let dn = d.dot(n);
    let l = shape.world_per_uv();
    // UV per world step along ∂P/∂u, ∂P/∂v (floored where ∂P/∂u vanishes, as at a pole).
    let floor = 1e-6 * l * l;
    let to_uv = |step: DVec3| {
        DVec2::new(
            step.dot(g.dp_du) / g.dp_du.length_squared().max(floor),
            step.dot(g.dp_dv) / g.dp_dv.length_squared().max(floor),
        )
    };
    let along = |dd: DVec3| to_uv((dd - d * (n.dot(dd) / dn)) * t);
    let tbn = [g.tangent, g.bitangent, n];
    let to_ts = |w: DVec3| DVec3::new(w.dot(tbn[0]), w.dot(tbn[1]), w.dot(tbn[2]));
    let s = stretch(shape, &g);
    let view = to_ts(-d);
    let sp = SurfacePoint {
        uv: uv.as_vec2(),
        duv_dx: along(ddx).as_vec2(),
        duv_dy: along(ddy).as_vec2(),
        tbn: Mat3::from_cols(tbn[0].as_vec3(), tbn[1].as_vec3(), tbn[2].as_vec3()),
        view_ts: DVec3::new(view.x / s.x, view.y / s.y, view.z).normalize_or_zero().as_vec3(),
        light_ts: to_ts(light).as_vec3(),
        position: g.position.as_vec3(),
        depth: t as f32,
        object: 0,
        material: 0,
    };
    (sp, patch_info(shape, &g))
}

/// The frame input of `shape` seen by `camera`, lit from the unit direction `light` (toward
/// the light, world space).
pub fn shape_frame<S: ReliefShape>(shape: &S, camera: &Camera, light: Vec3) -> ShapeFrame {
    let (w, h) = (camera.width as usize, camera.height as usize);
    let eye = camera.position.as_dvec3();
    let light = light.as_dvec3().normalize_or_zero();
    let (points, patches): (Vec<_>, Vec<_>) = (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (px, py) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
            let (d, ddx, ddy) = ray_with_differentials(camera, px, py);
            match shape.intersect(eye, d) {
                Some((t, uv)) => {
                    let (sp, patch) = surface_point(shape, uv, t, d, ddx, ddy, light);
                    (Some(sp), patch)
                }
                None => (None, PatchInfo::default()),
            }
        })
        .unzip();
    ShapeFrame { width: camera.width, height: camera.height, points, patches }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curved::patch::Patch;
    use crate::curved::sphere::Sphere;
    use glam::Vec2;

    #[test]
    fn differentials_match_the_camera_and_finite_differences() {
        let cam = Camera::look_at(Vec3::new(0.3, 0.5, 4.0), Vec3::ZERO, 64, 48);
        let (d, ddx, ddy) = ray_with_differentials(&cam, 20.5, 30.5);
        assert!((d.as_vec3() - cam.ray_direction(20.5, 30.5)).length() < 1e-6);
        let (dx, _, _) = ray_with_differentials(&cam, 20.5 + 1e-4, 30.5);
        let (dy, _, _) = ray_with_differentials(&cam, 20.5, 30.5 + 1e-4);
        assert!(((dx - d) / 1e-4 - ddx).length() < 1e-7);
        assert!(((dy - d) / 1e-4 - ddy).length() < 1e-7);
    }

    #[test]
    fn uv_derivatives_match_neighbouring_pixels() {
        let s = Sphere {
            centre: DVec3::ZERO,
            radius: 1.0,
            axis: DVec3::new(0.2, 0.3, 1.0).normalize(),
            tiles: 2.0,
        };
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.5), Vec3::ZERO, 96, 96);
        let f = shape_frame(&s, &cam, Vec3::Z);
        let at = |x: usize, y: usize| f.points[y * 96 + x].expect("covered");
        let (a, r, b) = (at(40, 44), at(41, 44), at(40, 45));
        let tol = 0.05 * a.duv_dx.length().max(a.duv_dy.length());
        assert!((r.uv - a.uv - a.duv_dx).length() < tol, "{:?} {:?}", r.uv - a.uv, a.duv_dx);
        assert!((b.uv - a.uv - a.duv_dy).length() < tol);
        assert!(a.view_ts.z > 0.0 && (a.view_ts.length() - 1.0).abs() < 1e-5);
        // Curvature 1/R times L times the stretch squared (1 along v, sin θ along u).
        let g = s.geometry(a.uv.as_dvec2());
        let sin_theta = (g.normal.cross(s.axis)).length();
        let l = s.world_per_uv();
        let k = f.patches[44 * 96 + 40].curvature;
        assert!(
            (k.y as f64 - l).abs() < 1e-5 && (k.x as f64 - l * sin_theta * sin_theta).abs() < 1e-5,
            "{k}"
        );
        assert!(f.points[0].is_none(), "the corner misses the sphere");
    }

    #[test]
    fn a_patch_seen_head_on_has_a_constant_footprint() {
        let p = Patch {
            origin: DVec3::new(-1.0, -1.0, 0.0),
            tangent: DVec3::X,
            bitangent: DVec3::Y,
            world_per_uv: 2.0,
            uv_min: DVec2::ZERO,
            uv_max: DVec2::ONE,
        };
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 32, 32);
        let f = shape_frame(&p, &cam, Vec3::Z);
        let c = f.points[16 * 32 + 16].expect("covered");
        assert!((c.view_ts - Vec3::Z).length() < 0.05);
        assert!(c.duv_dy.y < 0.0, "v grows up the screen");
        assert_eq!(f.patches[16 * 32 + 16].uv_max, Vec2::ONE);
    }
}
