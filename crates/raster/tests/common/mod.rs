//! Analytic references for the rasterizer tests: the pixel's centre ray in f64 (the same
//! construction as `Camera::ray_direction`) intersected with a quad's plane.

#![allow(dead_code)]

use glam::{DVec2, DVec3, Vec2, Vec3};
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE, WALL_HEIGHT, WALL_TILE, WALL_WIDTH};
use renderlab_core::{Camera, Image, Material, Mesh, Scene, SceneObject};

/// The view angles of the thesis's benchmark, in degrees from the wall's normal: the
/// rasterizer is checked at the views the relief lab renders (whose fixtures hold them).
pub const ANGLES_DEG: [f32; 4] = [0.0, 45.0, 60.0, 80.0];

/// A camera 6 units from the centre of the bricks wall, turned `angle_deg` from its normal:
/// the thesis's benchmark view.
pub fn wall_camera(angle_deg: f32, width: u32, height: u32) -> Camera {
    Camera::orbit(BRICKS_WALL_CENTRE, 6.0, angle_deg, width, height)
}

/// The bricks wall alone.
pub fn wall_scene() -> Scene {
    Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![flat()])
}

/// The thesis's room, every surface with the same flat material.
pub fn room() -> Scene {
    Scene::thesis_room([flat(), flat(), flat(), flat()])
}

/// A camera overlooking the whole room (the view `renderlab render --scene room` uses).
pub fn room_camera(width: u32, height: u32) -> Camera {
    Camera::look_at(Vec3::new(1.5, 1.6, 9.5), Vec3::new(0.0, 0.4, 1.0), width, height)
}

/// `Camera::ray_direction` evaluated in f64, so that finite differences over 1e-3 pixel are
/// meaningful.
pub fn ray_direction(cam: &Camera, px: f64, py: f64) -> DVec3 {
    let (w, h) = (cam.width as f64, cam.height as f64);
    let ndc_x = 2.0 * px / w - 1.0;
    let ndc_y = 1.0 - 2.0 * py / h;
    let t = ((cam.fov_y_deg as f64).to_radians() * 0.5).tan();
    let f = cam.forward.as_dvec3();
    let right = f.cross(cam.up.as_dvec3()).normalize();
    let up = right.cross(f);
    (f + right * (ndc_x * t * (w / h)) + up * (ndc_y * t)).normalize()
}

/// A quad as `Mesh::quad` builds it, kept analytically.
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    pub centre: DVec3,
    pub right: DVec3,
    pub down: DVec3,
    pub repeat: DVec2,
}

/// Where a ray meets a quad's plane.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Distance along the (unit) ray.
    pub t: f64,
    pub position: DVec3,
    pub uv: DVec2,
    /// Whether the hit lies inside the quad (local coordinates within ±1).
    pub inside: bool,
}

impl Quad {
    pub fn new(centre: Vec3, right: Vec3, down: Vec3, repeat: Vec2) -> Self {
        Self {
            centre: centre.as_dvec3(),
            right: right.as_dvec3(),
            down: down.as_dvec3(),
            repeat: repeat.as_dvec2(),
        }
    }

    /// The thesis's bricks wall (`renderlab_core::scene::bricks_wall`).
    pub fn bricks_wall() -> Self {
        Self::new(
            BRICKS_WALL_CENTRE,
            Vec3::X * (WALL_WIDTH * 0.5),
            -Vec3::Y * (WALL_HEIGHT * 0.5),
            Vec2::new(WALL_WIDTH / WALL_TILE, WALL_HEIGHT / WALL_TILE),
        )
    }

    pub fn mesh(&self) -> Mesh {
        Mesh::quad(self.centre.as_vec3(), self.right.as_vec3(), self.down.as_vec3(), self.repeat.as_vec2())
    }

    /// The ray `origin + t·dir` against the quad's plane; `None` if parallel or behind.
    pub fn intersect(&self, origin: DVec3, dir: DVec3) -> Option<Hit> {
        let n = self.down.cross(self.right);
        let denom = n.dot(dir);
        if denom.abs() < 1e-300 {
            return None;
        }
        let t = n.dot(self.centre - origin) / denom;
        if t.is_nan() || t <= 0.0 {
            return None;
        }
        let position = origin + dir * t;
        let d = position - self.centre;
        let s = d.dot(self.right) / self.right.length_squared();
        let r = d.dot(self.down) / self.down.length_squared();
        Some(Hit {
            t,
            position,
            uv: DVec2::new((s + 1.0) * 0.5 * self.repeat.x, (r + 1.0) * 0.5 * self.repeat.y),
            inside: s.abs() <= 1.0 && r.abs() <= 1.0,
        })
    }

    /// The hit of the centre ray through pixel position `(px, py)`.
    pub fn pixel(&self, cam: &Camera, px: f64, py: f64) -> Option<Hit> {
        self.intersect(cam.position.as_dvec3(), ray_direction(cam, px, py))
    }

    /// Whether the rays through the pixel's centre and through the points one pixel away
    /// in each direction all hit the quad (the pixel is safely inside), or all miss it
    /// (safely outside). `None` near the boundary.
    pub fn classify(&self, cam: &Camera, x: u32, y: u32) -> Option<bool> {
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        let probes = [(0.0, 0.0), (-1.0, 0.0), (1.0, 0.0), (0.0, -1.0), (0.0, 1.0)];
        let hits = probes
            .iter()
            .filter(|(dx, dy)| self.pixel(cam, cx + dx, cy + dy).is_some_and(|h| h.inside))
            .count();
        match hits {
            5 => Some(true),
            0 => Some(false),
            _ => None,
        }
    }
}

/// A scene with the given meshes (material i for object i) and one flat material.
pub fn scene_of(meshes: Vec<Mesh>) -> Scene {
    let objects = meshes
        .into_iter()
        .enumerate()
        .map(|(i, mesh)| SceneObject { name: format!("object{i}"), mesh, material: i as u32 })
        .collect();
    Scene::new(objects, vec![flat()])
}

/// A one-texel grey material: rasterization reads only the geometry and the light.
pub fn flat() -> Material {
    Material::from_maps("flat", Image::new(1, 1, Vec3::splat(0.5)), Image::new(1, 1, 0.5), None, 0.05)
        .expect("valid height scale")
}
