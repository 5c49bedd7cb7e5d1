//! Lights: point, spot and directional (as `KHR_lights_punctual` defines them) and
//! rectangular area lights, the one kind whose shadows have a penumbra.
//!
//! Every light answers one question for a surface point: "a direction toward you, how far,
//! and how much light arrives along it" ([`Light::sample`]). Punctual lights answer it
//! exactly; an area light answers it for a point on its surface chosen by a 2-D sample, with
//! the radiance already divided by the sampling density, so that averaging many samples
//! estimates the light's whole contribution. The rasterizer asks with a fixed stratified set
//! of samples, the tracers with random ones: the same integral, two estimators.

use crate::error::{Result, SceneError};
use glam::{Vec2, Vec3};

/// The shape of a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Emits equally in every direction from `position`.
    Point,
    /// A point light restricted to a cone around `direction`; full intensity inside
    /// `inner_cone`, none outside `outer_cone` (half-angles in radians).
    Spot {
        /// Half-angle of full intensity, radians.
        inner_cone: f32,
        /// Half-angle beyond which nothing is emitted, radians.
        outer_cone: f32,
    },
    /// Parallel light travelling along `direction` from infinitely far away.
    Directional,
    /// A one-sided emitting rectangle centred at `position`, spanning `±half_u` and
    /// `±half_v`; it emits toward `half_u × half_v`.
    Area {
        /// Half of one edge (world units, a vector).
        half_u: Vec3,
        /// Half of the other edge.
        half_v: Vec3,
    },
}

/// A light source.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Name (from the file, or the procedural scene's own).
    pub name: String,
    /// Shape.
    pub kind: LightKind,
    /// Position (point, spot, area centre); unused by directional lights.
    pub position: Vec3,
    /// Unit direction the light travels (spot axis, directional); unused otherwise.
    pub direction: Vec3,
    /// Linear RGB colour.
    pub color: Vec3,
    /// Intensity: radiant intensity for point and spot lights (irradiance falls as 1/d²),
    /// irradiance for directional lights, emitted radiance for area lights.
    pub intensity: f32,
    /// Distance beyond which a point or spot light has no effect (glTF's smooth window);
    /// `None` is unlimited.
    pub range: Option<f32>,
}

/// One sample of a light seen from a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction from the surface point toward the light.
    pub to_light: Vec3,
    /// Distance to the sampled point of the light (`f32::INFINITY` for directional lights);
    /// a shadow ray stops just short of it.
    pub distance: f32,
    /// Incident radiance along `to_light` divided by the sample's density (in solid angle),
    /// so that `brdf · cos θ · radiance`, averaged over samples, estimates the reflected light.
    pub radiance: Vec3,
}

impl Light {
    /// A white light named `light` of `kind` at `position` facing `direction` (normalised;
    /// zero if degenerate), of `intensity` (see [`Light::intensity`] for its unit), without a
    /// range limit: how the built-in test and benchmark scenes place their lights.
    pub fn white(kind: LightKind, position: Vec3, direction: Vec3, intensity: f32) -> Light {
        Light {
            name: "light".into(),
            kind,
            position,
            direction: direction.normalize_or_zero(),
            color: Vec3::ONE,
            intensity,
            range: None,
        }
    }

    /// Whether the light has extent (its shadows need many samples to be soft).
    pub fn is_area(&self) -> bool {
        matches!(self.kind, LightKind::Area { .. })
    }

    /// The light's emitting normal (area lights) — the side it shines toward.
    pub fn area_normal(&self) -> Option<Vec3> {
        match self.kind {
            LightKind::Area { half_u, half_v } => Some(half_u.cross(half_v).normalize()),
            _ => None,
        }
    }

    /// A sample of the light seen from `p`; `u` in [0, 1)² picks the point on an area light
    /// (punctual lights ignore it). Zero radiance where the point is outside a spot's cone,
    /// beyond the range, or behind an area light.
    pub fn sample(&self, p: Vec3, u: Vec2) -> LightSample {
        let energy = self.color * self.intensity;
        match self.kind {
            LightKind::Directional => {
                LightSample { to_light: -self.direction, distance: f32::INFINITY, radiance: energy }
            }
            LightKind::Point | LightKind::Spot { .. } => {
                let d = self.position - p;
                let dist2 = d.length_squared().max(1e-12);
                let dist = dist2.sqrt();
                let to_light = d / dist;
                let mut falloff = self.range.map_or(1.0, |r| {
                    let x = (dist / r).powi(4);
                    (1.0 - x).clamp(0.0, 1.0).powi(2)
                });
                if let LightKind::Spot { inner_cone, outer_cone } = self.kind {
                    let cd = (-to_light).dot(self.direction);
                    let (ci, co) = (inner_cone.cos(), outer_cone.cos());
                    let t = ((cd - co) / (ci - co).max(1e-6)).clamp(0.0, 1.0);
                    falloff *= t * t;
                }
                LightSample { to_light, distance: dist, radiance: energy * (falloff / dist2) }
            }
            LightKind::Area { half_u, half_v } => {
                let q = self.position + half_u * (2.0 * u.x - 1.0) + half_v * (2.0 * u.y - 1.0);
                let n = half_u.cross(half_v);
                let area = 4.0 * n.length();
                let n = n.normalize();
                let d = q - p;
                let dist2 = d.length_squared().max(1e-12);
                let dist = dist2.sqrt();
                let to_light = d / dist;
                // The light shines toward +n: seen from p, its surface faces p when -to_light·n > 0.
                let cos_l = (-to_light).dot(n).max(0.0);
                LightSample { to_light, distance: dist, radiance: energy * (cos_l * area / dist2) }
            }
        }
    }

    /// Checks that the light's parameters are finite and meaningful.
    pub fn validate(&self) -> Result<()> {
        let bad = |why: &str| Err(SceneError::Invalid(format!("light {:?}: {why}", self.name)));
        if !(self.position.is_finite() && self.direction.is_finite() && self.color.is_finite()) {
            return bad("non-finite position, direction or colour");
        }
        if !(self.intensity.is_finite() && self.intensity >= 0.0) {
            return bad("intensity must be finite and not negative");
        }
        if self.range.is_some_and(|r| !(r.is_finite() && r > 0.0)) {
            return bad("range must be positive");
        }
        match self.kind {
            LightKind::Directional | LightKind::Spot { .. }
                if (self.direction.length() - 1.0).abs() >= 1e-3 =>
            {
                bad("direction must be a unit vector")
            }
            LightKind::Spot { inner_cone, outer_cone }
                if !(0.0 <= inner_cone
                    && inner_cone < outer_cone
                    && outer_cone <= std::f32::consts::FRAC_PI_2) =>
            {
                bad("spot cones need 0 <= inner < outer <= pi/2")
            }
            LightKind::Area { half_u, half_v }
                if !(half_u.is_finite() && half_v.is_finite() && half_u.cross(half_v).length() > 0.0) =>
            {
                bad("area light has no area")
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn area() -> Light {
        Light {
            name: "panel".into(),
            kind: LightKind::Area { half_u: Vec3::new(0.5, 0.0, 0.0), half_v: Vec3::new(0.0, 0.0, 0.5) },
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: Vec3::NEG_Y,
            color: Vec3::ONE,
            intensity: 3.0,
            range: None,
        }
    }

    #[test]
    fn an_area_light_faces_down() {
        // half_u × half_v = X × Z = -Y: it shines downward.
        assert!((area().area_normal().unwrap() - Vec3::NEG_Y).length() < 1e-6);
        let s = area().sample(Vec3::new(0.0, 4.0, 0.0), Vec2::splat(0.5));
        assert_eq!(s.radiance, Vec3::ZERO, "a point above the panel sees its back");
    }

    #[test]
    fn far_away_an_area_light_is_a_point_light_of_radiance_times_area() {
        // At distance 1000 straight below, E ≈ L·A/d².
        let p = Vec3::new(0.0, 2.0 - 1000.0, 0.0);
        let s = area().sample(p, Vec2::new(0.3, 0.8));
        let expected = 3.0 * 1.0 / (1000.0f32 * 1000.0);
        assert!((s.radiance.x / expected - 1.0).abs() < 1e-3, "{} vs {expected}", s.radiance.x);
    }

    proptest! {
        /// The irradiance from 8×8 stratified samples of a square light agrees with a
        /// 256×256 quadrature within 2 % for a receiver straight below it at any height
        /// from half the light's size up: the sample weights carry the whole solid-angle
        /// conversion.
        #[test]
        fn stratified_samples_match_a_fine_quadrature(h in 0.5f32..4.0) {
            let light = area();
            let p = Vec3::new(0.0, 2.0 - h, 0.0);
            let est = |n: u32| {
                let mut sum = 0.0f64;
                for j in 0..n {
                    for i in 0..n {
                        let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                        let s = light.sample(p, u);
                        // Receiver facing up: cos θ = to_light.y.
                        sum += (s.radiance.x * s.to_light.y.max(0.0)) as f64;
                    }
                }
                sum / (n * n) as f64
            };
            let coarse = est(8);
            let fine = est(256);
            prop_assert!((coarse / fine - 1.0).abs() < 0.02, "8×8 {coarse} vs 256×256 {fine}");
        }
    }
}
