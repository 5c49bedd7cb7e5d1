//! What a stage reads and writes when the frame runs it: the scene, its BVH, the geometry
//! pass, the raster settings and the seed; the lighting terms, the light visibility the
//! shadow stage provides to later passes, and the image the last stages draw on.
//!
//! The frame runs the stages by [`Phase`](super::entry::Phase): the G-buffer is complete
//! when the first runs; `image` holds the composed opaque image when a
//! [`Phase::Over`](super::entry::Phase::Over) stage runs, and that stage leaves the final
//! image in it.

use super::shadows::maps::ShadowMapCache;
use crate::accel::Accel;
use crate::deferred::geometry::{GeometryPass, PreparedScene};
use crate::deferred::lighting::{Unshadowed, Visibility};
use crate::deferred::settings::RasterSettings;
use glam::Vec3;
use rayon::prelude::*;
use renderlab_scene::{GBuffer, HybridScene, LightingTerms};

/// One frame as its stages see it.
pub struct StageContext<'a> {
    /// The scene.
    pub scene: &'a HybridScene,
    /// Its BVH.
    pub accel: &'a Accel,
    /// Its world meshes, as the raster passes draw them.
    pub prepared: &'a PreparedScene<'a>,
    /// The geometry pass: the G-buffer and the translucent layers.
    pub geometry: &'a GeometryPass,
    /// The raster stages' parameters for this frame.
    pub raster: &'a RasterSettings,
    /// The cached shadow maps of the scene's static lights.
    pub shadow_maps: &'a ShadowMapCache,
    /// Seed of every ray-traced stage's random numbers.
    pub seed: u64,
    /// The lighting terms the stages write.
    pub terms: LightingTerms,
    /// The light visibility of the frame's shadow choice, for the passes after the shadow
    /// stage that light surfaces themselves (the forward translucent pass).
    pub visibility: Box<dyn Visibility + 'a>,
    /// The composed opaque image, then the final image (row-major linear radiance).
    pub image: Vec<Vec3>,
}

impl<'a> StageContext<'a> {
    /// A frame about to run its stages: zero terms, no shadows yet, no image yet.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        scene: &'a HybridScene,
        accel: &'a Accel,
        prepared: &'a PreparedScene<'a>,
        geometry: &'a GeometryPass,
        raster: &'a RasterSettings,
        shadow_maps: &'a ShadowMapCache,
        seed: u64,
    ) -> Self {
        Self {
            scene,
            accel,
            prepared,
            geometry,
            raster,
            shadow_maps,
            seed,
            terms: LightingTerms::zero(geometry.gbuffer.opaque.len()),
            visibility: Box::new(Unshadowed),
            image: Vec::new(),
        }
    }

    /// The G-buffer.
    pub fn gbuffer(&self) -> &'a GBuffer {
        &self.geometry.gbuffer
    }
}

/// Runs `f(pixel, &mut out[pixel])` for every pixel, rows in parallel, and sums the counts
/// it returns. Each pixel's work depends only on its index, and integer sums do not depend
/// on their order, so the result is the same for any number of threads.
pub fn par_pixels<T: Send>(out: &mut [T], width: u32, f: impl Fn(usize, &mut T) -> u64 + Sync) -> u64 {
    let w = width.max(1) as usize;
    out.par_chunks_mut(w)
        .enumerate()
        .map(|(y, row)| row.iter_mut().enumerate().map(|(x, o)| f(y * w + x, o)).sum::<u64>())
        .sum()
}
