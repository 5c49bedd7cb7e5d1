//! The patch behind each pixel of a rasterized scene ([`PatchInfo`]): what a mesh says about
//! the surface beyond the tangent plane a G-buffer keeps.
//!
//! Per object: the UV rectangle its vertices span (the edge past which a ray that stays in
//! the patch's relief has left the surface), and its scale, `world_per_uv = √(A_world /
//! A_uv)` summed over its triangles (exact for a mapping that stretches both axes alike, as
//! the scenes' quads do; the root mean square scale of an anisotropic one). Curvature is 0:
//! the rasterized scenes' meshes are planar pieces, and curved analytic shapes give their
//! own per-pixel curvature.

use crate::render::shade::PatchInfo;
use glam::Vec2;
use renderlab_core::{Mesh, Scene, SurfacePoint};

/// The patch of one mesh: its UV rectangle and its scale (0 when its UV area is 0).
pub fn mesh_patch(mesh: &Mesh) -> PatchInfo {
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for v in &mesh.vertices {
        lo = lo.min(v.uv);
        hi = hi.max(v.uv);
    }
    let (mut world, mut uv) = (0.0f64, 0.0f64);
    for t in &mesh.triangles {
        let vertex = |i: u32| mesh.vertices.get(i as usize);
        let (Some(a), Some(b), Some(c)) = (vertex(t[0]), vertex(t[1]), vertex(t[2])) else {
            continue;
        };
        world += 0.5 * (b.position - a.position).cross(c.position - a.position).length() as f64;
        uv += 0.5 * ((b.uv - a.uv).perp_dot(c.uv - a.uv)).abs() as f64;
    }
    let world_per_uv = if uv > 0.0 && world.is_finite() { (world / uv).sqrt() as f32 } else { 0.0 };
    if lo.x > hi.x || lo.y > hi.y {
        return PatchInfo { world_per_uv, ..PatchInfo::default() };
    }
    PatchInfo { uv_min: lo, uv_max: hi, world_per_uv, ..PatchInfo::default() }
}

/// One [`PatchInfo`] per pixel of `points` (a G-buffer of `scene`): its object's
/// [`mesh_patch`], the default (flat, unbounded, unknown scale) on background and on objects
/// the scene does not have.
pub fn patches_from_scene(scene: &Scene, points: &[Option<SurfacePoint>]) -> Vec<PatchInfo> {
    let per_object: Vec<PatchInfo> = scene.objects.iter().map(|o| mesh_patch(&o.mesh)).collect();
    points
        .iter()
        .map(|p| p.and_then(|sp| per_object.get(sp.object as usize).copied()).unwrap_or_default())
        .collect()
}

/// The median world units per UV over `patches` of known scale (0 when none is known): with a
/// material's depth scale, the relief's full depth in world units, which the pixel-depth
/// offset's errors are measured against.
pub fn median_world_per_uv(patches: &[PatchInfo]) -> f32 {
    let mut scales: Vec<f32> = patches.iter().map(|p| p.world_per_uv).filter(|&s| s > 0.0).collect();
    if scales.is_empty() {
        return 0.0;
    }
    let mid = scales.len() / 2;
    *scales.select_nth_unstable_by(mid, f32::total_cmp).1
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn a_quad_gives_its_uv_rectangle_and_scale() {
        // 4 × 2 world units mapped to 2 × 1 UV: 2 world units per UV unit.
        let q =
            Mesh::quad(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, -1.0, 0.0), Vec2::new(2.0, 1.0));
        let p = mesh_patch(&q);
        assert_eq!((p.uv_min, p.uv_max), (Vec2::ZERO, Vec2::new(2.0, 1.0)));
        assert!((p.world_per_uv - 2.0).abs() < 1e-6, "{}", p.world_per_uv);
        assert_eq!(p.curvature, Vec2::ZERO);
    }

    #[test]
    fn degenerate_meshes_give_an_unknown_scale() {
        let empty = Mesh { vertices: vec![], triangles: vec![[0, 1, 2]] };
        let p = mesh_patch(&empty);
        assert_eq!(p.world_per_uv, 0.0);
        assert_eq!(p.uv_min, Vec2::splat(f32::NEG_INFINITY));
    }
}
