//! The forward translucent pass: the translucent layers of each pixel (kept by the geometry
//! pass, nearest first, front and back faces alike) blended over the composed opaque image
//! from back to front — sorting per pixel, so that intersecting and overlapping surfaces
//! come out in the right order from any side.
//!
//! Each layer is lit like an opaque surface (the same direct lighting and shadows, the
//! ambient diffuse term) plus a Fresnel reflection of the sky, and blended with the
//! premultiplied "over" operator:
//!
//! `c ← layer + (1 − α) · base_color · c`, `α = 1 − transmission · (1 − F)`,
//! `layer = emitted + direct + sky · kd · base_color + F · sky`,
//!
//! with `F` Schlick's Fresnel at `n·v` (its channel mean in α). The light behind passes
//! straight through, tinted by the base colour: no refraction, the raster limitation the
//! thesis describes, which the ray-traced translucency stage removes.

use super::ambient::diffuse_albedo;
use super::geometry::GeometryPass;
use super::lighting::{shade_direct, Visibility};
use glam::Vec3;
use rayon::prelude::*;
use renderlab_scene::{brdf, HybridScene, ShadingPoint};

/// Radiance a translucent layer adds and the fraction `1 − α` of the light behind it that it
/// lets through (before tinting).
pub fn layer_radiance(
    scene: &HybridScene,
    sp: &ShadingPoint,
    v: Vec3,
    pixel: usize,
    visibility: &dyn Visibility,
    area_samples: u32,
) -> (Vec3, f32) {
    let f = brdf::fresnel_schlick(sp.normal.dot(v).max(0.0), brdf::f0(sp));
    let transmitted = sp.transmission * (1.0 - (f.x + f.y + f.z) / 3.0);
    let radiance = sp.emissive
        + shade_direct(scene, sp, v, pixel, visibility, area_samples)
        + scene.sky * diffuse_albedo(sp, v)
        + f * scene.sky;
    (radiance, transmitted)
}

/// The final linear image: `opaque` (the composed opaque image) with every pixel's
/// translucent layers blended over it, back to front.
pub fn forward_translucent(
    scene: &HybridScene,
    geometry: &GeometryPass,
    opaque: &[Vec3],
    visibility: &dyn Visibility,
    area_samples: u32,
) -> Vec<Vec3> {
    let g = &geometry.gbuffer;
    opaque
        .par_iter()
        .enumerate()
        .map(|(i, &behind)| {
            let layers = &geometry.translucent_layers[i * geometry.layers..(i + 1) * geometry.layers];
            if layers[0].is_none() {
                return behind;
            }
            let v = -g.view_dir(i);
            layers.iter().rev().flatten().fold(behind, |c, sp| {
                let (radiance, transmitted) = layer_radiance(scene, sp, v, i, visibility, area_samples);
                radiance + sp.base_color * transmitted * c
            })
        })
        .collect()
}
