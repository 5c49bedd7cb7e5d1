//! The relief lab's procedural materials (`bricks`, `sand_rocks`, `bark_willow`,
//! `brick_pavement`, …) as scene textures: the albedo in linear RGB, the tangent-space
//! normal map encoded as `n · 0.5 + 0.5` and the depth map (`1 − height`, with the
//! material's depth scale), all at [`RELIEF_TEXTURE_SIZE`] texels, small enough that
//! building a scene stays fast.

use crate::material::{DepthMap, Texture};
use glam::Vec3;
use std::sync::Arc;

/// Texel size of the relief materials' maps in the built-in scenes.
pub const RELIEF_TEXTURE_SIZE: u32 = 256;

/// One relief material's maps.
#[derive(Clone, Debug)]
pub(crate) struct ReliefMaps {
    /// Albedo, linear RGB.
    pub albedo: Texture,
    /// Tangent-space normals, encoded.
    pub normal: Texture,
    /// Depth below the top surface and its scale.
    pub depth: DepthMap,
}

/// The maps of relief materials, made once per process (in parallel for those not made
/// yet) and shared by every later build: making them is most of a build's cost.
pub(crate) fn relief_maps(names: &[&str]) -> Vec<Option<ReliefMaps>> {
    use rayon::prelude::*;
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static CACHE: OnceLock<Mutex<HashMap<String, Option<ReliefMaps>>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let missing: Vec<&str> = {
        let held = cache.lock().unwrap_or_else(|e| e.into_inner());
        names.iter().copied().filter(|n| !held.contains_key(*n)).collect()
    };
    let made: Vec<(String, Option<ReliefMaps>)> = missing
        .par_iter()
        .map(|&name| {
            let maps =
                renderlab_texture::materials::material(name, RELIEF_TEXTURE_SIZE).ok().map(|m| ReliefMaps {
                    albedo: Texture::new(m.albedo.map(|c| c.extend(1.0))),
                    normal: Texture::new(m.normal.map(|n| (n * 0.5 + Vec3::splat(0.5)).extend(1.0))),
                    depth: DepthMap { depth: Arc::new(m.height.map(|h| 1.0 - h)), scale: m.height_scale },
                });
            (name.to_string(), maps)
        })
        .collect();
    let mut held = cache.lock().unwrap_or_else(|e| e.into_inner());
    held.extend(made);
    names.iter().map(|n| held.get(*n).cloned().flatten()).collect()
}
