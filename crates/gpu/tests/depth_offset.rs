//! The pixel-depth offset in the fragment pipeline's depth buffer: a plane set into the
//! relief wall, between its top surface and its deepest point, shows through wherever the
//! relief lies deeper than it once the offset is written, as the CPU's offset depths of the
//! two surfaces predict; without the offset the wall's flat top surface hides it everywhere.

mod common;

use common::context;
use glam::{Vec2, Vec3};
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::{Camera, Mesh, Scene, SceneObject};
use renderlab_gpu::{ReliefPipeline, ReliefRenderer};
use renderlab_raster::rasterize;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::render::patch::mesh_patch;
use renderlab_relief::render::render;
use renderlab_relief::{patches_from_scene, FrameInput, Kernel, ReliefMaterial, Technique};
use renderlab_texture::materials;

const W: u32 = 240;
const H: u32 = 150;

fn object(name: &str, mesh: Mesh, material: u32) -> SceneObject {
    SceneObject { name: name.into(), mesh, material }
}

#[test]
fn a_plane_inside_the_relief_shows_where_the_offset_depth_lies_behind_it() {
    let Some(ctx) = context() else { return };
    let bricks = materials::material("bricks", 128).expect("built-in material");
    let sand = materials::material("sand_rocks", 128).expect("built-in material");
    let mats: Vec<ReliefMaterial> = [&bricks, &sand]
        .iter()
        .map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false))
        .collect();
    // The plane: 40 % of the wall's relief depth behind its top surface, smaller than the wall.
    let relief = mats[0].height_scale * mesh_patch(&bricks_wall()).world_per_uv;
    let inset = 0.4 * relief;
    let mut plane =
        Mesh::quad(BRICKS_WALL_CENTRE - Vec3::Z * inset, Vec3::X * 0.8, -Vec3::Y * 0.5, Vec2::new(1.0, 1.0));
    plane.compute_tangents();
    let both = Scene::new(
        vec![object("wall", bricks_wall(), 0), object("plane", plane.clone(), 1)],
        vec![bricks.clone(), sand.clone()],
    );
    let technique = Technique::parse("pom:32").unwrap();
    let camera = Camera::orbit(BRICKS_WALL_CENTRE, 3.0, 30.0, W, H);
    // The CPU's offset depths of each surface alone.
    let alone = |scene: &Scene| {
        let g = rasterize(scene, &camera);
        let patches = patches_from_scene(scene, g.pixels());
        let input = FrameInput::new(W, H, g.pixels()).with_patches(&patches);
        render(input, &mats, technique, Kernel::Scalar, scene.lighting, scene.background, false).expect("CPU")
    };
    let wall_only = alone(&Scene::new(vec![object("wall", bricks_wall(), 0)], vec![bricks.clone()]));
    let plane_only = alone(&Scene::new(vec![object("plane", plane, 1)], vec![bricks.clone(), sand.clone()]));
    let mut gpu = ReliefRenderer::new(&ctx, &both, &mats).expect("scene uploads");
    gpu.set_pipeline(ReliefPipeline::Fragment).unwrap();
    let flat = gpu.render(&camera, technique).expect("frame");
    gpu.set_pixel_depth_offset(true);
    let offset = gpu.render(&camera, technique).expect("frame");
    if let Some(dir) = std::env::var_os("RENDERLAB_GPU_TEST_IMAGES") {
        let dir = std::path::Path::new(&dir);
        for (name, f) in [("flat", &flat), ("offset", &offset)] {
            renderlab_core::io::save_color(dir.join(format!("depth_offset_{name}.png")), &f.image)
                .expect("writable");
        }
    }
    let (mut inside, mut through, mut wrong, mut flat_through) = (0usize, 0usize, 0usize, 0usize);
    let closer = |img: &renderlab_core::Image<Vec3>, x, y, a: Vec3, b: Vec3| {
        let c = img.get(x, y);
        (c - a).length() < (c - b).length()
    };
    for y in 0..H {
        for x in 0..W {
            if !(wall_only.mask.get(x, y) && plane_only.mask.get(x, y)) {
                continue;
            }
            inside += 1;
            let (w, p) = (wall_only.image.get(x, y), plane_only.image.get(x, y));
            if (w - p).length() < 0.05 {
                continue; // the two surfaces look alike here: the colour cannot tell them apart
            }
            let expect_plane = plane_only.view_depth.get(x, y) < wall_only.view_depth.get(x, y);
            let shows_plane = closer(&offset.image, x, y, p, w);
            through += expect_plane as usize;
            wrong += (shows_plane != expect_plane) as usize;
            flat_through += closer(&flat.image, x, y, p, w) as usize;
        }
    }
    println!("{inside} pixels see both; the plane shows through at {through}; {wrong} disagree; without the offset {flat_through}");
    assert!(inside > 3000, "{inside}");
    assert!(through > inside / 50, "the relief reaches behind the plane somewhere: {through} of {inside}");
    assert!(through < inside * 19 / 20, "and not everywhere: {through} of {inside}");
    // Pixels whose two depths are within rounding of each other may go either way.
    assert!(wrong <= inside / 100, "{wrong} of {inside} pixels disagree with the CPU's depths");
    assert_eq!(flat_through, 0, "without the offset the flat top surface hides the plane");
    // The offset depth read back agrees with the CPU's where the wall shows.
    let mut far = 0;
    for y in 0..H {
        for x in 0..W {
            if wall_only.mask.get(x, y) && !plane_only.mask.get(x, y) {
                let d = (offset.view_depth.get(x, y) - wall_only.view_depth.get(x, y)).abs();
                far += (d > 0.01 * relief) as usize;
            }
        }
    }
    assert!(far < 50, "{far} pixels' offset depths differ from the CPU's by more than 1 % of the relief");
}
