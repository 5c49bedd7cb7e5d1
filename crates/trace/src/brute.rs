//! The reference the hierarchy is tested against: every triangle of every instance, with the
//! same watertight test, the same object-space rays and the same tie rule. A correct hierarchy
//! returns exactly (bit for bit) what this returns.

use crate::hit::Hit;
use crate::ray::Ray;
use crate::tlas::Instance;
use crate::traverse::backend::RayQuery;
use crate::triangle::{intersect, is_hittable};
use glam::Vec3;

/// The closest hit of `ray` among `instances` of `meshes` (triangle soups), found by testing
/// every triangle. A mesh index out of range counts as an empty mesh.
pub fn closest_hit(meshes: &[Vec<[Vec3; 3]>], instances: &[Instance], ray: &Ray) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (i, inst) in instances.iter().enumerate() {
        let Some(w2o) = inst.world_to_object() else { continue };
        let Some(tris) = meshes.get(inst.mesh as usize) else { continue };
        if let Some(h) = closest_hit_mesh(tris, &ray.transformed(&w2o), i as u32) {
            if best.as_ref().is_none_or(|b| Hit::precedes(h.t, h.instance, h.primitive, b)) {
                best = Some(h);
            }
        }
    }
    best
}

/// The closest hit of `ray` in one triangle soup, reported with `instance`.
pub fn closest_hit_mesh(tris: &[[Vec3; 3]], ray: &Ray, instance: u32) -> Option<Hit> {
    let q = RayQuery::new(ray)?;
    let mut best: Option<Hit> = None;
    for (p, &[a, b, c]) in tris.iter().enumerate() {
        if !is_hittable(a, b, c) {
            continue;
        }
        let Some(h) = intersect(&q.tri, a.to_array(), b.to_array(), c.to_array(), q.t_min, q.t_max) else {
            continue;
        };
        if best.as_ref().is_none_or(|b| Hit::precedes(h.t, instance, p as u32, b)) {
            best = Some(Hit { t: h.t, u: h.u, v: h.v, primitive: p as u32, instance });
        }
    }
    best
}
