//! The GPU renderer against the CPU renderer: for every technique with a shader, at the
//! thesis's four view angles, the GPU image against the CPU image of the same frame (PSNR and
//! FLIP over the pixels both cover), and the GPU's per-pixel UV against the CPU's and against
//! the exact reference's, in texels of the depth map.
//!
//! Without an adapter these tests fail with a clear message when `CI` is set and report
//! themselves skipped otherwise. The frames are small (320 × 200) because in CI the GPU is
//! lavapipe, a CPU.
//!
//! # The bounds, and why
//!
//! Both renderers run the same arithmetic on the same maps; they differ in:
//! - the sampler: Vulkan's bilinear filtering computes its weights with `subTexelPrecisionBits`
//!   fractional bits (4 at least, 8 on most GPUs), so a bilinear fetch may differ from the
//!   CPU's f32 weights by up to 2⁻⁹ of the difference between neighbouring texels, and the
//!   blend between mip levels has `mipmapPrecisionBits` (4 to 8). Lavapipe filters 32-bit
//!   float textures in full f32, so there the difference is rounding alone;
//! - f32 against f64: the CPU rasterizer solves UV and its Jacobian in f64, the GPU in f32
//!   (relative error ~10⁻⁷: 10⁻⁴ texel on a 256² map tiled four times);
//! - transcendental functions (`log2` for the LOD, `pow` for adaptive POM's angle factor):
//!   a few ulp on a GPU, not correctly rounded;
//! - coverage: both rasterizers sample pixel centres with the top-left rule, but the GPU
//!   snaps f32 vertices to its own sub-pixel grid, so pixels on an edge may differ.
//!
//! Smooth results (basic, normal, parallax, POM, adaptive POM, and relief mapping, whose
//! bisection only goes astray where its midpoint lies within the depth error of the surface,
//! i.e. next to the true hit) move by a fraction of the sampler's error: with 8-bit weights an
//! albedo fetch is off by at most 2⁻⁹ of a texel difference (≤ 0.002, RMS far less), which is
//! ≥ 54 dB even if every pixel had it, so 45 dB (and at most 1 % of pixels more than ¼ texel
//! from the CPU's UV) leaves room for the few pixels where POM's march takes a different
//! layer at an occluding edge. A march that ends on a layer without interpolating (steep
//! parallax) turns a depth difference of 2⁻⁹ of a texel step into a whole layer step wherever
//! a layer boundary lies that close to the depth map: about ε·n of the pixels for n layers and
//! a depth error ε (0.1 %–2 % with 8-bit weights), each as wrong as the step's colour change,
//! so its bounds are 30 dB and 5 % of pixels beyond ¼ texel. FLIP's mean follows the same
//! split (0.005 and 0.02).
//!
//! Cone stepping is smooth in the same sense. Its cone ratio is read with `textureLoad` (no
//! sampler arithmetic), so a step differs only where the ray's UV lies within rounding of a
//! cone-map texel border (another cell's ratio) or its depth within the sampler's error of
//! the surface (the bracket closes one step earlier or later); either way both renderers
//! bracket the same crossing and the refinement shrinks the difference to the final
//! bracket's width, step/2^REFINE_STEPS for bisection, the 0.05-texel tolerance for the
//! secant. Newton-finished cone stepping reads the packed map with `textureLoad` and
//! interpolates its 16-bit integers in the shader with the CPU's operations: no sampler
//! precision enters, only f32 rounding (FMA contraction, a GPU's division), and a stopping
//! test that flips on rounding moves the hit by less than its tolerance (¼ texel). Both get
//! the smooth bounds.
//!
//! Soft self-shadowing (`pom-shadow`) multiplies the light by `1 − 25·occlusion`, so the
//! sampler's depth error reaches the image 25-fold: with 8-bit weights and the bricks' depth
//! steps between neighbouring texels (RMS 0.09, at most 0.52), the shadow term is off by
//! 25·2⁻⁹·0.09/√3 ≈ 0.003 RMS and 0.025 at worst, i.e. about 50 dB in the image; its bounds
//! are 40 dB and a FLIP mean of 0.01, a factor 3 of room for steeper maps and the march's
//! layer flips at occluding edges. Its UV is POM's, with POM's bound.
//!
//! Horizon self-shadowing (`pom-horizon`) is the visible fraction of a sun-sized disc
//! (radius ρ = 0.00466 rad) above the marched horizon α*, which changes by at most
//! 2/(π·ρ) ≈ 137 per radian of α*; a depth error δ at a sample r texel steps away moves
//! tan α* by δ·height_scale·c/r (c texel steps per UV unit; height_scale·c = 12.8 on the
//! 256² bricks along an axis; r ≥ ½). Only pixels whose horizon lies within ρ of the
//! light's elevation (the penumbra, a thin band along shadow edges) are sensitive at all.
//! With 8-bit weights such a pixel may flip entirely; on lavapipe (full-precision filtering)
//! δ is rounding alone and the shadow term moves by ~10⁻⁴. It takes the shadowed bounds.
//!
//! UV: the median difference between the GPU's and the CPU's UV must be tiny (0.01 texel:
//! f32 and sampler rounding), and the mean error against the exact reference must be the CPU
//! technique's own within 0.05 texel + 5 %: a shader bug (a wrong sign, a missing clamp, a
//! wrong step) moves that mean by whole texels.
//!
//! On lavapipe (full-precision filtering) the agreement is far inside these bounds; the
//! measured figures per technique and angle are in BENCHMARKS.md.

mod common;

use common::context;
use glam::Vec2;
use renderlab_core::{Camera, Image, Scene};
use renderlab_gpu::{GpuFrame, ReliefPipeline, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene, room_camera, thesis_room};
use renderlab_measure::metrics::{flip, flip_masked_mean, psnr};
use renderlab_raster::rasterize;
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::render::patch::median_world_per_uv;
use renderlab_relief::render::{render, render_reference};
use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_relief::{
    patches_from_scene, FrameInput, Kernel, Map, PatchInfo, ReliefMaterial, Shading, Technique,
};
use renderlab_texture::materials;

/// Frame size: small, since CI's GPU is a CPU.
const WIDTH: u32 = 320;
const HEIGHT: u32 = 200;
/// Texture size of the bricks material.
const TEXTURE: u32 = 256;
/// The thesis's view angles.
const ANGLES: [f32; 4] = [0.0, 45.0, 60.0, 80.0];

/// How a GPU frame compares with the CPU frames of the same view.
#[derive(Debug)]
struct Agreement {
    /// Pixels covered by one renderer only.
    coverage_diff: usize,
    /// PSNR (dB, sRGB-encoded) of the GPU image against the CPU image, over pixels both cover.
    psnr: f64,
    /// Mean FLIP over those pixels.
    flip: f64,
    /// Median |GPU UV − CPU UV| in texels.
    uv_median: f32,
    /// Fraction of pixels whose GPU UV is more than a quarter texel from the CPU's.
    uv_far: f64,
    /// Mean texel error of the GPU UV against the exact reference.
    gpu_ref: f32,
    /// Mean texel error of the CPU UV against the exact reference.
    cpu_ref: f32,
    /// Median |GPU − CPU| pixel-depth offset (distance to the displaced hit), as a fraction of
    /// the relief's full depth in world units.
    depth_median: f32,
    /// Fraction of pixels whose offset depths differ by more than 1 % of the relief's depth.
    depth_far: f64,
}

fn compare(
    gpu: &GpuFrame,
    cpu: &renderlab_relief::Frame,
    reference: &renderlab_relief::Frame,
    texels: Vec2,
    relief_depth: f32,
) -> Agreement {
    let both = Image::from_fn(WIDTH, HEIGHT, |x, y| gpu.mask.get(x, y) && cpu.mask.get(x, y));
    let coverage_diff = (0..HEIGHT)
        .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
        .filter(|&(x, y)| gpu.mask.get(x, y) != cpu.mask.get(x, y))
        .count();
    let f = flip(&gpu.image, &cpu.image);
    let mut diffs = Vec::new();
    let mut depth_diffs = Vec::new();
    let (mut gpu_ref, mut cpu_ref) = (0.0f64, 0.0f64);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            if both.get(x, y) {
                depth_diffs.push((gpu.view_depth.get(x, y) - cpu.view_depth.get(x, y)).abs() / relief_depth);
                let r = reference.uv.get(x, y);
                diffs.push(((gpu.uv.get(x, y) - cpu.uv.get(x, y)) * texels).length());
                gpu_ref += ((gpu.uv.get(x, y) - r) * texels).length() as f64;
                cpu_ref += ((cpu.uv.get(x, y) - r) * texels).length() as f64;
            }
        }
    }
    let n = diffs.len().max(1);
    let uv_far = diffs.iter().filter(|&&d| d > 0.25).count() as f64 / n as f64;
    diffs.sort_by(f32::total_cmp);
    let depth_far = depth_diffs.iter().filter(|&&d| d > 0.01 || d.is_nan()).count() as f64 / n as f64;
    depth_diffs.sort_by(f32::total_cmp);
    Agreement {
        depth_median: depth_diffs.get(n / 2).copied().unwrap_or(0.0),
        depth_far,
        coverage_diff,
        psnr: psnr(&gpu.image, &cpu.image, Some(&both)),
        flip: flip_masked_mean(&f, Some(&both)),
        uv_median: diffs.get(n / 2).copied().unwrap_or(0.0),
        uv_far,
        gpu_ref: (gpu_ref / n as f64) as f32,
        cpu_ref: (cpu_ref / n as f64) as f32,
    }
}

/// The bounds for a technique (see the module docs).
struct Bounds {
    psnr_db: f64,
    flip: f64,
    far_fraction: f64,
}

/// A march that stops on a layer (steep parallax) flips whole layer steps; soft shadows
/// amplify the depth error 25-fold; every other technique's result moves smoothly with the
/// sampler's rounding.
fn bounds(t: Technique) -> Bounds {
    if t.family() == "steep" {
        Bounds { psnr_db: 30.0, flip: 0.02, far_fraction: 0.05 }
    } else if t.shading() == Shading::LitShadowed {
        Bounds { psnr_db: 40.0, flip: 0.01, far_fraction: 0.01 }
    } else {
        Bounds { psnr_db: 45.0, flip: 0.005, far_fraction: 0.01 }
    }
}

/// Renders `name` on both renderers at every angle of the benchmark and checks the bounds.
fn check(name: &str) {
    let bricks = materials::material("bricks", TEXTURE).expect("built-in material");
    let scene = benchmark_scene(bricks);
    let cameras: Vec<(String, Camera)> =
        ANGLES.iter().map(|&a| (format!("{a:>3}°"), benchmark_camera(a, WIDTH, HEIGHT))).collect();
    check_views(name, &scene, &cameras);
}

/// Renders `name` of `scene` on both renderers from every camera and checks the bounds.
fn check_views(name: &str, scene: &Scene, cameras: &[(String, Camera)]) {
    let Some(ctx) = context() else { return };
    let technique = Technique::parse(name).expect("a registry technique");
    // The cone map only where the technique reads it (it takes a while to build).
    let cone = technique.descriptor().needs.contains(&Map::Cone);
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), cone)).collect();
    let texels = Vec2::new(mats[0].height.width() as f32, mats[0].height.height() as f32);
    let mut gpu = ReliefRenderer::new(&ctx, scene, &mats).expect("scene uploads");
    let b = bounds(technique);
    let mut failures = Vec::new();
    for (view, camera) in cameras {
        let g = rasterize(scene, camera);
        let patches = patches_from_scene(scene, g.pixels());
        let input = FrameInput::new(WIDTH, HEIGHT, g.pixels()).with_patches(&patches);
        let relief_depth = relief_depth(&patches, &mats);
        let cpu = render(input, &mats, technique, Kernel::Scalar, scene.lighting, scene.background, false)
            .expect("CPU render");
        let reference = render_reference(input, &mats, technique, scene.lighting, scene.background);
        let mut frames: Vec<GpuFrame> = Vec::new();
        for pipeline in ReliefPipeline::ALL {
            gpu.set_pipeline(pipeline).unwrap_or_else(|e| panic!("{name}: {e}"));
            let frame = gpu.render(camera, technique).unwrap_or_else(|e| panic!("{name} ({pipeline}): {e}"));
            let a = compare(&frame, &cpu, &reference, texels, relief_depth);
            if let Some(dir) = std::env::var_os("RENDERLAB_GPU_TEST_IMAGES") {
                // Both images side by side for a look, when asked for.
                let stem = format!("{}_{}", name.replace(':', "-"), view.trim().trim_end_matches('°'));
                let dir = std::path::Path::new(&dir);
                renderlab_core::io::save_color(dir.join(format!("{stem}_{pipeline}.png")), &frame.image)
                    .expect("writable");
                renderlab_core::io::save_color(dir.join(format!("{stem}_cpu.png")), &cpu.image)
                    .expect("writable");
            }
            println!(
                "{name:>13} {view} {pipeline:>8}: coverage diff {:>3} px, PSNR {:6.2} dB, FLIP {:.5}, UV |gpu−cpu| median {:.5} texel, >¼ texel {:.3} %, error vs exact: gpu {:.4} cpu {:.4} texel, offset depth |gpu−cpu| median {:.2e} of the relief, >1 % {:.3} %",
                a.coverage_diff, a.psnr, a.flip, a.uv_median, a.uv_far * 100.0, a.gpu_ref, a.cpu_ref, a.depth_median, a.depth_far * 100.0
            );
            let what = format!("{view} ({pipeline})");
            check_bounds(name, &what, &a, &b, &cpu, &mut failures);
            frames.push(frame);
        }
        // The compute frame against the fragment frame: the same shading of the same surface,
        // so the bounds against the CPU hold between them too.
        let a = compare(&frames[1], &frames_as_cpu(&frames[0]), &reference, texels, relief_depth);
        println!(
            "{name:>13} {view}  compute vs fragment: coverage diff {:>3} px, PSNR {:6.2} dB, FLIP {:.5}, UV median {:.5} texel, >¼ texel {:.3} %",
            a.coverage_diff, a.psnr, a.flip, a.uv_median, a.uv_far * 100.0
        );
        check_bounds(name, &format!("{view} (compute vs fragment)"), &a, &b, &cpu, &mut failures);
    }
    assert!(failures.is_empty(), "GPU and CPU disagree:\n{}", failures.join("\n"));
}

/// Adds to `failures` each bound of `b` that `a` (a GPU frame against `cpu`) breaks.
fn check_bounds(
    name: &str,
    view: &str,
    a: &Agreement,
    b: &Bounds,
    cpu: &renderlab_relief::Frame,
    failures: &mut Vec<String>,
) {
    let covered = cpu.mask.pixels().iter().filter(|&&m| m).count();
    let mut fail = |what: String| failures.push(format!("{name} at {view}: {what}"));
    if a.coverage_diff > (covered / 500).max(8) {
        fail(format!("{} pixels covered by one renderer only", a.coverage_diff));
    }
    if a.psnr < b.psnr_db {
        fail(format!("PSNR {:.2} dB < {}", a.psnr, b.psnr_db));
    }
    if a.flip > b.flip {
        fail(format!("FLIP {:.4} > {}", a.flip, b.flip));
    }
    if a.uv_median > 0.01 {
        fail(format!("median UV difference {:.4} texel > 0.01", a.uv_median));
    }
    if a.uv_far > b.far_fraction {
        fail(format!("{:.2} % of pixels' UV differ by more than ¼ texel", a.uv_far * 100.0));
    }
    // Both sides compute the same distance from the same hit in f32 (the GPU's scale from
    // the triangle or the screen Jacobian, the CPU's from the mesh's areas: equal on the
    // scenes' uniformly mapped quads): the median differs by rounding, and only pixels whose
    // hit differs (the UV bound's pixels) may differ by more than 1 % of the relief's depth.
    if a.depth_median > 1e-3 {
        fail(format!("median offset-depth difference {:.2e} of the relief's depth > 1e-3", a.depth_median));
    }
    if a.depth_far > b.far_fraction {
        fail(format!(
            "{:.2} % of pixels' offset depths differ by more than 1 % of the relief",
            a.depth_far * 100.0
        ));
    }
    if (a.gpu_ref - a.cpu_ref).abs() > 0.05 + 0.05 * a.cpu_ref {
        fail(format!("UV error vs exact {:.4} texel on one side, {:.4} on the other", a.gpu_ref, a.cpu_ref));
    }
}

/// The relief's full depth in world units: the first material's depth scale (UV per unit
/// depth) times the median world units per UV of the covered pixels.
fn relief_depth(patches: &[PatchInfo], mats: &[ReliefMaterial]) -> f32 {
    mats[0].height_scale * median_world_per_uv(patches)
}

/// A GPU frame in the CPU frame's form, to compare two GPU frames with [`compare`].
fn frames_as_cpu(f: &GpuFrame) -> renderlab_relief::Frame {
    renderlab_relief::Frame {
        image: f.image.clone(),
        uv: f.uv.clone(),
        view_depth: f.view_depth.clone(),
        layers: f.layers.clone(),
        mask: f.mask.clone(),
        depth: Image::new(f.image.width(), f.image.height(), 0.0),
        fetches: 0,
    }
}

/// One test per setting, and [`TESTED`], the list of them that
/// `every_registry_technique_is_tested` holds against the registry.
macro_rules! agreement_tests {
    ($($test:ident: $name:literal,)*) => {
        /// Every technique setting with an agreement test.
        const TESTED: &[&str] = &[$($name,)*];
        $(
            #[test]
            fn $test() {
                check($name);
            }
        )*
    };
}

agreement_tests! {
    basic_agrees: "basic",
    normal_agrees: "normal",
    parallax_agrees: "parallax",
    steep_agrees: "steep:32",
    pom_agrees: "pom:32",
    adaptive_pom_agrees: "adaptive:4:32",
    relief_agrees: "relief:16:6",
    adaptive_relief_agrees: "adaptive-relief",
    cone_binary_agrees: "cone",
    cone_secant_agrees: "cone:24:3:secant",
    cone_newton_agrees: "cone-newton",
    leap_agrees: "leap",
    pom_shadow_agrees: "pom-shadow",
    pom_horizon_agrees: "pom-horizon:32:32",
    silhouette_agrees: "silhouette:32",
    pom_lod_agrees: "pom-lod",
}

/// Every technique of the registry has a shader and an agreement test here: a technique added
/// without its WGSL twin, or without a test of it, fails this.
#[test]
fn every_registry_technique_is_tested() {
    for d in DESCRIPTORS {
        let t = Technique::parse(d.name).expect("a registry technique");
        assert!(t.wgsl().is_some(), "technique '{}' has no GPU shader", d.name);
        assert!(
            TESTED.iter().any(|n| Technique::parse(n).is_ok_and(|t| t.descriptor().name == d.name)),
            "technique '{}' has no agreement test",
            d.name
        );
    }
}

/// Horizon shadows at grazing light (5° above the wall, across the bricks' courses), where
/// their march takes its long geometric steps: the same bounds.
#[test]
fn pom_horizon_agrees_at_grazing_light() {
    let bricks = materials::material("bricks", TEXTURE).expect("built-in material");
    let mut scene = benchmark_scene(bricks);
    let (e, a) = (5f32.to_radians(), 30f32.to_radians());
    scene.light.to_light = glam::Vec3::new(e.cos() * a.cos(), -e.cos() * a.sin(), e.sin());
    let cameras: Vec<(String, Camera)> = [0.0, 45.0]
        .iter()
        .map(|&a| (format!("{a:>3}° light 5°"), benchmark_camera(a, WIDTH, HEIGHT)))
        .collect();
    check_views("pom-horizon:32:16", &scene, &cameras);
}

/// The silhouette technique in the room: rays that leave a wall's UV rectangle at the room's
/// edges miss on the CPU (its patches from the meshes) and on both GPU pipelines (the
/// per-object rectangles in `object_patches`), at the same pixels within the coverage bound.
#[test]
fn room_silhouette_agrees() {
    let scene = thesis_room(TEXTURE).expect("built-in room");
    let camera = room_camera(WIDTH, HEIGHT);
    // The test means something only if the room's edges cut some rays.
    let g = rasterize(&scene, &camera);
    let patches = patches_from_scene(&scene, g.pixels());
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    let input = FrameInput::new(WIDTH, HEIGHT, g.pixels()).with_patches(&patches);
    let t = Technique::parse("silhouette:32").unwrap();
    let cpu =
        render(input, &mats, t, Kernel::Scalar, scene.lighting, scene.background, false).expect("CPU render");
    let missed = g.pixels().iter().zip(cpu.mask.pixels()).filter(|(p, &m)| p.is_some() && !m).count();
    println!("silhouette:32 in the room: {missed} pixels miss at the walls' edges");
    assert!(missed > 20, "only {missed} rays left a wall's rectangle");
    check_views("silhouette:32", &scene, &[("room".to_string(), camera)]);
}

/// Several objects and materials, depth-tested against each other (the thesis's room; the
/// UV errors are in texels of its first material, all four being the same size).
#[test]
fn room_agrees() {
    let scene = thesis_room(TEXTURE).expect("built-in room");
    let cameras = [("room".to_string(), room_camera(WIDTH, HEIGHT))];
    check_views("adaptive:4:32", &scene, &cameras);
}
