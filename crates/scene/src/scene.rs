//! The hybrid lab's scene: meshes in object space, instances placing them with a transform
//! and a material, textures, lights and named cameras. The rasterizer flattens instances
//! into world-space meshes ([`HybridScene::world_mesh`]); the tracer builds one bottom-level
//! BVH per mesh and a top level over the instances, as DXR does.

use crate::error::{Result, SceneError};
use crate::light::Light;
use crate::material::{PbrMaterial, Texture};
use crate::shading::ShadingPoint;
use glam::{Affine3A, Mat3A, Vec2, Vec3, Vec4Swizzles};
use renderlab_core::{Camera, Mesh};

/// One placed copy of a mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Name (node name in a file, or the procedural scene's own).
    pub name: String,
    /// Index into [`HybridScene::meshes`].
    pub mesh: u32,
    /// Index into [`HybridScene::materials`].
    pub material: u32,
    /// Object → world.
    pub transform: Affine3A,
}

/// A named fixed viewpoint (the thesis's Camera1..3 of each scene).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneCamera {
    /// Name shown in reports.
    pub name: String,
    /// The camera (its width and height are the default resolution).
    pub camera: Camera,
}

/// Meshes, instances, materials, textures, lights and cameras.
#[derive(Clone, Debug)]
pub struct HybridScene {
    /// Name shown in reports.
    pub name: String,
    /// Meshes in object space.
    pub meshes: Vec<Mesh>,
    /// Placed meshes.
    pub instances: Vec<Instance>,
    /// Materials referenced by instances.
    pub materials: Vec<PbrMaterial>,
    /// Textures referenced by materials.
    pub textures: Vec<Texture>,
    /// Light sources.
    pub lights: Vec<Light>,
    /// Fixed viewpoints.
    pub cameras: Vec<SceneCamera>,
    /// Radiance of the sky (what a ray that leaves the scene sees), linear RGB.
    pub sky: Vec3,
}

impl HybridScene {
    /// A scene with nothing in it yet but its name and sky radiance, for builders to fill.
    pub fn empty(name: &str, sky: Vec3) -> Self {
        Self {
            name: name.into(),
            meshes: Vec::new(),
            instances: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            lights: Vec::new(),
            cameras: Vec::new(),
            sky,
        }
    }

    /// Triangles drawn (each instance counts its mesh's triangles), the thesis's Table 2.1
    /// measure of a scene's size.
    pub fn triangle_count(&self) -> usize {
        self.instances.iter().map(|i| self.meshes.get(i.mesh as usize).map_or(0, |m| m.triangles.len())).sum()
    }

    /// Whether some instance emits light: its material [`PbrMaterial::is_emissive`] and its
    /// mesh has triangles. Such a scene is lit even without [`Self::lights`] (a room whose
    /// lamp is an emissive panel). Instances with references out of range count as not
    /// emitting, so that this may be asked before [`Self::validate`].
    pub fn has_emitters(&self) -> bool {
        self.instances.iter().any(|i| {
            self.materials.get(i.material as usize).is_some_and(PbrMaterial::is_emissive)
                && self.meshes.get(i.mesh as usize).is_some_and(|m| !m.triangles.is_empty())
        })
    }

    /// Checks every reference and every number: indices in range, finite vertices, valid
    /// materials and lights. The loaders call it, so that a bad file is refused with one
    /// line rather than failing later inside a renderer.
    pub fn validate(&self) -> Result<()> {
        for (m, mesh) in self.meshes.iter().enumerate() {
            for (v, vert) in mesh.vertices.iter().enumerate() {
                if !vert.position.is_finite() {
                    return Err(SceneError::NonFinite { mesh: m, vertex: v, what: "position" });
                }
                if !(vert.normal.is_finite() && vert.uv.is_finite() && vert.tangent.is_finite()) {
                    return Err(SceneError::NonFinite { mesh: m, vertex: v, what: "normal, uv or tangent" });
                }
            }
            for (t, tri) in mesh.triangles.iter().enumerate() {
                if let Some(&index) = tri.iter().find(|&&i| i as usize >= mesh.vertices.len()) {
                    return Err(SceneError::IndexOutOfRange {
                        mesh: m,
                        triangle: t,
                        index,
                        vertices: mesh.vertices.len(),
                    });
                }
            }
        }
        for inst in &self.instances {
            if inst.mesh as usize >= self.meshes.len() {
                return Err(SceneError::MissingReference {
                    what: "mesh",
                    index: inst.mesh,
                    count: self.meshes.len(),
                });
            }
            if inst.material as usize >= self.materials.len() {
                return Err(SceneError::MissingReference {
                    what: "material",
                    index: inst.material,
                    count: self.materials.len(),
                });
            }
            if !inst.transform.is_finite() || inst.transform.matrix3.determinant() == 0.0 {
                return Err(SceneError::Invalid(format!(
                    "instance {:?} has a singular or non-finite transform",
                    inst.name
                )));
            }
        }
        for m in &self.materials {
            m.validate(self.textures.len())?;
        }
        for l in &self.lights {
            l.validate()?;
        }
        if !self.sky.is_finite() {
            return Err(SceneError::Invalid("the sky radiance is not finite".into()));
        }
        Ok(())
    }

    /// The instance's mesh in world space (positions, normals and tangents transformed;
    /// normals by the inverse transpose), for the rasterizer.
    pub fn world_mesh(&self, instance: &Instance) -> Mesh {
        let mut mesh = self.meshes[instance.mesh as usize].clone();
        let normal_matrix = normal_matrix(&instance.transform);
        for v in &mut mesh.vertices {
            v.position = instance.transform.transform_point3(v.position);
            v.normal = (normal_matrix * v.normal).normalize_or_zero();
            let t = instance.transform.transform_vector3(v.tangent.xyz()).normalize_or_zero();
            v.tangent = t.extend(v.tangent.w);
        }
        if instance.transform.matrix3.determinant() < 0.0 {
            // A mirroring transform turns the winding around; keep fronts counter-clockwise.
            for t in &mut mesh.triangles {
                t.swap(1, 2);
            }
        }
        mesh
    }

    /// Resolves a hit on triangle `triangle` of `instance` at barycentrics `bary` (weights
    /// of the second and third vertex), seen along the unit ray direction `dir`: interpolates
    /// the vertex attributes, samples the material's textures, applies its normal map and
    /// turns both normals toward the viewer. The back face of a material that is not
    /// [`PbrMaterial::double_sided`] emits nothing.
    pub fn shading_point(&self, instance: u32, triangle: u32, bary: Vec2, dir: Vec3) -> ShadingPoint {
        self.resolve(instance, triangle, bary, dir, None)
    }

    /// [`Self::shading_point`] with the material's textures (albedo, metal–roughness, the
    /// normal map) read at `uv` instead of the interpolated texture coordinate: the surface
    /// seen through a relief, whose trace moved the visible texel.
    pub fn shading_point_at_uv(
        &self,
        instance: u32,
        triangle: u32,
        bary: Vec2,
        dir: Vec3,
        uv: Vec2,
    ) -> ShadingPoint {
        self.resolve(instance, triangle, bary, dir, Some(uv))
    }

    /// The shading point of a hit, its textures read at `uv` when given.
    fn resolve(&self, instance: u32, triangle: u32, bary: Vec2, dir: Vec3, uv: Option<Vec2>) -> ShadingPoint {
        let inst = &self.instances[instance as usize];
        let mesh = &self.meshes[inst.mesh as usize];
        let [i0, i1, i2] = mesh.triangles[triangle as usize];
        let (a, b, c) = (mesh.vertices[i0 as usize], mesh.vertices[i1 as usize], mesh.vertices[i2 as usize]);
        let w0 = 1.0 - bary.x - bary.y;
        let lerp3 = |x: Vec3, y: Vec3, z: Vec3| x * w0 + y * bary.x + z * bary.y;
        let p_obj = lerp3(a.position, b.position, c.position);
        let n_obj = lerp3(a.normal, b.normal, c.normal);
        let t_obj = lerp3(a.tangent.xyz(), b.tangent.xyz(), c.tangent.xyz());
        let uv = uv.unwrap_or_else(|| a.uv * w0 + b.uv * bary.x + c.uv * bary.y);
        let nm = normal_matrix(&inst.transform);
        let position = inst.transform.transform_point3(p_obj);
        // The inverse transpose carries the object-space face normal to the world's; under a
        // mirroring transform that is the front of the re-wound triangle of `world_mesh`.
        let geometric = (nm * (b.position - a.position).cross(c.position - a.position)).normalize_or_zero();
        let mut normal = (nm * n_obj).normalize_or_zero();
        if normal == Vec3::ZERO {
            normal = geometric;
        }
        let material = &self.materials[inst.material as usize];
        let mut sp = ShadingPoint {
            position,
            normal,
            geometric_normal: geometric,
            uv,
            base_color: material.base_color,
            roughness: material.roughness,
            metallic: material.metallic,
            transmission: material.transmission,
            ior: material.ior,
            emissive: material.emissive,
            material: inst.material,
            front_face: true,
            relief_depth: 0.0,
        };
        if let Some(t) = material.base_color_texture {
            sp.base_color *= self.textures[t as usize].sample(uv).xyz();
        }
        if let Some(t) = material.metallic_roughness_texture {
            let mr = self.textures[t as usize].sample(uv);
            sp.roughness = (sp.roughness * mr.y).clamp(0.0, 1.0);
            sp.metallic = (sp.metallic * mr.z).clamp(0.0, 1.0);
        }
        if let Some(t) = material.normal_texture {
            let tangent = inst.transform.transform_vector3(t_obj);
            let tangent = (tangent - normal * normal.dot(tangent)).normalize_or_zero();
            if tangent != Vec3::ZERO {
                let bitangent = normal.cross(tangent) * a.tangent.w.signum();
                let m = self.textures[t as usize].sample(uv).xyz() * 2.0 - Vec3::ONE;
                let mapped = (tangent * m.x + bitangent * m.y + normal * m.z).normalize_or_zero();
                if mapped != Vec3::ZERO {
                    sp.normal = mapped;
                }
            }
        }
        // Face the viewer.
        sp.front_face = geometric.dot(dir) < 0.0;
        if !sp.front_face {
            sp.geometric_normal = -sp.geometric_normal;
            sp.normal = -sp.normal;
            if !material.double_sided {
                sp.emissive = Vec3::ZERO;
            }
        }
        if sp.normal.dot(dir) > 0.0 {
            // An interpolated or mapped normal that faces away: fall back to the face's.
            sp.normal = sp.geometric_normal;
        }
        sp
    }
}

/// The inverse transpose of the linear part, which carries normals.
fn normal_matrix(t: &Affine3A) -> Mat3A {
    t.matrix3.inverse().transpose()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;
    use renderlab_core::Vertex;

    fn one_triangle(transform: Affine3A) -> HybridScene {
        let v = |p: Vec3, uv: Vec2| Vertex {
            position: p,
            normal: Vec3::Z,
            uv,
            tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
        };
        HybridScene {
            name: "t".into(),
            meshes: vec![Mesh {
                vertices: vec![
                    v(Vec3::ZERO, Vec2::ZERO),
                    v(Vec3::X, Vec2::new(1.0, 0.0)),
                    v(Vec3::Y, Vec2::new(0.0, 1.0)),
                ],
                triangles: vec![[0, 1, 2]],
            }],
            instances: vec![Instance { name: "i".into(), mesh: 0, material: 0, transform }],
            materials: vec![PbrMaterial::default()],
            textures: vec![],
            lights: vec![],
            cameras: vec![],
            sky: Vec3::ZERO,
        }
    }

    #[test]
    fn a_hit_resolves_position_and_faces_the_viewer() {
        let s = one_triangle(Affine3A::from_translation(Vec3::new(0.0, 0.0, 2.0)));
        s.validate().unwrap();
        let front = s.shading_point(0, 0, Vec2::new(0.25, 0.5), Vec3::NEG_Z);
        assert!((front.position - Vec3::new(0.25, 0.5, 2.0)).length() < 1e-6);
        assert!(front.front_face);
        assert_eq!(front.normal, Vec3::Z);
        let back = s.shading_point(0, 0, Vec2::new(0.25, 0.5), Vec3::Z);
        assert!(!back.front_face);
        assert_eq!(back.normal, Vec3::NEG_Z);
        assert_eq!(back.geometric_normal, Vec3::NEG_Z);
    }

    #[test]
    fn a_single_sided_emitter_emits_from_its_front_only() {
        let mut s = one_triangle(Affine3A::from_translation(Vec3::new(0.0, 0.0, 2.0)));
        assert!(!s.has_emitters());
        let e = Vec3::new(4.0, 2.0, 1.0);
        s.materials[0].emissive = e;
        assert!(s.has_emitters());
        let at = Vec2::new(0.25, 0.25);
        // Double-sided (the default): both faces emit.
        assert_eq!(s.shading_point(0, 0, at, Vec3::NEG_Z).emissive, e);
        assert_eq!(s.shading_point(0, 0, at, Vec3::Z).emissive, e);
        s.materials[0].double_sided = false;
        let (front, back) = (s.shading_point(0, 0, at, Vec3::NEG_Z), s.shading_point(0, 0, at, Vec3::Z));
        assert!(front.front_face && !back.front_face);
        assert_eq!((front.emissive, back.emissive), (e, Vec3::ZERO));
        // A mesh without triangles lights nothing.
        s.meshes[0].triangles.clear();
        assert!(!s.has_emitters());
    }

    #[test]
    fn a_mirroring_instance_keeps_the_front_face_counter_clockwise() {
        let s = one_triangle(Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0)));
        let world = s.world_mesh(&s.instances[0]);
        let [a, b, c] = world.triangles[0].map(|i| world.vertices[i as usize].position);
        let face = (b - a).cross(c - a).normalize();
        assert!((face - world.vertices[0].normal).length() < 1e-6, "winding normal {face}");
        let hit = s.shading_point(0, 0, Vec2::new(0.2, 0.2), Vec3::NEG_Z);
        assert!(hit.front_face && (hit.geometric_normal - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn relief_materials_carry_their_depth_maps_and_resolve_at_a_moved_uv() {
        let s = crate::procedural::builtin("relief_wall").unwrap();
        let by_name = |n: &str| s.materials.iter().find(|m| m.name == n).unwrap();
        let bricks = by_name("bricks").depth_map.as_ref().expect("a relief material has depth");
        assert_eq!((bricks.scale, bricks.depth.size()), (0.05, (256, 256)));
        assert!(bricks.depth.pixels().contains(&0.0) && bricks.depth.pixels().contains(&1.0));
        assert!(by_name("limestone").depth_map.is_none());
        // The wall is instance 0; at the interpolated UV the moved resolve is the plain one.
        let (bary, dir) = (Vec2::new(0.3, 0.2), Vec3::new(0.1, -0.1, -1.0).normalize());
        let plain = s.shading_point(0, 0, bary, dir);
        assert_eq!(s.shading_point_at_uv(0, 0, bary, dir, plain.uv), plain);
        let moved = s.shading_point_at_uv(0, 0, bary, dir, plain.uv + Vec2::new(0.13, 0.07));
        assert_eq!((moved.position, moved.geometric_normal), (plain.position, plain.geometric_normal));
        assert!(moved.uv != plain.uv && moved.base_color != plain.base_color);
        let mut bad = s.clone();
        bad.materials[0].depth_map.as_mut().unwrap().scale = f32::NAN;
        assert!(bad.validate().is_err());
    }

    #[test]
    fn bad_references_and_numbers_are_refused() {
        let mut s = one_triangle(Affine3A::IDENTITY);
        s.meshes[0].triangles[0][2] = 7;
        assert!(matches!(s.validate(), Err(SceneError::IndexOutOfRange { index: 7, .. })));
        let mut s = one_triangle(Affine3A::IDENTITY);
        s.meshes[0].vertices[1].position.x = f32::NAN;
        assert!(matches!(s.validate(), Err(SceneError::NonFinite { vertex: 1, .. })));
        let mut s = one_triangle(Affine3A::IDENTITY);
        s.instances[0].material = 3;
        assert!(matches!(s.validate(), Err(SceneError::MissingReference { what: "material", .. })));
        let mut s = one_triangle(Affine3A::IDENTITY);
        s.materials[0].roughness = 2.0;
        assert!(s.validate().is_err());
        let s = one_triangle(Affine3A::from_scale(Vec3::new(0.0, 1.0, 1.0)));
        assert!(s.validate().is_err());
    }
}
