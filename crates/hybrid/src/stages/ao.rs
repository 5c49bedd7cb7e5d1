//! Ray-traced ambient occlusion: `samples_per_pixel` cosine-distributed rays of length
//! `radius` about the shading normal, tested for any hit; AO is the fraction that escapes.
//! With cosine-distributed rays this fraction estimates the cosine-weighted openness
//! `(1/π) ∫ V(ω) cos θ dω`, the quantity that multiplies the diffuse indirect term.

use crate::rng::{stratified, Rng, Stream};
use crate::stages::par_pixels;
use crate::Accel;
use renderlab_scene::sampling::{cosine_hemisphere, Frame};
use renderlab_scene::GBuffer;

/// Writes AO in [0, 1] of every opaque pixel to `ao`; returns the rays traced.
pub fn run(
    accel: &Accel,
    g: &GBuffer,
    samples_per_pixel: u32,
    radius: f32,
    seed: u64,
    ao: &mut [f32],
) -> u64 {
    par_pixels(ao, g.width(), |i, out| {
        let Some(sp) = &g.opaque[i] else { return 0 };
        let mut rng = Rng::new(seed, i as u64, Stream::Ao);
        let frame = Frame::new(sp.normal);
        let shift = rng.vec2();
        let n = samples_per_pixel.max(1);
        let mut open = 0u32;
        let mut rays = 0;
        for s in 0..n {
            let (local, _) = cosine_hemisphere(stratified(s, n, shift));
            let dir = frame.to_world(local);
            if dir.dot(sp.geometric_normal) <= 0.0 {
                // A shading normal tilted from the face sends some rays into the surface:
                // they count as occluded, without a ray.
                continue;
            }
            rays += 1;
            if !accel.occluded(sp.offset_origin(dir), dir, radius) {
                open += 1;
            }
        }
        *out = open as f32 / n as f32;
        rays
    })
}
