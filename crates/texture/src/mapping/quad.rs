//! The textured planar quad seen from an eye point, as in the thesis's program, and its
//! screen→texture mapping.

// `!(x > t)` is deliberate throughout: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::error::MappingError;
use super::projective::{Projective, REL_EPS};
use glam::{DVec2, DVec3};

/// A textured planar quad `P1…P4` in 3D seen from the eye `O1` through the screen plane
/// `z = screen_z`, as in the thesis's MFC program. Texture coordinates are the unit square:
/// `P1 → (0,0)`, `P2 → (1,0)`, `P3 → (1,1)`, `P4 → (0,1)`. The eye looks along +z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadScene {
    /// Corners `P1…P4`, in order around the quad.
    pub corners: [DVec3; 4],
    /// The eye (centre of projection) `O1`.
    pub eye: DVec3,
    /// z of the screen plane; screen coordinates are the plane's x and y.
    pub screen_z: f64,
}

impl QuadScene {
    /// Screen-plane z used by [`QuadScene::thesis_default`]. The thesis never states it; 1000
    /// puts the quad's image at about 150×155 px, inside the program's 232×400 output box.
    pub const THESIS_SCREEN_Z: f64 = 1000.0;

    /// The thesis's scene (Fig. 4.1): P1(80,50,1600), P2(240,80,1500), P3(200,280,1100),
    /// P4(40,250,1200), eye O1(130,240,0). The four corners are exactly coplanar and form a
    /// parallelogram (P1 + P3 = P2 + P4), which supports the OCR reading "280" for P3.y.
    pub fn thesis_default() -> Self {
        QuadScene {
            corners: [
                DVec3::new(80.0, 50.0, 1600.0),
                DVec3::new(240.0, 80.0, 1500.0),
                DVec3::new(200.0, 280.0, 1100.0),
                DVec3::new(40.0, 250.0, 1200.0),
            ],
            eye: DVec3::new(130.0, 240.0, 0.0),
            screen_z: Self::THESIS_SCREEN_Z,
        }
    }

    /// Checks the scene: finite, in front of the eye, no three corners collinear, planar,
    /// eye off the plane.
    pub fn validate(&self) -> Result<(), MappingError> {
        if self.corners.iter().any(|p| !p.is_finite()) {
            return Err(MappingError::NonFinite { what: "quad corner" });
        }
        if !self.eye.is_finite() {
            return Err(MappingError::NonFinite { what: "eye" });
        }
        if !self.screen_z.is_finite() {
            return Err(MappingError::NonFinite { what: "screen plane z" });
        }
        if !(self.screen_z > self.eye.z) {
            return Err(MappingError::ScreenBehindEye { screen_z: self.screen_z, eye_z: self.eye.z });
        }
        let p = &self.corners;
        let size = (0..4).map(|k| (p[(k + 1) % 4] - p[k]).length()).fold(0.0, f64::max);
        for (k, c) in p.iter().enumerate() {
            let depth = c.z - self.eye.z;
            if !(depth > REL_EPS * size.max(1.0)) {
                return Err(MappingError::BehindEye { index: k + 1, depth });
            }
        }
        for tri in [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]] {
            let n = (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]);
            if !(n.length() > REL_EPS * size * size) {
                return Err(MappingError::Collinear([tri[0] + 1, tri[1] + 1, tri[2] + 1]));
            }
        }
        let n = (p[1] - p[0]).cross(p[3] - p[0]).normalize();
        let off = (p[2] - p[0]).dot(n).abs() / size;
        if !(off <= 1e-6) {
            return Err(MappingError::NonPlanar(off));
        }
        let eye_off = (self.eye - p[0]).dot(n).abs();
        if !(eye_off > REL_EPS * size.max((self.eye - p[0]).length())) {
            return Err(MappingError::EyeInPlane);
        }
        Ok(())
    }

    /// The corners' images on the screen plane, `S = O1 + (z − O1.z)/(P.z − O1.z) · (P − O1)`.
    pub fn project(&self) -> Result<[DVec2; 4], MappingError> {
        self.validate()?;
        let o = self.eye;
        let t = self.screen_z - o.z;
        Ok(self.corners.map(|p| {
            let s = o + (p - o) * (t / (p.z - o.z));
            DVec2::new(s.x, s.y)
        }))
    }

    /// The screen→texture mapping (`A…I`): the inverse, by adjugate, of the unit square's
    /// projective map onto the projected quad. For a planar quad this is exact: the plane's
    /// projection is itself projective.
    pub fn mapping(&self) -> Result<Projective, MappingError> {
        let s = self.project()?;
        Projective::quad_to_square(s)
    }

    /// Depth `P.z − eye.z` of the quad's surface point seen at screen point `(x, y)`, or
    /// `None` off the plane's visible half (at or beyond the horizon).
    pub fn depth_at(&self, x: f64, y: f64) -> Option<f64> {
        self.validate().ok()?;
        let o = self.eye;
        let dir = DVec3::new(x, y, self.screen_z) - o;
        let p = &self.corners;
        let n = (p[1] - p[0]).cross(p[3] - p[0]);
        let den = dir.dot(n);
        if den == 0.0 {
            return None;
        }
        let t = (p[0] - o).dot(n) / den;
        (t > 0.0 && t.is_finite()).then_some(t * dir.z)
    }
}
