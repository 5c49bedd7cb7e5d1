//! A unit square tilted by an angle about the horizontal axis (0° facing the camera), one unit
//! from the eye, with the bricks albedo (256²) repeated 2×2; the focal length is 0.9 of the
//! frame's shorter side and screen coordinates are centred on the optical axis.

use super::descriptor::{Descriptor, Entry, Param, Parts};
use crate::scene::view::PlanarView;
use crate::error::SceneError;
use crate::mapping::QuadScene;
use crate::mip::{Texture, Wrap};
use crate::procedural::bricks_texture;
use glam::{DVec2, DVec3, Vec3};

/// A square tilted by `tilt` degrees (0 = facing the camera) with the bricks texture.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TiltedQuad {
    /// The tilt in degrees, in [0, 89.9].
    pub tilt: f64,
}

/// The tilt's parameter: `quad_tilt_DEG`, DEG in [0, 89.9].
const TILT: Param = Param { name: "DEG", what: "tilt", unit: "°", min: 0.0, max: 89.9 };

impl Entry for TiltedQuad {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "quad_tilt_",
        description: "a square tilted by DEG degrees (0 = facing the camera) with the bricks texture",
        note: "",
        param: Some(TILT),
        horizon: false,
    };

    fn from_value(value: Option<f64>) -> Self {
        TiltedQuad { tilt: value.expect("a tilted quad has its tilt (tested by the registry)") }
    }

    fn value(&self) -> Option<f64> {
        Some(self.tilt)
    }

    /// 0°, 45°, 70° and 85°.
    fn lab() -> Vec<Self> {
        [0.0, 45.0, 70.0, 85.0].into_iter().map(|tilt| TiltedQuad { tilt }).collect()
    }

    fn build(&self, width: u32, height: u32) -> Result<Parts, SceneError> {
        let tilt = TILT.check(self.tilt)?;
        let (w, h) = (width as f64, height as f64);
        let f = 0.9 * w.min(h);
        let (st, ct) = tilt.to_radians().sin_cos();
        let d = 1.0;
        let corner = |lx: f64, ly: f64| DVec3::new(lx, ly * ct, d - ly * st);
        let q = QuadScene {
            corners: [corner(-0.5, -0.5), corner(0.5, -0.5), corner(0.5, 0.5), corner(-0.5, 0.5)],
            eye: DVec3::ZERO,
            screen_z: f,
        };
        // Screen coordinates are centred on the optical axis.
        let view = PlanarView::quad(&q, 1.0, DVec2::new(-0.5 * w, -0.5 * h))?;
        Ok(Parts {
            description: format!(
                "unit square tilted {tilt}° about the horizontal axis, 1 unit from the eye, \
                 bricks albedo (256²) repeated 2×2"
            ),
            view,
            texture: Texture::new(bricks_texture(256)?, Wrap::Repeat),
            uv_scale: 2.0,
            background: Vec3::splat(0.18),
            horizon_crop: None,
        })
    }
}
