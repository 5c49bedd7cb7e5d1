//! The relief lab's procedural materials (`bricks`, `sand_rocks`, `bark_willow`,
//! `brick_pavement`, …) as scene textures: the albedo in linear RGB and the tangent-space
//! normal map encoded as `n · 0.5 + 0.5`, both at [`RELIEF_TEXTURE_SIZE`] texels, small
//! enough that building a scene stays fast.

use crate::material::Texture;
use glam::Vec3;

/// Texel size of the relief materials' maps in the built-in scenes.
pub const RELIEF_TEXTURE_SIZE: u32 = 256;

/// Albedo and normal-map textures of relief materials, made once per process (in
/// parallel for those not made yet) and shared by every later build: making them is most
/// of a build's cost.
pub(crate) fn relief_maps(names: &[&str]) -> Vec<Option<(Texture, Texture)>> {
    use rayon::prelude::*;
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    type Maps = Option<(Texture, Texture)>;
    static CACHE: OnceLock<Mutex<HashMap<String, Maps>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let missing: Vec<&str> = {
        let held = cache.lock().unwrap_or_else(|e| e.into_inner());
        names.iter().copied().filter(|n| !held.contains_key(*n)).collect()
    };
    let made: Vec<(String, Maps)> = missing
        .par_iter()
        .map(|&name| {
            let maps = renderlab_texture::materials::material(name, RELIEF_TEXTURE_SIZE).ok().map(|m| {
                let albedo = Texture::new(m.albedo.map(|c| c.extend(1.0)));
                let normal = Texture::new(m.normal.map(|n| (n * 0.5 + Vec3::splat(0.5)).extend(1.0)));
                (albedo, normal)
            });
            (name.to_string(), maps)
        })
        .collect();
    let mut held = cache.lock().unwrap_or_else(|e| e.into_inner());
    held.extend(made);
    names.iter().map(|n| held.get(*n).cloned().flatten()).collect()
}
