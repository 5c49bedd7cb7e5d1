//! glTF materials and textures into the scene's: metal–roughness factors and maps, the
//! texture transform, images decoded once per use (colour or data). `doubleSided` (false
//! unless the file says so) decides whether a material's back face emits.

use super::{uri_bytes, Loader, Problem};
use crate::load::textures::decode_image;
use crate::material::{PbrMaterial, Texture};
use glam::{Vec2, Vec3, Vec4};

impl Loader<'_> {
    /// The scene material for a glTF material (converted once).
    pub(super) fn material(&mut self, m: ::gltf::Material) -> Result<u32, Problem> {
        if let Some(&done) = self.materials.get(&m.index()) {
            return Ok(done);
        }
        let pbr = m.pbr_metallic_roughness();
        let base = Vec4::from(pbr.base_color_factor());
        let mut out = PbrMaterial {
            name: m
                .name()
                .map_or_else(|| format!("material {}", m.index().map_or(-1, |i| i as i64)), str::to_string),
            base_color: clamp01(base.truncate()),
            roughness: unit(pbr.roughness_factor()),
            metallic: unit(pbr.metallic_factor()),
            emissive: Vec3::from(m.emissive_factor()).max(Vec3::ZERO),
            transmission: m.transmission().map_or(0.0, |t| unit(t.transmission_factor())),
            ior: m.ior().map_or(1.5, |i| if i.is_finite() && i >= 1.0 { i } else { 1.5 }),
            double_sided: m.double_sided(),
            ..PbrMaterial::default()
        };
        if !out.emissive.is_finite() {
            out.emissive = Vec3::ZERO;
        }
        let label = out.name.clone();
        if base.w < 1.0 && m.alpha_mode() == ::gltf::material::AlphaMode::Blend {
            self.warnings
                .push(format!("{label}: alpha blending is drawn opaque (use KHR_materials_transmission)"));
        }
        if let Some(info) = pbr.base_color_texture() {
            self.uv_set(&label, info.tex_coord());
            out.base_color_texture = Some(self.texture(&info.texture(), true)?);
        }
        if let Some(info) = pbr.metallic_roughness_texture() {
            self.uv_set(&label, info.tex_coord());
            out.metallic_roughness_texture = Some(self.texture(&info.texture(), false)?);
        }
        if let Some(info) = m.normal_texture() {
            self.uv_set(&label, info.tex_coord());
            out.normal_texture = Some(self.texture(&info.texture(), false)?);
        }
        if let Some(info) = m.emissive_texture() {
            // The scene's material has a constant emission: fold the map in as its mean.
            let t = self.texture(&info.texture(), true)?;
            let img = &self.scene.textures[t as usize].image;
            let mean =
                img.pixels().iter().map(|p| p.truncate()).sum::<Vec3>() / img.pixels().len().max(1) as f32;
            out.emissive *= mean;
            self.warnings.push(format!("{label}: emissive texture folded into a constant (its mean)"));
        }
        if m.transmission().and_then(|t| t.transmission_texture()).is_some() {
            self.warnings.push(format!("{label}: transmission texture ignored (factor used)"));
        }
        self.scene.materials.push(out);
        let index = (self.scene.materials.len() - 1) as u32;
        self.materials.insert(m.index(), index);
        Ok(index)
    }

    /// The `KHR_texture_transform` of `m`'s textures, applied to the primitive's UVs (the
    /// scene's material has one UV map for all its textures): the base colour's, else the
    /// metallic-roughness or emissive map's, with a warning when they differ. `None` without
    /// one, or when its numbers are not finite (warned).
    pub(super) fn uv_transform(&mut self, m: &::gltf::Material, label: &str) -> Option<UvTransform> {
        let pbr = m.pbr_metallic_roughness();
        let found: Vec<UvTransform> =
            [pbr.base_color_texture(), pbr.metallic_roughness_texture(), m.emissive_texture()]
                .into_iter()
                .flatten()
                .filter_map(|info| info.texture_transform())
                .map(|t| {
                    if t.tex_coord().is_some_and(|c| c != 0) {
                        self.uv_set(label, t.tex_coord().unwrap_or(0));
                    }
                    UvTransform::new(t.offset(), t.rotation(), t.scale())
                })
                .collect();
        let first = *found.first()?;
        if found.iter().any(|t| *t != first) {
            self.warnings.push(format!(
                "{label}: its textures have different KHR_texture_transforms; the first (base colour's) is used for all"
            ));
        }
        if !first.is_finite() {
            self.warnings.push(format!("{label}: KHR_texture_transform with non-finite numbers ignored"));
            return None;
        }
        Some(first)
    }

    fn uv_set(&mut self, label: &str, set: u32) {
        if set != 0 {
            self.warnings.push(format!("{label}: texture uses UV set {set}; read with set 0"));
        }
    }

    /// The scene texture of a glTF texture, decoded from sRGB when `srgb` (colour data).
    fn texture(&mut self, texture: &::gltf::Texture, srgb: bool) -> Result<u32, Problem> {
        let source = texture.source();
        let key = (source.index(), srgb);
        if let Some(&done) = self.textures.get(&key) {
            return Ok(done);
        }
        let what = format!("image {}", source.index());
        // Read the image's JSON directly: `image::Image::source` panics on an image with a
        // buffer view but no MIME type, or with neither a view nor a URI.
        let json = self.document.as_json().images.get(source.index());
        let view = json.and_then(|j| j.buffer_view.as_ref()).map(|v| self.document.views().nth(v.value()));
        let uri = json.and_then(|j| j.uri.as_deref());
        let bytes = match (view, uri) {
            (Some(Some(view)), _) => {
                let data = self.buffers.get(view.buffer().index()).map(Vec::as_slice).unwrap_or(&[]);
                let end = view.offset().checked_add(view.length());
                end.and_then(|e| data.get(view.offset()..e))
                    .ok_or_else(|| {
                        Problem::Image(format!("{what}: its buffer view lies outside the buffer"))
                    })?
                    .to_vec()
            }
            (None, Some(uri)) => {
                uri_bytes(uri, self.base, self.limits).map_err(|e| Problem::Image(format!("{what}: {e}")))?
            }
            _ => return Err(Problem::Image(format!("{what}: neither a buffer view nor a URI"))),
        };
        let image =
            decode_image(&bytes, srgb, self.limits).map_err(|e| Problem::Image(format!("{what}: {e}")))?;
        self.scene.textures.push(Texture::new(image));
        let index = (self.scene.textures.len() - 1) as u32;
        self.textures.insert(key, index);
        Ok(index)
    }
}

fn unit(x: f32) -> f32 {
    if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

fn clamp01(v: Vec3) -> Vec3 {
    Vec3::new(unit(v.x), unit(v.y), unit(v.z))
}

/// A `KHR_texture_transform` as one affine map of the UVs: `uv' = m · uv + offset`, with
/// the extension's order (scale, then rotation by `rotation` radians, then offset) and its
/// rotation's sense: a rotation of π/2 with scale ½ and offset (0, 1) takes the unit square to
/// the image's lower-left quadrant, as the extension's example says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct UvTransform {
    m: glam::Mat2,
    offset: Vec2,
}

impl UvTransform {
    fn new(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> Self {
        let (sin, cos) = rotation.sin_cos();
        let [sx, sy] = scale;
        let m = glam::Mat2::from_cols(Vec2::new(cos * sx, -sin * sx), Vec2::new(sin * sy, cos * sy));
        Self { m, offset: Vec2::from(offset) }
    }

    fn is_finite(&self) -> bool {
        self.m.is_finite() && self.offset.is_finite()
    }

    pub(super) fn apply(&self, uv: Vec2) -> Vec2 {
        self.m * uv + self.offset
    }
}
