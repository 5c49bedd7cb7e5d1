//! A material prepared for relief rendering: filtered textures, the depth field, the
//! complexity map and (on request) the cone map.

use crate::fused::texture8::Textures8;
use crate::maps::complexity::{complexity_map, ComplexityCodes, ComplexityParams};
use crate::maps::cone::{ConeKind, ConeMap};
use crate::maps::height::HeightField;
use crate::maps::packed::PackedRelief;
use crate::maps::pyramid::DepthPyramid;
use crate::trace::ReliefInputs;
use renderlab_core::{Image, Material};
use renderlab_texture::{Texture, Wrap};

/// Size (per side, at most) of the cone map built for cone-step mapping.
pub const CONE_MAP_SIZE: u32 = 512;

/// Everything the relief renderer reads for one material.
#[derive(Clone, Debug)]
pub struct ReliefMaterial {
    /// Material name.
    pub name: String,
    /// Albedo with its mip pyramid (linear light, repeat wrap).
    pub albedo: Texture,
    /// Tangent-space normals with their mip pyramid.
    pub normal: Texture,
    /// Depth field (1 − height), bilinear.
    pub height: HeightField,
    /// Depth scale in UV per unit depth.
    pub height_scale: f32,
    /// The thesis's Sobel complexity map of the height map.
    pub complexity: Image<f32>,
    /// The complexity map as one byte per texel (when it has at most 256 distinct values).
    pub complexity_codes: Option<ComplexityCodes>,
    /// Relaxed cone map, if built.
    pub cone: Option<ConeMap>,
    /// The depth field packed with the cone ratios (ratios 0 without a cone map).
    pub packed: PackedRelief,
    /// The min-depth pyramid (built always: one pass over the depth field per level).
    pub pyramid: DepthPyramid,
    /// Albedo and normals in the fused frame's 8-bit formats, rounded from the pyramids above.
    pub textures8: Textures8,
}

impl ReliefMaterial {
    /// Prepares `m`: builds pyramids, the depth field and the complexity map with `params`;
    /// builds the relaxed cone map too when `with_cone_map` is set, at [`CONE_MAP_SIZE`].
    pub fn new(m: &Material, params: &ComplexityParams, with_cone_map: bool) -> Self {
        Self::with_cone_size(m, params, with_cone_map.then_some(CONE_MAP_SIZE))
    }

    /// Like [`ReliefMaterial::new`] with the cone map's largest side chosen (`None`: no cone
    /// map). Larger maps give wider, more precise cones and cost more to build.
    pub fn with_cone_size(m: &Material, params: &ComplexityParams, cone_size: Option<u32>) -> Self {
        let height = HeightField::from_height(&m.height);
        let cone = cone_size.map(|size| ConeMap::build(&height, ConeKind::Relaxed, size));
        let packed = PackedRelief::build(&height, cone.as_ref());
        let pyramid = DepthPyramid::build(&height);
        let albedo = Texture::from_rgb(&m.albedo, Wrap::Repeat);
        let normal = Texture::from_rgb(&m.normal, Wrap::Repeat);
        let complexity = complexity_map(&m.height, params);
        Self {
            name: m.name.clone(),
            textures8: Textures8::new(&albedo, &normal),
            albedo,
            normal,
            complexity_codes: ComplexityCodes::new(&complexity),
            complexity,
            height,
            height_scale: m.height_scale,
            cone,
            packed,
            pyramid,
        }
    }

    /// The inputs a [`ReliefTechnique`](crate::trace::ReliefTechnique) reads.
    pub fn inputs(&self) -> ReliefInputs<'_> {
        ReliefInputs {
            height: &self.height,
            height_scale: self.height_scale,
            complexity: &self.complexity,
            complexity_codes: self.complexity_codes.as_ref(),
            cone: self.cone.as_ref(),
            packed: Some(&self.packed),
            pyramid: Some(&self.pyramid),
        }
    }
}
