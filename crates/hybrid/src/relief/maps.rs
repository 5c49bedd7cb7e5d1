//! The relief inputs of a scene's materials, made on first use and kept: the depth field of
//! every material with a depth map, and the maps a technique reads besides it (the
//! complexity map, the relaxed cone map, the packed map, the min-depth pyramid), each built
//! once per material the first time a tracer needs it.

use renderlab_core::Image;
use renderlab_relief::maps::complexity::{complexity_map, ComplexityCodes, ComplexityParams};
use renderlab_relief::maps::cone::{ConeKind, ConeMap};
use renderlab_relief::maps::packed::PackedRelief;
use renderlab_relief::maps::pyramid::DepthPyramid;
use renderlab_relief::render::material::CONE_MAP_SIZE;
use renderlab_relief::{HeightField, Map, ReliefInputs};
use renderlab_scene::HybridScene;
use std::sync::{Arc, OnceLock};

/// One material's relief maps.
struct MaterialMaps {
    depth: Arc<Image<f32>>,
    scale: f32,
    field: OnceLock<HeightField>,
    complexity: OnceLock<(Image<f32>, Option<ComplexityCodes>)>,
    cone: OnceLock<ConeMap>,
    packed: OnceLock<PackedRelief>,
    packed_cones: OnceLock<PackedRelief>,
    pyramid: OnceLock<DepthPyramid>,
}

/// The relief maps of every material of a scene that has a depth map, built lazily and
/// shared by every later frame (thread-safe).
pub struct ReliefMaps {
    materials: Vec<Option<MaterialMaps>>,
}

impl std::fmt::Debug for ReliefMaps {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let with = self.materials.iter().filter(|m| m.is_some()).count();
        f.debug_struct("ReliefMaps").field("materials_with_relief", &with).finish()
    }
}

impl ReliefMaps {
    /// The (not yet built) maps of `scene`'s materials; costs nothing until a frame asks.
    pub fn new(scene: &HybridScene) -> Self {
        let materials = scene
            .materials
            .iter()
            .map(|m| {
                m.depth_map.as_ref().map(|d| MaterialMaps {
                    depth: d.depth.clone(),
                    scale: d.scale,
                    field: OnceLock::new(),
                    complexity: OnceLock::new(),
                    cone: OnceLock::new(),
                    packed: OnceLock::new(),
                    packed_cones: OnceLock::new(),
                    pyramid: OnceLock::new(),
                })
            })
            .collect();
        Self { materials }
    }

    /// Whether material `material` has a relief.
    pub fn has_relief(&self, material: u32) -> bool {
        self.materials.get(material as usize).is_some_and(Option::is_some)
    }

    /// The inputs of material `material` with the maps in `needs` present (built now if they
    /// were not yet); `None` when the material has no relief.
    pub fn inputs(&self, material: u32, needs: &[Map]) -> Option<ReliefInputs<'_>> {
        let m = self.materials.get(material as usize)?.as_ref()?;
        let height = m.field.get_or_init(|| HeightField::from_depth(&m.depth));
        let (complexity, codes) = m.complexity.get_or_init(|| {
            let c = complexity_map(&m.depth.map(|d| 1.0 - d), &ComplexityParams::default());
            let codes = ComplexityCodes::new(&c);
            (c, codes)
        });
        let cone = needs
            .contains(&Map::Cone)
            .then(|| m.cone.get_or_init(|| ConeMap::build(height, ConeKind::Relaxed, CONE_MAP_SIZE)));
        let packed = needs.contains(&Map::Packed).then(|| match cone {
            Some(c) => m.packed_cones.get_or_init(|| PackedRelief::build(height, Some(c))),
            None => m.packed.get_or_init(|| PackedRelief::build(height, None)),
        });
        let pyramid =
            needs.contains(&Map::Pyramid).then(|| m.pyramid.get_or_init(|| DepthPyramid::build(height)));
        Some(ReliefInputs {
            height,
            height_scale: m.scale,
            complexity,
            complexity_codes: codes.as_ref(),
            cone,
            packed,
            pyramid,
        })
    }
}
