//! Bilinear interpolation on level 0: four fetches, no antialiasing under minification.

use super::descriptor::{Descriptor, Entry, Value};
use super::gpu_form::{Gpu, GpuForm, HardwareSampler, Levels};
use super::lookup::bilinear_level;
use super::sampling::Filter;
use crate::mip::Texture;
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;

/// Bilinear interpolation on level 0 (4 fetches): no antialiasing under minification.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Bilinear;

impl Filter for Bilinear {
    fn name(&self) -> &'static str {
        Self::DESCRIPTOR.name
    }

    #[inline]
    fn sample<C: Counter>(&self, tex: &Texture, uv: Vec2, _: Vec2, _: Vec2, counter: &mut C) -> Vec4 {
        bilinear_level(tex, 0, uv, counter)
    }
}

impl Entry for Bilinear {
    const DESCRIPTOR: Descriptor =
        Descriptor { name: "bilinear", description: "bilinear on level 0 (4 fetches)", params: &[] };

    fn from_values(_: &[Value]) -> Self {
        Bilinear
    }

    fn values(&self) -> Vec<Value> {
        Vec::new()
    }

    /// The hardware's bilinear filter on level 0.
    fn gpu(&self) -> Gpu {
        Gpu::Form(GpuForm::Sampler(HardwareSampler { linear: true, levels: Levels::Base }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mip::Wrap;
    use renderlab_core::counter::Tally;
    use renderlab_core::Image;

    fn ramp() -> Texture {
        Texture::from_gray(&Image::from_fn(8, 4, |x, _| x as f32 / 7.0), Wrap::Clamp)
    }

    #[test]
    fn bilinear_hits_texel_centres_and_interpolates() {
        let t = ramp();
        let mut c = Tally::default();
        let v = Bilinear.sample(&t, Vec2::new(2.5 / 8.0, 0.5), Vec2::ZERO, Vec2::ZERO, &mut c);
        assert!((v.x - 2.0 / 7.0).abs() < 1e-6);
        let v = Bilinear.sample(&t, Vec2::new(3.0 / 8.0, 0.5), Vec2::ZERO, Vec2::ZERO, &mut c);
        assert!((v.x - 2.5 / 7.0).abs() < 1e-6);
        assert_eq!(c.0, 8);
    }
}
