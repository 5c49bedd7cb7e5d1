//! The raster shadow stage: shadow maps with percentage-closer filtering.
//!
//! Per light, depth maps drawn with the visibility rasterizer (two-sided, so that open
//! meshes cast shadows from either side) and resolved to the exact distance along the map's
//! axis at each texel centre:
//! - directional: one orthographic map fitted to the scene's bounds (square texels);
//! - spot: one perspective map covering the cone (a cube map when the cone is wider than
//!   [`MAX_SPOT_HALF_ANGLE_DEG`]);
//! - point: a cube map, six 90° faces;
//! - area: the thesis's trick, a cube map from each of the rectangle's four corners; the
//!   visibility is the fraction of corners that see the point (each filtered by PCF), which
//!   gives a penumbra as wide as the light.
//!
//! A lookup compares the receiver's distance along the map's axis, minus a slope-scaled
//! bias `s · (bias_constant + bias_slope · max(r, 1) · tan θ)` (s: a texel's world size at
//! the receiver, r: the PCF radius, θ: between the geometric normal and the light), with
//! the `(2r + 1)²` texels around it and returns the lit fraction. A point below its surface
//! (a relief's displaced hit) is looked up where its ray toward the light leaves the
//! surface, the first point of that ray the maps' flat casters can block. Points outside every map
//! are lit. Translucent instances cast no shadow-map shadow: glass lets the light through,
//! and the raster pipeline has no caustics to put in its place.

use crate::deferred::geometry::PreparedScene;
use crate::deferred::lighting::{ShadowQuery, Visibility};
use crate::deferred::settings::ShadowSettings;
use glam::{DMat4, Mat4, Vec3, Vec4Swizzles};
use rayon::prelude::*;
use renderlab_raster::visibility::{Source, VisFrame, NO_TRIANGLE};
use renderlab_scene::shading::surface_exit;
use renderlab_scene::{Light, LightKind};
use std::sync::{Arc, Mutex};

/// Widest spot cone (half-angle, degrees) drawn into one perspective map.
pub const MAX_SPOT_HALF_ANGLE_DEG: f32 = 60.0;

/// The cube faces' axes and up vectors, in the order +X, −X, +Y, −Y, +Z, −Z.
const CUBE_FACES: [(Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Y),
    (Vec3::NEG_X, Vec3::NEG_Y),
    (Vec3::Y, Vec3::Z),
    (Vec3::NEG_Y, Vec3::NEG_Z),
    (Vec3::Z, Vec3::NEG_Y),
    (Vec3::NEG_Z, Vec3::NEG_Y),
];

/// One depth map: the distance along `forward` from `eye` of the nearest caster per texel.
#[derive(Clone, Debug)]
pub struct DepthMap {
    view_projection: Mat4,
    eye: Vec3,
    forward: Vec3,
    resolution: u32,
    orthographic: bool,
    /// World size of a texel: at unit distance (perspective) or everywhere (orthographic).
    texel: f32,
    depth: Vec<f32>,
}

/// The maps of one light: one map, or cube maps (six faces each) whose lookups average.
#[derive(Clone, Debug)]
pub enum LightShadow {
    /// A single (orthographic or perspective) map.
    Single(DepthMap),
    /// Cube maps, one per point of the light (one for a point light, four corners for an
    /// area light); the visibility is their mean.
    Cubes(Vec<[DepthMap; 6]>),
}

/// Shadow maps of every light of a scene, in light order; a [`Visibility`] for the lighting
/// pass.
#[derive(Clone, Debug)]
pub struct ShadowMaps {
    /// Per light.
    pub lights: Vec<LightShadow>,
    settings: ShadowSettings,
}

/// Scene bounds as centre and radius (a unit sphere at the origin for an empty scene).
fn sphere(prepared: &PreparedScene) -> (Vec3, f32) {
    let (lo, hi) = prepared.bounds;
    if lo.cmple(hi).all() {
        ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1e-3))
    } else {
        (Vec3::ZERO, 1.0)
    }
}

/// Where one shadow map looks from and how it projects: what the CPU's depth map is drawn
/// with and the GPU's map is drawn and looked up with, so that both place every map alike.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapPlacement {
    /// World to clip (the map's texel grid is clip space's [−1, 1]²).
    pub view_projection: DMat4,
    /// The map's eye (for an orthographic map, a point behind the scene along `forward`).
    pub eye: Vec3,
    /// The unit viewing direction.
    pub forward: Vec3,
    /// Whether the projection is orthographic.
    pub orthographic: bool,
    /// The world size of a texel at unit distance (perspective) or everywhere (orthographic).
    pub texel: f32,
    /// Texels per side.
    pub resolution: u32,
}

impl MapPlacement {
    /// An orthographic map looking along `direction`, fitted to the sphere (`centre`, `radius`).
    pub fn orthographic(direction: Vec3, centre: Vec3, radius: f32, resolution: u32) -> Self {
        let forward = direction.normalize_or(Vec3::NEG_Y);
        let up = forward.any_orthonormal_vector();
        let eye = centre - forward * (radius * 1.01 + 1e-3);
        let view = DMat4::look_to_rh(eye.as_dvec3(), forward.as_dvec3(), up.as_dvec3());
        let r = radius as f64 * 1.01 + 1e-3;
        let proj = DMat4::orthographic_rh(-r, r, -r, r, 0.0, 2.0 * r);
        let texel = (2.0 * r / resolution as f64) as f32;
        Self { view_projection: proj * view, eye, forward, orthographic: true, texel, resolution }
    }

    /// A perspective map with vertical and horizontal field of view `fov` (radians).
    pub fn perspective(eye: Vec3, forward: Vec3, up: Vec3, fov: f32, near: f32, far: f32, resolution: u32) -> Self {
        let view = DMat4::look_to_rh(eye.as_dvec3(), forward.as_dvec3(), up.as_dvec3());
        let proj = DMat4::perspective_rh(fov as f64, 1.0, near as f64, far as f64);
        let texel = 2.0 * (fov * 0.5).tan() / resolution as f32;
        Self { view_projection: proj * view, eye, forward, orthographic: false, texel, resolution }
    }
}

/// One light's maps: one map (a directional light; a spot light narrower than
/// [`MAX_SPOT_HALF_ANGLE_DEG`]), or cube maps (a point light or wider spot: one cube; an area
/// light: one per corner), faces in the lookup's order.
#[derive(Clone, Debug, PartialEq)]
pub enum LightPlacement {
    /// One map.
    Single(MapPlacement),
    /// Cube maps, six faces each.
    Cubes(Vec<[MapPlacement; 6]>),
}

/// Where every light of `prepared`'s scene puts its maps, in light order, with `settings`'
/// resolutions (directional maps: `directional_resolution`; spot and point: `cube_resolution`;
/// area corners: `area_resolution`).
pub fn placements(prepared: &PreparedScene, settings: &ShadowSettings) -> Vec<LightPlacement> {
    let (centre, radius) = sphere(prepared);
    let cube = |eye: Vec3, res: u32| {
        let far = (eye - centre).length() + radius * 1.01 + 1e-3;
        let near = (far * 1e-5).max(1e-4);
        CUBE_FACES.map(|(f, up)| MapPlacement::perspective(eye, f, up, 90f32.to_radians(), near, far, res))
    };
    prepared
        .scene
        .lights
        .iter()
        .map(|light| match light.kind {
            LightKind::Directional => LightPlacement::Single(MapPlacement::orthographic(
                light.direction,
                centre,
                radius,
                settings.directional_resolution,
            )),
            LightKind::Spot { outer_cone, .. } if outer_cone.to_degrees() <= MAX_SPOT_HALF_ANGLE_DEG => {
                let far = (light.position - centre).length() + radius * 1.01 + 1e-3;
                let near = (far * 1e-5).max(1e-4);
                let up = light.direction.any_orthonormal_vector();
                let fov = (2.0 * outer_cone * 1.05 + 2f32.to_radians()).min(179f32.to_radians());
                LightPlacement::Single(MapPlacement::perspective(
                    light.position,
                    light.direction,
                    up,
                    fov,
                    near,
                    far,
                    settings.cube_resolution,
                ))
            }
            LightKind::Point | LightKind::Spot { .. } => {
                LightPlacement::Cubes(vec![cube(light.position, settings.cube_resolution)])
            }
            LightKind::Area { half_u, half_v } => LightPlacement::Cubes(
                [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
                    .into_iter()
                    .map(|(a, b)| cube(light.position + half_u * a + half_v * b, settings.area_resolution))
                    .collect(),
            ),
        })
        .collect()
}

impl ShadowMaps {
    /// Draws the maps of every light of `prepared`'s scene.
    pub fn build(prepared: &PreparedScene, settings: &ShadowSettings) -> Self {
        let sources: Vec<Source> =
            prepared.sources(false).into_iter().map(|s| Source { two_sided: true, ..s }).collect();
        let draw = |p: &MapPlacement| DepthMap::draw(prepared, &sources, p);
        let lights = placements(prepared, settings)
            .iter()
            .map(|placed| match placed {
                LightPlacement::Single(p) => LightShadow::Single(draw(p)),
                LightPlacement::Cubes(cubes) => LightShadow::Cubes(cubes.iter().map(|faces| faces.each_ref().map(draw)).collect()),
            })
            .collect();
        Self { lights, settings: settings.clone() }
    }

    /// The lit fraction of `point` (with geometric normal `normal`) for light `light`.
    pub fn lookup(&self, light: &Light, index: usize, point: Vec3, normal: Vec3) -> f32 {
        self.lookup_below(light, index, point, normal, 0.0)
    }

    /// [`Self::lookup`] for a point `depth` world units below its surface (a relief's
    /// displaced hit, [`ShadingPoint::relief_depth`](renderlab_scene::ShadingPoint)): each
    /// map is read where the ray toward its eye leaves the surface ([`surface_exit`]), so
    /// that the flat surface above the point does not shadow it and the usual bias applies
    /// there. Depth 0 is [`Self::lookup`].
    pub fn lookup_below(&self, light: &Light, index: usize, point: Vec3, normal: Vec3, depth: f32) -> f32 {
        let Some(maps) = self.lights.get(index) else {
            return 1.0;
        };
        let to_light = |eye: Vec3| match light.kind {
            LightKind::Directional => -light.direction,
            _ => (eye - point).normalize_or_zero(),
        };
        let read = |m: &DepthMap, l: Vec3| m.lookup(surface_exit(point, normal, depth, l), normal, l, &self.settings);
        match maps {
            LightShadow::Single(m) => read(m, to_light(m.eye)),
            LightShadow::Cubes(cubes) => {
                let sum: f32 = cubes
                    .iter()
                    .map(|faces| {
                        let eye = faces[0].eye;
                        let l = to_light(eye);
                        let from = surface_exit(point, normal, depth, l);
                        read(&faces[face_of(from - eye)], l)
                    })
                    .sum();
                sum / cubes.len() as f32
            }
        }
    }
}

/// The cube face whose axis is the major axis of `d`.
fn face_of(d: Vec3) -> usize {
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        if d.x >= 0.0 {
            0
        } else {
            1
        }
    } else if a.y >= a.z {
        if d.y >= 0.0 {
            2
        } else {
            3
        }
    } else if d.z >= 0.0 {
        4
    } else {
        5
    }
}

impl Visibility for ShadowMaps {
    fn visibility(&self, q: &ShadowQuery) -> f32 {
        let p = q.point;
        self.lookup_below(q.light, q.light_index, p.position, p.geometric_normal, p.relief_depth)
    }

    /// One lookup per light serves all of an area light's samples (the corner maps already
    /// average over the light).
    fn varies_per_sample(&self) -> bool {
        false
    }
}

impl DepthMap {
    /// Rasterizes the casters seen from `placement` and resolves each texel's exact distance
    /// along its `forward`.
    fn draw(prepared: &PreparedScene, sources: &[Source], placement: &MapPlacement) -> Self {
        let MapPlacement { view_projection, eye, forward, orthographic, texel, resolution } = *placement;
        let frame = VisFrame::new(sources, view_projection, resolution, resolution);
        let (_, ids) = frame.nearest(None);
        let depth = ids
            .par_iter()
            .enumerate()
            .map(|(i, &id)| {
                if id == NO_TRIANGLE {
                    return f32::INFINITY;
                }
                let t = frame.tris[id as usize];
                let b = t.barycentrics(i as u32 % resolution, i as u32 / resolution);
                let mesh = &prepared.world[t.instance as usize];
                let [a, bb, c] =
                    mesh.triangles[t.triangle as usize].map(|k| mesh.vertices[k as usize].position);
                let p = a * (1.0 - b.x - b.y) + bb * b.x + c * b.y;
                (p - eye).dot(forward)
            })
            .collect();
        Self {
            view_projection: view_projection.as_mat4(),
            eye,
            forward,
            resolution,
            orthographic,
            texel,
            depth,
        }
    }

    /// The PCF-filtered lit fraction of `point`; 1 outside the map.
    fn lookup(&self, point: Vec3, normal: Vec3, to_light: Vec3, s: &ShadowSettings) -> f32 {
        let h = self.view_projection * point.extend(1.0);
        let d = (point - self.eye).dot(self.forward);
        if h.w <= 0.0 || d <= 0.0 {
            return 1.0;
        }
        let ndc = h.xy() / h.w;
        if !(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0) {
            return 1.0;
        }
        let res = self.resolution as i64;
        let tx = (((ndc.x + 1.0) * 0.5 * res as f32).floor() as i64).clamp(0, res - 1);
        let ty = (((1.0 - ndc.y) * 0.5 * res as f32).floor() as i64).clamp(0, res - 1);
        let size = if self.orthographic { self.texel } else { self.texel * d };
        let cos = normal.dot(to_light).abs().clamp(1e-4, 1.0);
        let tan = ((1.0 - cos * cos).sqrt() / cos).min(10.0);
        let r = s.pcf_radius as i64;
        let bias = size * (s.bias_constant + s.bias_slope * (r.max(1) as f32) * tan);
        let mut lit = 0u32;
        for y in ty - r..=ty + r {
            for x in tx - r..=tx + r {
                let k = (y.clamp(0, res - 1) * res + x.clamp(0, res - 1)) as usize;
                lit += (d - bias <= self.depth[k]) as u32;
            }
        }
        lit as f32 / ((2 * r + 1) * (2 * r + 1)) as f32
    }
}

/// The shadow maps of the last raster-shadowed frame, with the settings they were built for.
/// The lights and the scene are static, so the maps are built once and reused, as an engine
/// caches the shadow maps of static lights; a frame rebuilds them only when the shadow
/// settings have changed.
#[derive(Debug, Default)]
pub struct ShadowMapCache {
    maps: Mutex<Option<(ShadowSettings, Arc<ShadowMaps>)>>,
}

impl ShadowMapCache {
    /// The maps of `prepared` for `settings`, building them if needed (`true` when built
    /// now).
    pub fn get(&self, prepared: &PreparedScene, settings: &ShadowSettings) -> (Arc<ShadowMaps>, bool) {
        let mut cache = self.maps.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((s, maps)) = cache.as_ref() {
            if s == settings {
                return (maps.clone(), false);
            }
        }
        let maps = Arc::new(ShadowMaps::build(prepared, settings));
        *cache = Some((settings.clone(), maps.clone()));
        (maps, true)
    }
}

/// Shared maps as a [`Visibility`]: what a frame with raster shadows hands its later passes.
#[derive(Clone, Debug)]
pub struct SharedShadowMaps(pub Arc<ShadowMaps>);

impl Visibility for SharedShadowMaps {
    fn visibility(&self, q: &ShadowQuery) -> f32 {
        self.0.visibility(q)
    }

    fn varies_per_sample(&self) -> bool {
        self.0.varies_per_sample()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_faces_are_orthonormal_and_selected_by_major_axis() {
        for (k, (f, up)) in CUBE_FACES.iter().enumerate() {
            assert!(f.dot(*up).abs() < 1e-6);
            assert_eq!(face_of(*f * 2.0 + *up * 0.5), k);
        }
    }
}
