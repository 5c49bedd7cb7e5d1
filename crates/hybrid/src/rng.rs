//! The per-pixel random numbers of the ray-traced stages and the path tracer.
//!
//! Every pixel of every stage draws from its own stream, seeded from `(seed, pixel, stage)`
//! by a hash, so an image does not depend on how pixels are spread over threads: the same
//! seed gives bit-identical images on one thread or many.

use glam::Vec2;

/// Which consumer a stream belongs to (part of the seed, so consumers never share numbers).
/// Each stage names its own in its descriptor (`stages::NAME::STREAM`); the
/// registry's test checks that no two consumers share one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Stream(pub u64);

impl Stream {
    /// The path tracer's first half.
    pub const REFERENCE_A: Stream = Stream(6);
    /// The path tracer's second half.
    pub const REFERENCE_B: Stream = Stream(7);
    /// The path tracer's ambient-occlusion rays, first half.
    pub const REFERENCE_AO_A: Stream = Stream(8);
    /// The path tracer's ambient-occlusion rays, second half.
    pub const REFERENCE_AO_B: Stream = Stream(9);
}

/// SplitMix64's finaliser: a bijective avalanche of 64 bits.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A small, fast generator (SplitMix64: a Weyl sequence through `mix`), ample for Monte
/// Carlo estimates of a few thousand samples per pixel.
#[derive(Clone, Debug)]
pub struct Rng {
    state: u64,
}

impl Rng {
    /// The stream of `pixel` in `stream` for the frame seed `seed`.
    pub fn new(seed: u64, pixel: u64, stream: Stream) -> Self {
        Self::from_base(Self::stream_base(seed, stream), pixel)
    }

    /// What every pixel's stream of `stream` shares in a frame seeded `seed`: computed once
    /// per frame (the GPU stages receive it and derive each pixel's stream as
    /// [`Rng::from_base`] does).
    pub fn stream_base(seed: u64, stream: Stream) -> u64 {
        seed ^ mix(stream.0 << 56)
    }

    /// The stream of `pixel` from the frame's [`Rng::stream_base`].
    pub fn from_base(base: u64, pixel: u64) -> Self {
        Self { state: mix(base ^ mix(pixel.wrapping_add(0x9e37_79b9_7f4a_7c15))) }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        mix(self.state)
    }

    /// Uniform in [0, 1).
    pub fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// Uniform in [0, 1)².
    pub fn vec2(&mut self) -> Vec2 {
        Vec2::new(self.f32(), self.f32())
    }
}

/// Sample `i` of `n` stratified points in [0, 1)², rotated by `shift` (Cranley–Patterson):
/// the first coordinate is stratified in `n` strata, the second follows the golden-ratio
/// sequence, so any `n` (not only squares) covers the square evenly. A random `shift` per
/// pixel turns the fixed pattern into an unbiased estimator without visible structure.
pub fn stratified(i: u32, n: u32, shift: Vec2) -> Vec2 {
    const G: f64 = 0.618_033_988_749_894_9;
    let x = (i as f64 + 0.5) / n as f64;
    let y = (i as f64 * G).fract();
    let w = |a: f64, s: f32| {
        let v = (a + s as f64).fract() as f32;
        v.min(1.0 - f32::EPSILON / 2.0)
    };
    Vec2::new(w(x, shift.x), w(y, shift.y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_differ_and_repeat() {
        let a: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 2, crate::stages::gi::STREAM), |r, _| Some(r.next_u64()))
            .collect();
        let b: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 2, crate::stages::gi::STREAM), |r, _| Some(r.next_u64()))
            .collect();
        let c: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 2, crate::stages::ao::STREAM), |r, _| Some(r.next_u64()))
            .collect();
        let d: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 3, crate::stages::gi::STREAM), |r, _| Some(r.next_u64()))
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_ne!(a, d);
    }

    #[test]
    fn uniform_numbers_have_the_right_mean_and_range() {
        let mut r = Rng::new(7, 0, crate::stages::shadows::STREAM);
        let n = 100_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let x = r.f32();
            assert!((0.0..1.0).contains(&x));
            sum += x as f64;
        }
        // Standard error of the mean is 1/sqrt(12 n) ≈ 0.0009; 5 of them.
        assert!((sum / n as f64 - 0.5).abs() < 0.0046);
    }

    #[test]
    fn stratified_points_fill_every_stratum_once() {
        let n = 7;
        let mut seen = [0u32; 7];
        for i in 0..n {
            let p = stratified(i, n, Vec2::new(0.3, 0.9));
            assert!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
            seen[(p.x * n as f32) as usize] += 1;
        }
        assert_eq!(seen, [1; 7]);
    }
}
