//! Surface materials: albedo, height and normal maps plus the relief depth scale.

use crate::error::{check_range, Result};
use crate::image::Image;
use glam::Vec3;

/// A relief material. Each map has its own resolution and is addressed in UV. `height` is 1 at the top of the relief and 0
/// at its deepest point; techniques that follow the thesis work with the inverted *depth*
/// `1 − height`.
#[derive(Clone, Debug)]
pub struct Material {
    /// Name used on the command line and in reports.
    pub name: String,
    /// Base colour in linear light.
    pub albedo: Image<Vec3>,
    /// Height in [0, 1], 1 = top surface.
    pub height: Image<f32>,
    /// Unit tangent-space normals (x along +u, y along +v, z out of the surface).
    pub normal: Image<Vec3>,
    /// Depth scale: a ray that descends the full relief depth (1) moves by
    /// `height_scale · V.xy / V.z` in UV (the thesis's `HeightScale`).
    pub height_scale: f32,
}

impl Material {
    /// Builds a material from user maps, deriving the normal map from the height map when none
    /// is given. The maps may have different resolutions (a 512² albedo over a 1024² height map
    /// is common in asset sets): each is sampled in UV through its own mip pyramid, so only
    /// the height scale is checked here.
    pub fn from_maps(
        name: impl Into<String>,
        albedo: Image<Vec3>,
        height: Image<f32>,
        normal: Option<Image<Vec3>>,
        height_scale: f32,
    ) -> Result<Self> {
        let name = name.into();
        check_range("--height-scale", height_scale, 0.0, 1.0)?;
        let normal = normal.unwrap_or_else(|| normals_from_height(&height, height_scale));
        Ok(Self { name, albedo, height, normal, height_scale })
    }

    /// `(width, height)` of the albedo map (the other maps may differ; see
    /// [`Material::from_maps`]).
    pub fn size(&self) -> (u32, u32) {
        self.albedo.size()
    }
}

/// Tangent-space normals consistent with the relief geometry: the surface is
/// `z = height_scale · h(u, v)` in UV units, so the slope along u is
/// `height_scale · width · ∂h/∂x` per texel. Central differences with wrap-around.
pub fn normals_from_height(height: &Image<f32>, height_scale: f32) -> Image<Vec3> {
    let (w, h) = height.size();
    let sx = height_scale * w as f32 * 0.5;
    let sy = height_scale * h as f32 * 0.5;
    Image::from_fn_par(w, h, |x, y| {
        let (x, y) = (x as i64, y as i64);
        let dx = height.get_wrapped(x + 1, y) - height.get_wrapped(x - 1, y);
        let dy = height.get_wrapped(x, y + 1) - height.get_wrapped(x, y - 1);
        Vec3::new(-dx * sx, -dy * sy, 1.0).normalize()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_height_gives_up_normals() {
        let h = Image::new(7, 5, 0.5f32);
        let n = normals_from_height(&h, 0.1);
        assert!(n.pixels().iter().all(|v| (*v - Vec3::Z).length() < 1e-6));
    }

    #[test]
    fn ramp_normal_tilts_against_the_slope() {
        // Height rising along +x: the normal leans toward −x, by the exact slope.
        let h = Image::from_fn(8, 8, |x, _| x as f32 / 8.0);
        let n = normals_from_height(&h, 0.05);
        let v = n.get(3, 3);
        let slope = 0.05 * 8.0 * (1.0 / 8.0); // height_scale · width · dh/dx
        let expect = Vec3::new(-slope, 0.0, 1.0).normalize();
        assert!((v - expect).length() < 1e-5, "{v} vs {expect}");
    }

    #[test]
    fn maps_of_different_sizes_are_accepted() {
        let a = Image::new(4, 4, Vec3::ONE);
        let h = Image::new(8, 16, 0.5f32);
        let m = Material::from_maps("m", a, h, None, 0.05).unwrap();
        assert_eq!(m.size(), (4, 4));
        assert_eq!(m.normal.size(), (8, 16), "derived normals follow the height map");
        assert!(Material::from_maps("m", m.albedo.clone(), m.height.clone(), None, f32::NAN).is_err());
    }
}
