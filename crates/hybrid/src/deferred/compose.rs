//! The composition the reflection stage reflects: the lit opaque image of the stages before
//! it. (The frame's final composition of every term is `LightingTerms::compose`, in the
//! scene crate, beside the terms it composes.)

use glam::Vec3;
use renderlab_scene::{GBuffer, LightingTerms};

/// The lit opaque image the reflections reflect: `emitted + direct + diffuse_indirect · AO`
/// where a surface is, the sky elsewhere (`specular_indirect` is left out, so reflections
/// do not reflect reflections).
pub fn lit_opaque(gbuffer: &GBuffer, terms: &LightingTerms, sky: Vec3) -> Vec<Vec3> {
    gbuffer
        .opaque
        .iter()
        .enumerate()
        .map(|(i, sp)| match sp {
            None => sky,
            Some(sp) => {
                sp.emissive + terms.direct[i] + terms.diffuse_indirect[i] * terms.ambient_occlusion[i]
            }
        })
        .collect()
}
