//! The ground plane the horizon scenes stand on: a camera one unit above an infinite plane,
//! and the depth where that plane is clipped before the horizon.
//!
//! Towards the horizon a pixel's footprint grows without bound. The ground plane is therefore
//! clipped at the depth where one pixel's footprint (the major axis of its Jacobian, at the
//! image's centre column) spans [`FAR_CLIP_TILES`] texture tiles; beyond that depth, up to the
//! horizon and above it, pixels show the background (sky).

// `!(x > t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::descriptor::Parts;
use crate::error::SceneError;
use crate::mapping::MappingError;
use crate::mip::{Texture, Wrap};
use crate::scene::view::{Crop, PlanarView, Region};
use glam::{DVec3, Vec3, Vec4};
use renderlab_core::Image;

/// A ground-plane pixel is clipped once its footprint spans this many texture tiles.
pub const FAR_CLIP_TILES: f64 = 1.0;

/// Ground-plane camera: height above the plane, field of view and horizon placement.
pub(super) struct Ground {
    f: f64,
    cx: f64,
    cy: f64,
    origin: DVec3,
    eu: DVec3,
    ev: DVec3,
}

/// The ground plane (y up in the world, camera 1 unit above it, pitched down so that the
/// horizon sits 22% below the top of the frame, 60° horizontal field of view), one texture
/// tile per `period` world units.
pub(super) fn ground(width: u32, height: u32, period: f64) -> Ground {
    let (w, h) = (width as f64, height as f64);
    let f = 0.5 * w / (30f64).to_radians().tan();
    let (cx, cy) = (0.5 * w, 0.5 * h);
    let pitch = ((cy - 0.22 * h) / f).atan();
    let (s, c) = pitch.sin_cos();
    // Camera axes in world coordinates: right (1,0,0), down (0,−c,−s), forward (0,−s,c).
    let to_cam = |p: DVec3| DVec3::new(p.x, -c * p.y - s * p.z, -s * p.y + c * p.z);
    let eye_h = 1.0;
    Ground {
        f,
        cx,
        cy,
        origin: to_cam(DVec3::new(0.37 * period, -eye_h, 0.0)),
        eu: to_cam(DVec3::new(period, 0.0, 0.0)),
        ev: to_cam(DVec3::new(0.0, 0.0, period)),
    }
}

/// The depth at which the footprint at the centre column spans `tiles` surface units, found
/// by walking up the centre column towards the horizon.
pub(super) fn clip_depth(g: &Ground, height: u32, tiles: f64) -> Result<f64, MappingError> {
    let open = PlanarView::plane(g.origin, g.eu, g.ev, g.f, (g.cx, g.cy), f64::INFINITY)?;
    let Region::Plane { n, c, .. } = open.region else { unreachable!("plane region") };
    let depth = |y: f64| c / n.dot(DVec3::new(0.0, (y - g.cy) / g.f, 1.0));
    let mut y = height as f64;
    let mut last = depth(y);
    // 0.01-pixel steps: bounded by the frame height.
    let steps = (height as usize + 1) * 100;
    for _ in 0..steps {
        let Some(fp) = open.footprint(g.cx, y) else { break };
        let major = fp.duv_dx.length().max(fp.duv_dy.length());
        let z = depth(y);
        if !(major <= tiles) || !(z > 0.0) {
            break;
        }
        last = z;
        y -= 0.01;
    }
    Ok(last)
}

/// The parts of a scene on the ground plane at `width × height`: `texture` repeated once per
/// `period` world units, clipped where a pixel spans [`FAR_CLIP_TILES`] tiles, sky beyond,
/// with a crop around the horizon; `what` names the texture in the description.
pub(super) fn horizon_parts(
    width: u32,
    height: u32,
    texture: Image<Vec4>,
    period: f64,
    what: &str,
) -> Result<Parts, SceneError> {
    let g = ground(width, height, period);
    let far = clip_depth(&g, height, FAR_CLIP_TILES)?;
    let view = PlanarView::plane(g.origin, g.eu, g.ev, g.f, (g.cx, g.cy), far)?;
    Ok(Parts {
        description: format!(
            "ground plane, camera 1 unit up, 60° field of view, {what}; clipped at depth {far:.1} \
             where a pixel spans {FAR_CLIP_TILES} tile(s); sky beyond"
        ),
        view,
        texture: Texture::new(texture, Wrap::Repeat),
        uv_scale: 1.0,
        background: Vec3::new(0.55, 0.7, 0.9),
        horizon_crop: horizon_crop(width, height),
    })
}

/// A rectangle around the horizon (22% below the top of the frame), worth zooming into.
fn horizon_crop(width: u32, height: u32) -> Option<Crop> {
    let horizon = 0.22 * height as f64;
    let cw = (width / 4).max(8);
    let ch = (height / 6).max(8);
    Some(Crop {
        x: (width - cw) / 2,
        y: ((horizon as i64 - 2).clamp(0, (height - ch) as i64)) as u32,
        w: cw,
        h: ch,
    })
}
