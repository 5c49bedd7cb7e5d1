//! TEMPORARY stand-ins for the rasterized deferred pipeline.
//!
//! The raster stages (geometry pass, shadow maps, SSR, SSAO, the forward translucent pass)
//! belong to `renderlab_raster::deferred`, written on another branch; until it lands, the
//! raster slots of a frame call these minimal versions so that the ray-traced stages have a
//! G-buffer and a baseline to replace. They are deliberately simple and NOT the thesis's
//! raster methods:
//!
//! * geometry pass: primary rays through pixel centres (exactly what a rasterizer samples);
//! * lighting pass: direct light WITHOUT shadows (area lights by a fixed 4×4 pattern);
//! * ambient: sky radiance × diffuse albedo (this one is the real "GI off" baseline);
//! * SSAO: none (AO = 1);
//! * SSR: the environment fallback only (sky × specular weight), no screen-space march;
//! * translucency: one layer blended over the opaque image with
//!   `alpha = 1 − transmission·(1 − F)`, its colour the layer's direct light plus `F·sky`.
//!
//! Replace each by the deferred module's stage function when it is merged.

use crate::accel::{resolve, Accel};
use crate::lighting::{ambient, specular_weight, unshadowed_direct};
use crate::stages::par_pixels;
use glam::Vec3;
use renderlab_core::Camera;
use renderlab_scene::brdf::{f0, fresnel_schlick};
use renderlab_scene::{GBuffer, HybridScene, LightingTerms};

/// Area-light samples of the stand-in lighting pass (a fixed 4×4 pattern).
pub const AREA_SAMPLES: u32 = 16;

/// The G-buffer by primary rays through pixel centres: the nearest opaque surface, and the
/// nearest translucent surface in front of it. Returns the buffer and the rays traced.
pub fn geometry_pass(scene: &HybridScene, accel: &Accel, camera: &Camera) -> (GBuffer, u64) {
    let mut g = GBuffer::empty(*camera);
    let origin = camera.position;
    let width = camera.width;
    let dirs: Vec<Vec3> = (0..g.opaque.len()).map(|i| g.view_dir(i)).collect();
    let mut rays = par_pixels(&mut g.opaque, width, |i, out| {
        let dir = dirs[i];
        *out = accel.closest_where(origin, dir, f32::INFINITY, |t| !t).map(|h| resolve(scene, &h, dir));
        1
    });
    let opaque = g.opaque.clone();
    rays += par_pixels(&mut g.translucent, width, |i, out| {
        let dir = dirs[i];
        let t_max = opaque[i].map_or(f32::INFINITY, |sp| (sp.position - origin).length());
        *out = accel.closest_where(origin, dir, t_max, |t| t).map(|h| resolve(scene, &h, dir));
        1
    });
    (g, rays)
}

/// Direct light without shadows into `direct`.
pub fn lighting_pass(scene: &HybridScene, g: &GBuffer, direct: &mut [Vec3]) -> u64 {
    par_pixels(direct, g.width(), |i, out| {
        if let Some(sp) = &g.opaque[i] {
            *out = unshadowed_direct(scene, sp, -g.view_dir(i), AREA_SAMPLES);
        }
        0
    })
}

/// Sky × diffuse albedo into `diffuse` (the "GI off" baseline).
pub fn ambient_pass(scene: &HybridScene, g: &GBuffer, diffuse: &mut [Vec3]) -> u64 {
    par_pixels(diffuse, g.width(), |i, out| {
        if let Some(sp) = &g.opaque[i] {
            *out = ambient(scene.sky, sp, -g.view_dir(i));
        }
        0
    })
}

/// No screen-space AO yet: AO = 1.
pub fn ssao_pass(_g: &GBuffer, _samples: u32, _radius: f32, ao: &mut [f32]) -> u64 {
    ao.fill(1.0);
    0
}

/// The environment fallback of SSR: sky × specular weight.
pub fn ssr_pass(scene: &HybridScene, g: &GBuffer, _terms: &LightingTerms, specular: &mut [Vec3]) -> u64 {
    par_pixels(specular, g.width(), |i, out| {
        if let Some(sp) = &g.opaque[i] {
            *out = scene.sky * specular_weight(sp, -g.view_dir(i));
        }
        0
    })
}

/// One translucent layer blended over `hdr`, no refraction.
pub fn translucent_pass(scene: &HybridScene, g: &GBuffer, hdr: &mut [Vec3]) -> u64 {
    par_pixels(hdr, g.width(), |i, out| {
        if let Some(sp) = &g.translucent[i] {
            let v = -g.view_dir(i);
            let f = fresnel_schlick(sp.normal.dot(v).clamp(0.0, 1.0), f0(sp));
            let alpha = (Vec3::ONE - sp.transmission * (Vec3::ONE - f)).clamp(Vec3::ZERO, Vec3::ONE);
            let layer = unshadowed_direct(scene, sp, v, AREA_SAMPLES) + f * scene.sky + sp.emissive;
            *out = layer + (Vec3::ONE - alpha) * *out;
        }
        0
    })
}
