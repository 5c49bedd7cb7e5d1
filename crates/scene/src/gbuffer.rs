//! The contract between the hybrid pipeline's stages.
//!
//! The geometry pass (always rasterized, as in the thesis) fills a [`GBuffer`]: per pixel the
//! nearest opaque surface and the nearest translucent surface in front of it, both as
//! resolved [`ShadingPoint`]s. Each lighting stage — shadows, reflections, GI, AO — reads it
//! and writes its own term into [`LightingTerms`], by rasterization or by ray tracing, and
//! [`LightingTerms::compose`] adds the terms into the opaque image; the translucency stage
//! then draws the translucent layer over that image. Because every stage has exactly one
//! slot, switching one stage between its raster and its ray-traced form changes only that
//! slot, and its cost and error can be measured alone.

use crate::shading::ShadingPoint;
use glam::Vec3;
use renderlab_core::Camera;

/// Per-pixel surfaces seen by the camera.
#[derive(Clone, Debug)]
pub struct GBuffer {
    /// The camera the buffer was drawn with (its width and height are the buffer's).
    pub camera: Camera,
    /// Nearest opaque surface per pixel (row-major), `None` where the sky shows.
    pub opaque: Vec<Option<ShadingPoint>>,
    /// Nearest translucent surface in front of the opaque one, if any.
    pub translucent: Vec<Option<ShadingPoint>>,
}

impl GBuffer {
    /// An empty buffer (all sky) for `camera`.
    pub fn empty(camera: Camera) -> Self {
        let n = camera.width as usize * camera.height as usize;
        Self { camera, opaque: vec![None; n], translucent: vec![None; n] }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.camera.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.camera.height
    }

    /// Unit direction of the primary ray through the centre of pixel `i` (row-major).
    pub fn view_dir(&self, i: usize) -> Vec3 {
        let w = self.camera.width as usize;
        self.camera.ray_direction((i % w) as f32 + 0.5, (i / w) as f32 + 0.5)
    }
}

/// The lighting stages' outputs for the opaque layer, one value per pixel (row-major), in
/// linear radiance.
#[derive(Clone, Debug, PartialEq)]
pub struct LightingTerms {
    /// Direct light from every light source, shadows applied (the lighting pass with the
    /// shadow stage's visibility).
    pub direct: Vec<Vec3>,
    /// Diffuse light arriving indirectly: an ambient estimate when rasterized, one diffuse
    /// bounce when ray traced (GI).
    pub diffuse_indirect: Vec<Vec3>,
    /// Ambient occlusion in [0, 1] (1 = open), multiplying `diffuse_indirect`.
    pub ambient_occlusion: Vec<f32>,
    /// Specular light arriving indirectly (reflections: screen-space or ray traced, the
    /// sky where neither finds anything).
    pub specular_indirect: Vec<Vec3>,
}

impl LightingTerms {
    /// All terms zero and AO open, for `pixels` pixels.
    pub fn zero(pixels: usize) -> Self {
        Self {
            direct: vec![Vec3::ZERO; pixels],
            diffuse_indirect: vec![Vec3::ZERO; pixels],
            ambient_occlusion: vec![1.0; pixels],
            specular_indirect: vec![Vec3::ZERO; pixels],
        }
    }

    /// The opaque image in linear radiance: `emitted + direct + diffuse_indirect·AO +
    /// specular_indirect` where a surface is, the sky where none is.
    pub fn compose(&self, gbuffer: &GBuffer, sky: Vec3) -> Vec<Vec3> {
        gbuffer
            .opaque
            .iter()
            .enumerate()
            .map(|(i, sp)| match sp {
                None => sky,
                Some(sp) => {
                    sp.emissive
                        + self.direct[i]
                        + self.diffuse_indirect[i] * self.ambient_occlusion[i]
                        + self.specular_indirect[i]
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_adds_the_terms_and_shows_the_sky_elsewhere() {
        let camera = Camera::look_at(Vec3::Z, Vec3::ZERO, 2, 1);
        let mut g = GBuffer::empty(camera);
        g.opaque[0] = Some(ShadingPoint { emissive: Vec3::splat(0.5), ..ShadingPoint::default() });
        let mut t = LightingTerms::zero(2);
        t.direct[0] = Vec3::splat(1.0);
        t.diffuse_indirect[0] = Vec3::splat(2.0);
        t.ambient_occlusion[0] = 0.25;
        t.specular_indirect[0] = Vec3::splat(0.125);
        let img = t.compose(&g, Vec3::new(0.1, 0.2, 0.3));
        assert_eq!(img[0], Vec3::splat(0.5 + 1.0 + 0.5 + 0.125));
        assert_eq!(img[1], Vec3::new(0.1, 0.2, 0.3));
        assert!(g.view_dir(0).z < 0.0 && g.view_dir(0).x < 0.0 && g.view_dir(1).x > 0.0);
    }
}
