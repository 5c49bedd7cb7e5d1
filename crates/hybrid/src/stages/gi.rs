//! Ray-traced global illumination: one diffuse bounce.
//!
//! From every opaque pixel, `samples_per_pixel` cosine-distributed rays (stratified, with a
//! random rotation per pixel) find the nearest surface; its outgoing radiance toward the
//! pixel is estimated by its emission plus its direct light (one shadow ray per light, one
//! random sample per area light); a ray that escapes sees the sky. The mean, times the
//! pixel's diffuse albedo `kd·base_colour`, is the indirect diffuse light (cosine sampling
//! cancels the `cos θ / π` of the Lambertian term). Written to `diffuse_indirect`, where the
//! composition multiplies it by AO.
//!
//! Only one bounce: light that reaches the hit point indirectly is left out, so converged
//! GI equals a path tracer limited to paths of two segments (and no refraction).

use crate::lighting::{diffuse_albedo, direct_light};
use crate::reference::REGULARIZE_ROUGHNESS;
use crate::rng::{stratified, Rng, Stream};
use crate::stages::par_pixels;
use crate::Accel;
use glam::Vec3;
use renderlab_scene::sampling::{cosine_hemisphere, Frame};
use renderlab_scene::{GBuffer, HybridScene};

/// Writes the one-bounce diffuse indirect light of every opaque pixel; returns the rays
/// traced (bounce rays and their shadow rays).
pub fn run(
    scene: &HybridScene,
    accel: &Accel,
    g: &GBuffer,
    samples_per_pixel: u32,
    seed: u64,
    out: &mut [Vec3],
) -> u64 {
    par_pixels(out, g.width(), |i, out| {
        let Some(sp) = &g.opaque[i] else { return 0 };
        let v = -g.view_dir(i);
        let albedo = diffuse_albedo(sp, v);
        if albedo == Vec3::ZERO {
            *out = Vec3::ZERO;
            return 0;
        }
        let mut rng = Rng::new(seed, i as u64, Stream::Gi);
        let frame = Frame::new(sp.normal);
        let shift = rng.vec2();
        let n = samples_per_pixel.max(1);
        let mut sum = Vec3::ZERO;
        let mut rays = 0;
        for s in 0..n {
            let (local, _) = cosine_hemisphere(stratified(s, n, shift));
            let dir = frame.to_world(local);
            if dir.dot(sp.geometric_normal) <= 0.0 {
                continue;
            }
            rays += 1;
            sum += match accel.surface(scene, sp.offset_origin(dir), dir) {
                None => scene.sky,
                Some(mut hit) => {
                    // After this diffuse bounce the reference regularises (no caustics); so
                    // does the stage, so that it converges to the reference's answer.
                    hit.roughness = hit.roughness.max(REGULARIZE_ROUGHNESS);
                    hit.emissive + direct_light(scene, accel, &hit, -dir, 1, &mut rng, &mut rays)
                }
            };
        }
        *out = albedo * sum / n as f32;
        rays
    })
}
