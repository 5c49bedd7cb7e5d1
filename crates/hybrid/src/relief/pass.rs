//! The relief pass: after the geometry pass, every opaque pixel whose material has a depth
//! map traces its camera ray through the relief and moves its shading point to the hit.
//!
//! # The ray in tangent space, exact per triangle
//!
//! On a triangle with world positions `P_k` and texture coordinates `uv_k`, the texture
//! mapping is affine: `∂P/∂u`, `∂P/∂v` solve `P_1 − P_0 = ∂P/∂u Δu_1 + ∂P/∂v Δv_1` (and
//! likewise for `P_2`). World units per UV is `w = √|∂P/∂u × ∂P/∂v|` (the root of the area
//! ratio) and the relief is `s · w` world units deep (`s` the depth scale). A point `Δu, Δv`
//! from the top-surface point and `d` deep lies at `P + M (Δu, Δv, d)` with
//! `M = [∂P/∂u, ∂P/∂v, −N s w]` (`N` the face's normal toward the viewer), so the unit camera
//! ray `D` advances `(a, b, c) = M⁻¹ D` per world unit: `c` depth and `(a, b)` UV. The
//! tangent-space view vector the techniques read (toward the eye, `uv − V.xy/V.z · s · d` at
//! depth `d`) is then `V = normalize(−a, −b, c s)`; for a conformal mapping this is the
//! usual `TBNᵀ(−D)`.
//!
//! # The shading point at the hit
//!
//! The hit's texture coordinate replaces the pixel's (albedo, roughness and the normal map
//! are read there: [`HybridScene::shading_point_at_uv`]). With the pixel-depth offset the
//! position moves along the camera ray to the displaced hit, `t = |M (Δuv, d)|` world units
//! behind the top surface (the relief frame's `offset_depth`,
//! `|(Δuv, d · s)| · w`, written with the exact Jacobian), and
//! [`ShadingPoint::relief_depth`] records its depth `d · s · w` below the surface: the shadow
//! stages test the light from where its ray leaves the surface
//! ([`ShadingPoint::surface_exit`]) rather than from inside the wall, where the flat
//! geometry would shadow every point. Without the offset the position stays on the flat
//! top surface, as an engine without it leaves its depth buffer.

use super::maps::ReliefMaps;
use super::settings::{ReliefSettings, ReliefTracer};
use crate::deferred::geometry::{GeometryPass, PreparedScene, VisibilitySample};
use glam::{Mat3, Vec2, Vec3};
use rayon::prelude::*;
use renderlab_core::counter::NoCount;
use renderlab_relief::march::exact::ExactTrace;
use renderlab_relief::techniques::descriptor::WithTracer;
use renderlab_relief::{Kernel, Map, RayContext, ReliefHit, ReliefTechnique};
use renderlab_scene::{HybridScene, ShadingPoint};

/// Smallest tangent-space depth rate `c` (relief depths per world unit along the ray) the
/// pass accepts: a ray running within ~0.06° of the surface is left flat.
const MIN_DEPTH_RATE: f32 = 1e-6;

/// The camera ray on one pixel's triangle, in the relief's tangent space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentRay {
    /// Unit view vector toward the eye in tangent space (the techniques' `view_ts`).
    pub view_ts: Vec3,
    /// Tangent space → world offsets: `[∂P/∂u, ∂P/∂v, −N s w]`.
    pub to_world: Mat3,
    /// World units per UV unit, `√|∂P/∂u × ∂P/∂v|`.
    pub world_per_uv: f32,
}

impl TangentRay {
    /// The ray `dir` (unit, from the eye) on the triangle `positions` (world) with texture
    /// coordinates `uvs`, face normal `normal` toward the viewer, for a relief of depth scale
    /// `scale`; `None` on a triangle without a usable UV mapping or for a ray that does not
    /// enter the surface.
    pub fn new(positions: [Vec3; 3], uvs: [Vec2; 3], normal: Vec3, dir: Vec3, scale: f32) -> Option<Self> {
        let (e1, e2) = (positions[1] - positions[0], positions[2] - positions[0]);
        let (t1, t2) = (uvs[1] - uvs[0], uvs[2] - uvs[0]);
        let det = t1.x * t2.y - t2.x * t1.y;
        if det.abs() <= f32::EPSILON * (t1.length_squared() + t2.length_squared()) || !det.is_finite() {
            return None;
        }
        let dp_du = (e1 * t2.y - e2 * t1.y) / det;
        let dp_dv = (e2 * t1.x - e1 * t2.x) / det;
        let world_per_uv = dp_du.cross(dp_dv).length().sqrt();
        let to_world = Mat3::from_cols(dp_du, dp_dv, -normal * (scale * world_per_uv));
        let det_m = to_world.determinant();
        if !(world_per_uv > 0.0 && det_m.is_finite() && det_m != 0.0) {
            return None;
        }
        let rate = to_world.inverse() * dir;
        if !(rate.is_finite() && rate.z > MIN_DEPTH_RATE) {
            return None;
        }
        let view_ts = Vec3::new(-rate.x, -rate.y, rate.z * scale).normalize();
        Some(Self { view_ts, to_world, world_per_uv })
    }

    /// World distance along the camera ray from the top-surface point to a hit `delta_uv`
    /// away in UV and `depth` deep: `|M (Δuv, d)|`.
    pub fn distance(&self, delta_uv: Vec2, depth: f32) -> f32 {
        (self.to_world * delta_uv.extend(depth)).length()
    }
}

/// What the relief pass found at one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReliefSample {
    /// The tracer's hit (unwrapped UV, depth in [0, 1]).
    pub hit: ReliefHit,
    /// The top-surface point the geometry pass resolved.
    pub top: Vec3,
    /// World distance from `top` to the hit along the camera ray.
    pub distance: f32,
    /// The relief's full depth here in world units, `s · w`.
    pub relief_world_depth: f32,
}

/// Runs the relief pass over `geometry`'s opaque layer as `settings` say (nothing when its
/// tracer is `None`), with `maps` holding the materials' relief inputs; returns what it found
/// per pixel (`None` where the pixel shows no relief).
pub fn relief_pass(
    prepared: &PreparedScene,
    geometry: &mut GeometryPass,
    settings: &ReliefSettings,
    maps: &ReliefMaps,
) -> Vec<Option<ReliefSample>> {
    let n = geometry.visibility.len();
    let Some(tracer) = settings.tracer else {
        return vec![None; n];
    };
    let job = Job { prepared, geometry: &*geometry, maps, pdo: settings.pixel_depth_offset };
    let found = match tracer {
        ReliefTracer::Technique(t) => {
            let needs = t.descriptor().needs(Kernel::Scalar);
            t.with_tracer(Kernel::Scalar, WithNeeds { job, needs: &needs })
        }
        ReliefTracer::Exact => job.run(&ExactTrace, &[]),
    };
    let mut samples = vec![None; n];
    for (i, f) in found.into_iter().enumerate() {
        if let Some((sp, sample)) = f {
            geometry.gbuffer.opaque[i] = Some(sp);
            samples[i] = Some(sample);
        }
    }
    samples
}

/// The pass's inputs, shared by every pixel.
#[derive(Clone, Copy)]
struct Job<'a, 's> {
    prepared: &'a PreparedScene<'s>,
    geometry: &'a GeometryPass,
    maps: &'a ReliefMaps,
    pdo: bool,
}

/// A technique's monomorphised pass (the relief catalogue hands over its tracer).
struct WithNeeds<'a, 's> {
    job: Job<'a, 's>,
    needs: &'a [Map],
}

impl WithTracer for WithNeeds<'_, '_> {
    type Output = Vec<Option<(ShadingPoint, ReliefSample)>>;

    fn run<T: ReliefTechnique>(self, t: &T) -> Self::Output {
        self.job.run(t, self.needs)
    }
}

impl Job<'_, '_> {
    /// Every pixel in parallel.
    fn run<T: ReliefTechnique>(&self, t: &T, needs: &[Map]) -> Vec<Option<(ShadingPoint, ReliefSample)>> {
        let g = &self.geometry.gbuffer;
        self.geometry
            .visibility
            .par_iter()
            .enumerate()
            .map(|(i, v)| {
                let (v, sp) = (v.as_ref()?, g.opaque[i].as_ref()?);
                self.pixel(t, needs, v, sp, g.view_dir(i))
            })
            .collect()
    }

    /// One pixel: trace, then resolve the surface at the hit.
    fn pixel<T: ReliefTechnique>(
        &self,
        t: &T,
        needs: &[Map],
        v: &VisibilitySample,
        sp: &ShadingPoint,
        dir: Vec3,
    ) -> Option<(ShadingPoint, ReliefSample)> {
        let scene: &HybridScene = self.prepared.scene;
        let material = scene.instances[v.instance as usize].material;
        if !sp.front_face || !self.maps.has_relief(material) {
            return None;
        }
        let inputs = self.maps.inputs(material, needs)?;
        let mesh = &self.prepared.world[v.instance as usize];
        let tri = mesh.triangles[v.triangle as usize].map(|k| mesh.vertices[k as usize]);
        let ray = TangentRay::new(
            tri.map(|x| x.position),
            tri.map(|x| x.uv),
            sp.geometric_normal,
            dir,
            inputs.height_scale,
        )?;
        // Trace from the first tile (the depth field repeats), then move the hit back.
        let base = sp.uv.floor();
        let hit = t.trace_in(&inputs, sp.uv - base, ray.view_ts, &RayContext::default(), &mut NoCount);
        if hit.is_miss() || !hit.uv.is_finite() {
            return None;
        }
        let delta = hit.uv - (sp.uv - base);
        let hit = ReliefHit { uv: hit.uv + base, ..hit };
        let distance = ray.distance(delta, hit.depth);
        let relief_world_depth = inputs.height_scale * ray.world_per_uv;
        let mut moved = scene.shading_point_at_uv(v.instance, v.triangle, v.bary, dir, hit.uv);
        if self.pdo && distance.is_finite() {
            moved.position = sp.position + dir * distance;
            moved.relief_depth = hit.depth * relief_world_depth;
        }
        let sample = ReliefSample { hit, top: sp.position, distance, relief_world_depth };
        Some((moved, sample))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_conformal_triangle_gives_the_usual_tangent_view_and_distances() {
        // A wall in the plane z = 0, 2 world units per UV, u along +x, v along +y.
        let p = [Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)];
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        let dir = Vec3::new(0.6, 0.0, -0.8);
        let r = TangentRay::new(p, uv, Vec3::Z, dir, 0.05).unwrap();
        assert!((r.world_per_uv - 2.0).abs() < 1e-6);
        // TBNᵀ(−D) = (−0.6, 0, 0.8).
        assert!((r.view_ts - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-5, "{}", r.view_ts);
        // Full depth d = 1 is 0.1 world units deep: 0.125 along the ray, 0.0375 in u.
        let along = 0.1 / 0.8;
        let delta = Vec2::new(0.6 * along / 2.0, 0.0);
        assert!((r.distance(delta, 1.0) - along).abs() < 1e-6);
        // A ray along the surface or leaving it does not enter.
        assert!(TangentRay::new(p, uv, Vec3::Z, Vec3::X, 0.05).is_none());
        assert!(TangentRay::new(p, uv, Vec3::Z, -dir, 0.05).is_none());
        // Degenerate UVs give no frame.
        assert!(TangentRay::new(p, [Vec2::ZERO; 3], Vec3::Z, dir, 0.05).is_none());
    }

    #[test]
    fn a_stretched_mapping_follows_the_ray_exactly() {
        // u stretched: 4 world units per u, 1 per v; the ray's UV per depth must land the hit
        // on the camera ray.
        let p = [Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        let dir = Vec3::new(0.3, -0.2, -0.9).normalize();
        let scale = 0.05;
        let r = TangentRay::new(p, uv, Vec3::Z, dir, scale).unwrap();
        let per_depth = renderlab_relief::trace::uv_per_depth(r.view_ts, scale);
        let offset = r.to_world * per_depth.extend(1.0);
        assert!(offset.normalize().dot(dir) > 1.0 - 1e-6, "{offset} against {dir}");
        assert!((offset.z + scale * r.world_per_uv).abs() < 1e-6);
    }
}
