//! Ray-traced shadows: the lighting pass with visibility from shadow rays.
//!
//! For each light and pixel, shadow rays (any hit) leave `sp.offset_origin(l)` toward the
//! light sample and stop just short of it: one ray for a punctual light (a hard, exact
//! shadow), `samples_per_light` for an area light, stratified over its rectangle with a
//! random rotation per pixel (a soft shadow whose noise falls as the samples grow). The
//! pixel's direct light is `Σ brdf::eval · radiance · visible`, written to `direct`.

use crate::lighting::direct_light;
use crate::rng::{Rng, Stream};
use crate::stages::par_pixels;
use crate::Accel;
use glam::Vec3;
use renderlab_scene::{GBuffer, HybridScene};

/// Writes the shadowed direct light of every opaque pixel to `direct`; returns the shadow
/// rays traced.
pub fn run(
    scene: &HybridScene,
    accel: &Accel,
    g: &GBuffer,
    samples_per_light: u32,
    seed: u64,
    direct: &mut [Vec3],
) -> u64 {
    par_pixels(direct, g.width(), |i, out| {
        let Some(sp) = &g.opaque[i] else { return 0 };
        let mut rng = Rng::new(seed, i as u64, Stream::Shadows);
        let mut rays = 0;
        *out = direct_light(scene, accel, sp, -g.view_dir(i), samples_per_light, &mut rng, &mut rays);
        rays
    })
}
