//! Trilinear mip-mapping: bilinear on the two levels around the footprint's level of detail
//! (the Vulkan rule, [`lod`]), blended linearly; eight fetches.

use super::descriptor::{Descriptor, Entry, Value};
use super::gpu_form::{Gpu, GpuForm, HardwareSampler, Levels};
use super::lookup::{lod, trilinear_at};
use super::sampling::Filter;
use crate::mip::Texture;
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;

/// Trilinear mip-mapping (8 fetches): bilinear on the two levels around the LOD of [`lod`],
/// blended linearly.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Trilinear;

impl Filter for Trilinear {
    fn name(&self) -> &'static str {
        Self::DESCRIPTOR.name
    }

    #[inline]
    fn sample<C: Counter>(
        &self,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4 {
        trilinear_at(tex, uv, lod(tex, duv_dx, duv_dy), counter)
    }
}

impl Entry for Trilinear {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "trilinear",
        description: "mip-mapping, level from the longer screen axis' footprint as GPUs choose it (8 fetches)",
        params: &[],
    };

    fn from_values(_: &[Value]) -> Self {
        Trilinear
    }

    fn values(&self) -> Vec<Value> {
        Vec::new()
    }

    /// The hardware's trilinear filter, its level chosen by the hardware from the footprint's
    /// Jacobian passed as explicit gradients.
    fn gpu(&self) -> Gpu {
        Gpu::Form(GpuForm::Sampler(HardwareSampler { linear: true, levels: Levels::Gradients }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mip::Wrap;
    use renderlab_core::counter::Tally;
    use renderlab_core::Image;

    #[test]
    fn trilinear_of_constant_is_constant() {
        let t = Texture::from_gray(&Image::new(33, 17, 0.25), Wrap::Repeat);
        let mut c = Tally::default();
        for k in 0..20 {
            let d = Vec2::new(0.01 * k as f32, 0.003);
            let v = Trilinear.sample(&t, Vec2::new(0.3, 0.7), d, d.perp(), &mut c);
            assert!((v.x - 0.25).abs() < 1e-5);
        }
    }

    #[test]
    fn nan_uv_is_defined() {
        let t = Texture::from_gray(&Image::from_fn(8, 4, |x, _| x as f32 / 7.0), Wrap::Clamp);
        let mut c = Tally::default();
        let v = Trilinear.sample(&t, Vec2::NAN, Vec2::NAN, Vec2::NAN, &mut c);
        assert!(v.is_finite());
    }
}
