//! Physically based materials (metal–roughness, as glTF 2.0 defines them) and their
//! textures.

use crate::error::{Result, SceneError};
use glam::{Vec2, Vec3, Vec4};
use renderlab_core::Image;
use std::sync::Arc;

/// A texture in linear light (colour textures are decoded from sRGB when loaded), sampled
/// bilinearly with wrapping. The hybrid lab's error is measured between renderers that all
/// sample textures through this one function, so its filter needs no mip levels to be fair.
#[derive(Clone, Debug)]
pub struct Texture {
    /// Texels, linear RGBA.
    pub image: Image<Vec4>,
}

impl Texture {
    /// Wraps an image of linear RGBA texels.
    pub fn new(image: Image<Vec4>) -> Self {
        Self { image }
    }

    /// Bilinear lookup at `uv` (texel centres at half-integers, repeat wrapping).
    pub fn sample(&self, uv: Vec2) -> Vec4 {
        let (w, h) = self.image.size();
        let x = uv.x * w as f32 - 0.5;
        let y = uv.y * h as f32 - 0.5;
        if !(x.is_finite() && y.is_finite()) {
            return self.image.get(0, 0);
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (xi, yi) = (x0 as i64, y0 as i64);
        let a = self.image.get_wrapped(xi, yi);
        let b = self.image.get_wrapped(xi + 1, yi);
        let c = self.image.get_wrapped(xi, yi + 1);
        let d = self.image.get_wrapped(xi + 1, yi + 1);
        a.lerp(b, fx).lerp(c.lerp(d, fx), fy)
    }
}

/// A relief's depth map: how far below the surface each texel's relief lies, for the hybrid
/// renderer's relief pass (the relief lab's convention: depth `1 − height`, 0 at the top
/// surface, 1 at the deepest point, repeat-wrapped like every texture). A ray entering the
/// top surface at `uv` along the tangent-space direction `V` (toward the eye) reaches depth
/// `d` at `uv − V.xy / V.z · scale · d`.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthMap {
    /// Depth per texel in [0, 1]; shared, so that cloning a material or a scene does not
    /// copy it.
    pub depth: Arc<Image<f32>>,
    /// Depth scale in UV per unit depth (the relief lab's `height_scale`): the full relief
    /// is `scale` UV units deep, `scale × world units per UV` in the world.
    pub scale: f32,
}

/// A metal–roughness material. Texture indices refer to [`HybridScene::textures`]; a
/// texture's value multiplies the constant factor, as in glTF.
///
/// [`HybridScene::textures`]: crate::HybridScene::textures
#[derive(Clone, Debug, PartialEq)]
pub struct PbrMaterial {
    /// Name (from the file, or the procedural scene's own).
    pub name: String,
    /// Base colour (albedo for dielectrics, F0 for metals), linear RGB.
    pub base_color: Vec3,
    /// Base-colour texture (linear after sRGB decoding).
    pub base_color_texture: Option<u32>,
    /// Perceptual roughness in [0, 1]; the GGX α is its square.
    pub roughness: f32,
    /// Metalness in [0, 1] (the thesis treats it as binary; textures may blend).
    pub metallic: f32,
    /// glTF's metallic–roughness texture: roughness in G, metalness in B.
    pub metallic_roughness_texture: Option<u32>,
    /// Tangent-space normal map (RGB in [0, 1] encoding [-1, 1]).
    pub normal_texture: Option<u32>,
    /// Emitted radiance, linear RGB.
    pub emissive: Vec3,
    /// Fraction of light transmitted through the surface (glass: 1), as
    /// `KHR_materials_transmission` defines it.
    pub transmission: f32,
    /// Index of refraction (glass 1.5, water 1.33), as `KHR_materials_ior`.
    pub ior: f32,
    /// Whether the surface emits (and, as glTF's `doubleSided` means, is meant to be seen)
    /// from its back face too; a hit on the back of a single-sided material resolves to no
    /// emission ([`HybridScene::shading_point`]). `true` by default, so that a material
    /// built in code emits from both faces as it always has; glTF files set it from
    /// `doubleSided` (whose own default is `false`).
    ///
    /// [`HybridScene::shading_point`]: crate::HybridScene::shading_point
    pub double_sided: bool,
    /// The relief under the surface, for renderers that trace it (the hybrid renderer's
    /// relief pass, off by default); every other renderer shades the flat surface with the
    /// albedo and normal maps. Built-in relief-dressed materials carry their relief
    /// material's depth map; loaded files leave it empty.
    pub depth_map: Option<DepthMap>,
}

impl Default for PbrMaterial {
    /// A grey (0.8), half-rough dielectric of ior 1.5 that neither emits nor transmits,
    /// double-sided.
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: Vec3::splat(0.8),
            base_color_texture: None,
            roughness: 0.5,
            metallic: 0.0,
            metallic_roughness_texture: None,
            normal_texture: None,
            emissive: Vec3::ZERO,
            transmission: 0.0,
            ior: 1.5,
            double_sided: true,
            depth_map: None,
        }
    }
}

impl PbrMaterial {
    /// A diffuse-looking dielectric of the given colour and roughness.
    pub fn dielectric(name: &str, base_color: Vec3, roughness: f32) -> Self {
        Self { name: name.into(), base_color, roughness, ..Self::default() }
    }

    /// A metal of the given F0 colour and roughness.
    pub fn metal(name: &str, base_color: Vec3, roughness: f32) -> Self {
        Self { name: name.into(), base_color, roughness, metallic: 1.0, ..Self::default() }
    }

    /// A clear transmissive dielectric (glass, water).
    pub fn glass(name: &str, ior: f32, roughness: f32) -> Self {
        Self {
            name: name.into(),
            base_color: Vec3::ONE,
            roughness,
            transmission: 1.0,
            ior,
            ..Self::default()
        }
    }

    /// Whether the material emits light: some component of [`Self::emissive`] is above zero.
    /// An instance of such a material lights the scene by itself, so a file lit only by its
    /// emitters gets no default light when loaded.
    pub fn is_emissive(&self) -> bool {
        self.emissive.cmpgt(Vec3::ZERO).any()
    }

    /// Whether the material lets light through (drawn by the translucent pass).
    pub fn is_translucent(&self) -> bool {
        self.transmission > 0.0
    }

    /// Checks that every parameter is finite and within its meaning.
    pub fn validate(&self, textures: usize) -> Result<()> {
        let finite = self.base_color.is_finite()
            && self.emissive.is_finite()
            && self.roughness.is_finite()
            && self.metallic.is_finite()
            && self.transmission.is_finite()
            && self.ior.is_finite();
        if !finite {
            return Err(SceneError::Invalid(format!("material {:?} has a non-finite parameter", self.name)));
        }
        if !(0.0..=1.0).contains(&self.roughness)
            || !(0.0..=1.0).contains(&self.metallic)
            || !(0.0..=1.0).contains(&self.transmission)
        {
            return Err(SceneError::Invalid(format!(
                "material {:?}: roughness, metallic and transmission must lie in [0, 1]",
                self.name
            )));
        }
        if self.ior < 1.0 {
            return Err(SceneError::Invalid(format!(
                "material {:?}: ior {} is below 1",
                self.name, self.ior
            )));
        }
        if let Some(d) = &self.depth_map {
            let (w, h) = d.depth.size();
            let in_range = d.depth.pixels().iter().all(|v| (0.0..=1.0).contains(v));
            if !(d.scale.is_finite() && d.scale > 0.0) || w == 0 || h == 0 || !in_range {
                return Err(SceneError::Invalid(format!(
                    "material {:?}: the depth map must be non-empty with depths in [0, 1] and a finite, positive scale",
                    self.name
                )));
            }
        }
        for t in [self.base_color_texture, self.metallic_roughness_texture, self.normal_texture]
            .into_iter()
            .flatten()
        {
            if t as usize >= textures {
                return Err(SceneError::MissingReference { what: "texture", index: t, count: textures });
            }
        }
        Ok(())
    }
}
