//! The per-ray context and the frame's outputs that follow the patch: a technique that reads
//! its ray's context gets the pixel's footprint and the patch's bounds moved with its ray into
//! the first tile; a miss leaves the background; and the pixel-depth offset puts the
//! displaced hit on the camera ray at its depth behind the wall.

use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;
use renderlab_core::scene::{bricks_wall, Lighting, BRICKS_WALL_CENTRE};
use renderlab_core::{Camera, Scene, SceneObject};
use renderlab_raster::rasterize;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::render::render_reference;
use renderlab_relief::render::shade::{render_frame, ShadeOptions, ShadowMode};
use renderlab_relief::{
    patches_from_scene, FrameInput, PatchInfo, RayContext, ReliefHit, ReliefInputs, ReliefMaterial,
    ReliefTechnique, Shading, Technique,
};

fn wall() -> (Scene, ReliefMaterial) {
    let m = renderlab_texture::materials::material("bricks", 64).expect("built-in material");
    let mat = ReliefMaterial::new(&m, &ComplexityParams::default(), false);
    let scene =
        Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![m]);
    (scene, mat)
}

/// Reports what it was handed: the hit lies 0.25 UV inside the context's lower bound, its
/// layer count is the footprint in millionths, and rays whose entry lies outside the
/// rectangle miss.
struct Probe;

impl ReliefTechnique for Probe {
    const USES_CONTEXT: bool = true;

    fn trace<C: Counter>(&self, _: &ReliefInputs, uv: Vec2, _: Vec3, _: &mut C) -> ReliefHit {
        ReliefHit { uv, depth: 0.0, layers: 0 }
    }

    fn trace_in<C: Counter>(
        &self,
        _: &ReliefInputs,
        uv: Vec2,
        _: Vec3,
        ctx: &RayContext,
        _: &mut C,
    ) -> ReliefHit {
        if uv.cmplt(ctx.uv_min).any() || uv.cmpgt(ctx.uv_max).any() {
            return ReliefHit::miss();
        }
        ReliefHit {
            uv: ctx.uv_min + Vec2::splat(0.25),
            depth: 0.5,
            layers: (ctx.footprint * 1e6).round() as u32,
        }
    }
}

fn options() -> ShadeOptions {
    ShadeOptions {
        lighting: Lighting::default(),
        shading: Shading::Unlit,
        shadow: ShadowMode::None,
        background: Vec3::new(0.1, 0.2, 0.3),
    }
}

#[test]
fn a_context_technique_gets_the_footprint_and_bounds_and_its_misses_stay_background() {
    let (scene, mat) = wall();
    let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, 30.0, 96, 60);
    let g = rasterize(&scene, &cam);
    // Bounds covering the left half of the wall's UV range (the wall maps to 0..repeat).
    let mut patches = patches_from_scene(&scene, g.pixels());
    let full = patches.iter().find(|p| p.world_per_uv > 0.0).copied().expect("the wall is seen");
    let mid = 0.5 * (full.uv_min.x + full.uv_max.x);
    for p in &mut patches {
        p.uv_max.x = p.uv_max.x.min(mid);
    }
    let input = FrameInput::new(96, 60, g.pixels()).with_patches(&patches);
    let frame = render_frame(input, std::slice::from_ref(&mat), &Probe, &options(), false);
    let (mut inside, mut outside) = (0, 0);
    for (i, p) in g.pixels().iter().enumerate() {
        let (x, y) = ((i % 96) as u32, (i / 96) as u32);
        let Some(sp) = p else {
            assert!(!frame.mask.get(x, y));
            continue;
        };
        if sp.uv.x > mid {
            outside += 1;
            assert!(!frame.mask.get(x, y), "a miss counts as uncovered");
            assert_eq!(frame.image.get(x, y), options().background);
            assert_eq!((frame.uv.get(x, y), frame.view_depth.get(x, y)), (Vec2::ZERO, 0.0));
            continue;
        }
        inside += 1;
        assert!(frame.mask.get(x, y));
        // The bounds moved with the ray into its tile and the hit back: the patch's corner.
        let got = frame.uv.get(x, y);
        assert!((got - (full.uv_min + Vec2::splat(0.25))).abs().max_element() < 1e-5, "{got:?}");
        let want = sp.duv_dx.length().max(sp.duv_dy.length());
        assert_eq!(frame.layers.get(x, y) as u32, ((want * 1e6).round() as u32).min(u16::MAX as u32));
    }
    assert!(inside > 500 && outside > 500, "{inside} inside, {outside} outside");
}

#[test]
fn the_pixel_depth_offset_puts_the_exact_hit_on_the_camera_ray_behind_the_wall() {
    let (scene, mat) = wall();
    for angle in [0.0, 45.0, 70.0] {
        let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, angle, 80, 50);
        let g = rasterize(&scene, &cam);
        let patches = patches_from_scene(&scene, g.pixels());
        let input = FrameInput::new(80, 50, g.pixels()).with_patches(&patches);
        let pom = Technique::parse("pom:32").unwrap();
        let frame = render_reference(input, std::slice::from_ref(&mat), pom, Lighting::default(), Vec3::ZERO);
        let mut checked = 0;
        for (i, p) in g.pixels().iter().enumerate() {
            let Some(sp) = p else { continue };
            let (x, y) = ((i % 80) as u32, (i / 80) as u32);
            let patch: PatchInfo = patches[i];
            let dir = (sp.position - cam.position).normalize();
            let normal = sp.tbn.z_axis;
            // The displaced point on the camera ray, and its distance behind the wall plane.
            let point = cam.position + dir * frame.view_depth.get(x, y);
            let behind = (sp.position - point).dot(normal);
            let want = frame.depth.get(x, y) * mat.height_scale * patch.world_per_uv;
            assert!((behind - want).abs() < 1e-3 * (1.0 + want), "{angle}°: {behind} behind, want {want}");
            assert!(frame.view_depth.get(x, y) >= sp.depth);
            checked += 1;
        }
        assert!(checked > 1000, "{checked}");
    }
}

#[test]
fn without_patches_the_depth_is_the_top_surface_and_nothing_misses() {
    let (scene, mat) = wall();
    let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, 45.0, 64, 40);
    let g = rasterize(&scene, &cam);
    let frame = render_frame(
        FrameInput::new(64, 40, g.pixels()),
        std::slice::from_ref(&mat),
        &Probe,
        &options(),
        false,
    );
    for (i, p) in g.pixels().iter().enumerate() {
        let (x, y) = ((i % 64) as u32, (i / 64) as u32);
        assert_eq!(frame.mask.get(x, y), p.is_some());
        assert_eq!(frame.view_depth.get(x, y), p.map_or(0.0, |sp| sp.depth));
    }
}
