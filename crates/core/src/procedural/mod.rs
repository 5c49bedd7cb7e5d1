//! Built-in procedural materials named after the thesis's textures. Deterministic: the same
//! name and size always give bit-identical maps.

use crate::error::{CoreError, Result};
use crate::image::{check_dimensions, Image};
use crate::material::Material;
use glam::Vec3;

/// Names of the built-in materials, in the order the thesis's scene uses them.
pub const MATERIAL_NAMES: [&str; 4] = ["bricks", "sand_rocks", "bark_willow", "brick_pavement"];

/// Default texture size of the built-in materials.
pub const DEFAULT_SIZE: u32 = 1024;

/// Builds the built-in material `name` at `size × size` texels.
pub fn material(name: &str, size: u32) -> Result<Material> {
    check_dimensions("--texture-size", size as u64, size as u64)?;
    if size < 16 {
        return Err(CoreError::param(
            "--texture-size",
            size,
            "must be at least 16",
        ));
    }
    let (albedo, height, scale) = match name {
        "bricks" | "sand_rocks" | "bark_willow" | "brick_pavement" => placeholder(size),
        _ => {
            return Err(CoreError::UnknownName {
                kind: "material",
                name: name.to_string(),
                known: MATERIAL_NAMES.join(", "),
            })
        }
    };
    Material::from_maps(name, albedo, height, None, scale)
}

fn placeholder(size: u32) -> (Image<Vec3>, Image<f32>, f32) {
    let cell = (size / 8).max(1);
    let height = Image::from_fn(size, size, |x, y| {
        let (cx, cy) = (x % cell, y % cell);
        if cx < cell / 10 || cy < cell / 10 {
            0.2
        } else {
            1.0
        }
    });
    let albedo = height.map(|h| Vec3::new(0.5, 0.25, 0.2) * (0.5 + 0.5 * h));
    (albedo, height, 0.05)
}
