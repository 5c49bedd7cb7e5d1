//! Normal mapping: the thesis's lighting with the normal map, at the undisplaced UV.

use super::basic::Undisplaced;
use super::descriptor::{Descriptor, Entry, WithTracer};
use crate::kernel::Kernel;
use crate::trace::Shading;

/// Normal mapping.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct NormalMapping;

impl Entry for NormalMapping {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "normal",
        summary: "normal-mapped lighting at the undisplaced UV",
        params: &[],
        needs: &[],
        kernels: &[Kernel::Scalar],
        shading: Shading::Lit,
    };

    fn from_params(_: &[u32]) -> Result<Self, String> {
        Ok(NormalMapping)
    }

    fn params(&self) -> Vec<u32> {
        Vec::new()
    }

    const WGSL: Option<&'static str> = Some(include_str!("normal.wgsl"));

    fn dispatch<A: WithTracer>(&self, _: Kernel, action: A) -> A::Output {
        action.run(&Undisplaced)
    }
}
