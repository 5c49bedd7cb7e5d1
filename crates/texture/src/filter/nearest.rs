//! Nearest-texel lookup on level 0: one fetch, no interpolation, no antialiasing.

use super::descriptor::{Descriptor, Entry, Value};
use super::gpu_form::{Gpu, GpuForm, HardwareSampler, Levels};
use super::lookup::finite;
use super::sampling::Filter;
use crate::mip::Texture;
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;
use renderlab_core::fastmath::floor_i64;

/// Nearest-texel lookup on level 0 (1 fetch).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Nearest;

impl Filter for Nearest {
    fn name(&self) -> &'static str {
        Self::DESCRIPTOR.name
    }

    #[inline]
    fn sample<C: Counter>(&self, tex: &Texture, uv: Vec2, _: Vec2, _: Vec2, counter: &mut C) -> Vec4 {
        let s = tex.size();
        counter.count(1);
        tex.texel(0, floor_i64(finite(uv.x) * s.x), floor_i64(finite(uv.y) * s.y))
    }
}

impl Entry for Nearest {
    const DESCRIPTOR: Descriptor =
        Descriptor { name: "nearest", description: "nearest texel of level 0 (1 fetch)", params: &[] };

    fn from_values(_: &[Value]) -> Self {
        Nearest
    }

    fn values(&self) -> Vec<Value> {
        Vec::new()
    }

    /// The hardware's nearest texel on level 0.
    fn gpu(&self) -> Gpu {
        Gpu::Form(GpuForm::Sampler(HardwareSampler { linear: false, levels: Levels::Base }))
    }
}
