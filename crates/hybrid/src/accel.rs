//! The scene's acceleration structure as the stages use it: built once per scene (one
//! bottom level per mesh, one top-level instance per scene instance, so a hit's `instance`
//! and `primitive` are the scene's instance and the mesh's triangle), with the two queries
//! every stage needs — the nearest surface along a ray, resolved into a [`ShadingPoint`],
//! and whether a segment is blocked.
//!
//! Shadow and occlusion rays treat every surface as opaque, translucent ones included: light
//! that reaches a point through glass is a caustic, which neither the stages nor the
//! unidirectional path tracer (whose lights are not geometry) can sample, so both leave it
//! out alike and their images stay comparable.

use crate::error::Result;
use glam::Vec3;
use renderlab_scene::{HybridScene, ShadingPoint};
use renderlab_trace::{Blas, Hit, Instance, Ray, Tlas};

/// The BVH of a [`HybridScene`] and what its hits mean.
#[derive(Clone, Debug)]
pub struct Accel {
    tlas: Tlas,
    translucent: Vec<bool>,
}

/// A shadow ray stops this fraction short of the light sample so that it does not hit the
/// light's own geometry (an emissive panel placed at an area light).
pub const SHADOW_END: f32 = 1.0 - 1e-4;

impl Accel {
    /// Builds the two levels for `scene` (which must have passed `validate`).
    pub fn build(scene: &HybridScene) -> Result<Self> {
        let meshes = scene
            .meshes
            .iter()
            .map(|m| {
                let positions: Vec<Vec3> = m.vertices.iter().map(|v| v.position).collect();
                Blas::build(&positions, &m.triangles)
            })
            .collect::<std::result::Result<Vec<_>, _>>()?;
        let instances: Vec<Instance> =
            scene.instances.iter().map(|i| Instance::new(i.mesh, i.transform)).collect();
        let tlas = Tlas::build(meshes, &instances)?;
        let translucent =
            scene.instances.iter().map(|i| scene.materials[i.material as usize].is_translucent()).collect();
        Ok(Self { tlas, translucent })
    }

    /// The top level (for statistics).
    pub fn tlas(&self) -> &Tlas {
        &self.tlas
    }

    /// Whether scene instance `instance` has a translucent material.
    pub fn is_translucent(&self, instance: u32) -> bool {
        self.translucent.get(instance as usize).copied().unwrap_or(false)
    }

    /// The nearest hit of the ray `origin + t·dir` (`dir` unit) for `t` in `(0, t_max]`.
    pub fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<Hit> {
        self.tlas.closest_hit(&closest_ray(origin, dir, t_max))
    }

    /// The nearest hit whose instance `keep` accepts (e.g. only opaque surfaces).
    pub fn closest_where(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        keep: impl Fn(bool) -> bool,
    ) -> Option<Hit> {
        let mut filter = |h: &Hit| keep(self.is_translucent(h.instance));
        self.tlas.closest_hit_filtered(&Ray::segment(origin, dir, 0.0, t_max), &mut filter)
    }

    /// The nearest surface along the unit direction `dir`, resolved.
    pub fn surface(&self, scene: &HybridScene, origin: Vec3, dir: Vec3) -> Option<ShadingPoint> {
        let hit = self.closest(origin, dir, f32::INFINITY)?;
        Some(resolve(scene, &hit, dir))
    }

    /// Whether anything lies between `origin` and the point `distance` along the unit `dir`
    /// (`f32::INFINITY` for a directional light).
    pub fn occluded(&self, origin: Vec3, dir: Vec3, distance: f32) -> bool {
        self.tlas.any_hit(&shadow_ray(origin, dir, distance))
    }
}

/// The ray [`Accel::occluded`] traces for a light `distance` along the unit `dir` from
/// `origin`: it stops [`SHADOW_END`] of the way there (or runs on, for a directional light),
/// for batches of shadow rays ([`crate::stages::tiles`]).
pub fn shadow_ray(origin: Vec3, dir: Vec3, distance: f32) -> Ray {
    let t_max = if distance.is_finite() { distance * SHADOW_END } else { f32::INFINITY };
    Ray::segment(origin, dir, 0.0, t_max)
}

/// The ray [`Accel::closest`] traces: `origin + t·dir` for `t` in `(0, t_max]`.
pub fn closest_ray(origin: Vec3, dir: Vec3, t_max: f32) -> Ray {
    Ray::segment(origin, dir, 0.0, t_max)
}

/// A hit resolved into a shading point seen along `dir`.
pub fn resolve(scene: &HybridScene, hit: &Hit, dir: Vec3) -> ShadingPoint {
    scene.shading_point(hit.instance, hit.primitive, glam::Vec2::new(hit.u, hit.v), dir)
}
