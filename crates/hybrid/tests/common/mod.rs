//! Fixtures shared by the integration tests: small scenes with known answers.
#![allow(dead_code)]

use glam::{Vec3, Vec4Swizzles};
use renderlab_core::Camera;
use renderlab_scene::shapes::{light, quad, SceneBuilder};
use renderlab_scene::{HybridScene, LightKind, PbrMaterial};

/// Mean squared error over pixels and channels.
pub fn mse(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (*x - *y).length_squared() as f64 / 3.0).sum::<f64>() / a.len() as f64
}

/// The pixel (column, row) where the world point `p` projects in `camera`.
pub fn project(camera: &Camera, p: Vec3) -> (u32, u32) {
    let c = camera.view_projection() * p.extend(1.0);
    let ndc = c.xyz() / c.w;
    let x = (ndc.x + 1.0) * 0.5 * camera.width as f32;
    let y = (1.0 - ndc.y) * 0.5 * camera.height as f32;
    (x as u32, y as u32)
}

/// A closed room (inward-facing floor, ceiling, back, left red and right green walls, and a
/// front wall behind the camera) of side 2 centred at (0, 1, 0), with a point light under
/// the ceiling and a black sky: a Cornell-box-like scene with only diffuse-looking
/// surfaces, and its camera at `size`².
pub fn cornell(size: u32) -> (HybridScene, Camera) {
    let mut b = SceneBuilder::new("cornell", Vec3::ZERO);
    let white = PbrMaterial::dielectric("white", Vec3::splat(0.7), 1.0);
    let h = 1.0;
    // Fronts face the inside.
    b.add(quad(Vec3::ZERO, Vec3::new(0.0, 0.0, h), Vec3::new(h, 0.0, 0.0)), white.clone());
    b.add(quad(Vec3::new(0.0, 2.0, 0.0), Vec3::new(h, 0.0, 0.0), Vec3::new(0.0, 0.0, h)), white.clone());
    b.add(quad(Vec3::new(0.0, 1.0, -h), Vec3::new(h, 0.0, 0.0), Vec3::new(0.0, h, 0.0)), white.clone());
    b.add(quad(Vec3::new(0.0, 1.0, h), Vec3::new(0.0, h, 0.0), Vec3::new(h, 0.0, 0.0)), white);
    b.add(
        quad(Vec3::new(-h, 1.0, 0.0), Vec3::new(0.0, h, 0.0), Vec3::new(0.0, 0.0, h)),
        PbrMaterial::dielectric("red", Vec3::new(0.7, 0.1, 0.1), 1.0),
    );
    b.add(
        quad(Vec3::new(h, 1.0, 0.0), Vec3::new(0.0, 0.0, h), Vec3::new(0.0, h, 0.0)),
        PbrMaterial::dielectric("green", Vec3::new(0.1, 0.7, 0.1), 1.0),
    );
    b.light(light(LightKind::Point, Vec3::new(0.0, 1.8, 0.0), Vec3::ZERO, 2.0));
    let mut camera = Camera::look_at(Vec3::new(0.0, 1.0, 0.95), Vec3::new(0.0, 1.0, -1.0), size, size);
    camera.fov_y_deg = 80.0;
    camera.near = 0.01;
    (b.scene, camera)
}
