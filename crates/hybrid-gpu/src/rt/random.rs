//! The CPU's per-pixel random streams in WGSL (`shaders/random.wgsl`): the same 64-bit
//! generator (`renderlab_hybrid::rng::Rng`) in pairs of 32-bit words, so that a GPU stage
//! draws, for each pixel, the very numbers the CPU stage draws; and the sampling helpers the
//! stages share (stratified points, cosine-weighted directions, the normal's frame, GGX's
//! visible normals, mirror reflection and refraction, as `renderlab_scene::sampling` has
//! them).

use renderlab_hybrid::rng::{Rng, Stream};

/// The WGSL functions.
pub const WGSL: &str = include_str!("../shaders/random.wgsl");

/// A stream's per-frame base as the shaders take it: `(low, high)` words of
/// [`Rng::stream_base`].
pub fn base_words(seed: u64, stream: Stream) -> [u32; 2] {
    let b = Rng::stream_base(seed, stream);
    [b as u32, (b >> 32) as u32]
}
