//! What both loaders need for textures: image decoding within the limits, and vertex
//! colours drawn through a baked texture.

use super::common::LoadLimits;
use crate::material::Texture;
use crate::scene::HybridScene;
use glam::{Vec3, Vec4};
use renderlab_core::color::srgb8_to_linear_table;
use renderlab_core::Image;

/// Draws a primitive's vertex colours (COLOR_0, or OBJ's `v x y z r g b`): bakes them into a
/// texture of the mesh's own (see [`super::geometry::bake_vertex_colors`]) and returns a copy
/// of `material` that uses it as its base-colour texture, the material's base colour
/// multiplying it as glTF asks. `Err` holds the warning when they cannot be drawn: the
/// material already has a texture read through the UVs, or the texture would be too large.
pub(crate) fn vertex_colors(
    scene: &mut HybridScene,
    mesh: &mut renderlab_core::Mesh,
    colors: &[Vec4],
    material: u32,
    limits: &LoadLimits,
    label: &str,
) -> Result<u32, String> {
    let m = &scene.materials[material as usize];
    if m.base_color_texture.is_some() || m.normal_texture.is_some() || m.metallic_roughness_texture.is_some()
    {
        return Err(format!(
            "{label}: vertex colours ignored (its material has textures read through the UVs)"
        ));
    }
    if colors.iter().all(|c| c.truncate() == Vec3::ONE) {
        return Ok(material);
    }
    if (mesh.triangles.len() as u64).saturating_mul(4) > limits.max_texture_texels {
        return Err(format!("{label}: vertex colours ignored (too many triangles to bake into a texture)"));
    }
    let image = super::geometry::bake_vertex_colors(mesh, colors)
        .map_err(|e| format!("{label}: vertex colours ignored ({e})"))?;
    let mut m = m.clone();
    m.name = format!("{} × vertex colours of {label}", m.name);
    scene.textures.push(Texture::new(image));
    m.base_color_texture = Some((scene.textures.len() - 1) as u32);
    scene.materials.push(m);
    Ok((scene.materials.len() - 1) as u32)
}

/// Decodes a PNG or JPEG into linear RGBA, from sRGB when `srgb`.
pub(crate) fn decode_image(bytes: &[u8], srgb: bool, limits: &LoadLimits) -> Result<Image<Vec4>, String> {
    let reader = ::image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    let mut decode_limits = ::image::Limits::default();
    decode_limits.max_alloc = Some(limits.max_texture_texels.saturating_mul(16));
    let mut reader = reader;
    reader.limits(decode_limits.clone());
    let (w, h) = reader.into_dimensions().map_err(|e| e.to_string())?;
    if u64::from(w) * u64::from(h) > limits.max_texture_texels {
        return Err(format!("{w}×{h} is more than the limit of {} texels", limits.max_texture_texels));
    }
    let mut reader = ::image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    reader.limits(decode_limits);
    let rgba = reader.decode().map_err(|e| e.to_string())?.to_rgba8();
    let table = srgb8_to_linear_table();
    let texels = rgba
        .pixels()
        .map(|p| {
            let c = |v: u8| if srgb { table[v as usize] } else { v as f32 / 255.0 };
            Vec4::new(c(p[0]), c(p[1]), c(p[2]), p[3] as f32 / 255.0)
        })
        .collect();
    Image::from_vec(w, h, texels).map_err(|e| e.to_string())
}
