//! Drawing into a caller's texture ([`ReliefRenderer::render_to_view_region`]): two passes
//! into the two halves of one texture give, pixel for pixel, the picture of one pass over the
//! whole frame, and a texture cleared with alpha 0 marks in alpha exactly the pixels that the
//! debug frame's mask calls covered.

mod common;

use common::context;
use renderlab_gpu::{read_rgba8, DisplayRegion, GpuContext, ReliefRenderer};
use renderlab_measure::fixtures::{benchmark_camera, benchmark_scene};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{ReliefMaterial, Technique};
use renderlab_texture::materials;

const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

fn target(ctx: &GpuContext, w: u32, h: u32) -> wgpu::Texture {
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("test display"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

#[test]
fn two_half_passes_make_the_whole_frame() {
    let Some(ctx) = context() else { return };
    let scene = benchmark_scene(materials::material("bricks", 64).expect("built-in material"));
    let mats: Vec<_> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let (w, h) = (161, 100);
    let camera = benchmark_camera(45.0, w, h);
    let (pom, basic) = (Technique::parse("pom:32").unwrap(), Technique::parse("basic").unwrap());
    let whole_tex = target(&ctx, w, h);
    let whole_view = whole_tex.create_view(&Default::default());
    let split_tex = target(&ctx, w, h);
    let split_view = split_tex.create_view(&Default::default());

    // The same technique in both halves: the whole frame, byte for byte (the scissor only
    // drops fragments; it changes none).
    r.render_to_view(&whole_view, FORMAT, &camera, pom).unwrap();
    let half = w / 2;
    let left = DisplayRegion { rect: [0, 0, half, h], clear_alpha: Some(1.0) };
    let right = DisplayRegion { rect: [half, 0, u32::MAX, h], clear_alpha: None };
    let ms_left = r.render_to_view_region(&split_view, FORMAT, &camera, pom, left).unwrap();
    let ms_right = r.render_to_view_region(&split_view, FORMAT, &camera, pom, right).unwrap();
    assert_eq!(ms_left.is_some(), ctx.report.timestamps);
    assert_eq!(ms_right.is_some(), ctx.report.timestamps);
    let whole = read_rgba8(&ctx, &whole_tex).unwrap();
    assert_eq!(read_rgba8(&ctx, &split_tex).unwrap(), whole, "pom in both halves differs from pom whole");

    // Another technique on the right: the left half is still pom's, the right half differs.
    r.render_to_view_region(&split_view, FORMAT, &camera, pom, left).unwrap();
    r.render_to_view_region(&split_view, FORMAT, &camera, basic, right).unwrap();
    let split = read_rgba8(&ctx, &split_tex).unwrap();
    let (mut same_left, mut diff_right) = (true, 0usize);
    for y in 0..h as usize {
        for x in 0..w as usize {
            let i = (y * w as usize + x) * 4;
            let equal = split[i..i + 4] == whole[i..i + 4];
            if x < half as usize {
                same_left &= equal;
            } else if !equal {
                diff_right += 1;
            }
        }
    }
    assert!(same_left, "the second pass changed the left half");
    let right_px = ((w - half) * h) as usize;
    assert!(
        diff_right * 4 > right_px,
        "basic on the right differs from pom in only {diff_right} of {right_px} px"
    );
}

#[test]
fn a_transparent_clear_marks_the_covered_pixels() {
    let Some(ctx) = context() else { return };
    let scene = benchmark_scene(materials::material("bricks", 64).expect("built-in material"));
    let mats: Vec<_> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &ComplexityParams::default(), false)).collect();
    let mut r = ReliefRenderer::new(&ctx, &scene, &mats).expect("scene uploads");
    let (w, h) = (120, 80);
    // At 80° the plane leaves part of the frame to the background.
    let camera = benchmark_camera(80.0, w, h);
    let t = Technique::parse("pom:16").unwrap();
    let tex = target(&ctx, w, h);
    let view = tex.create_view(&Default::default());
    let region = DisplayRegion { rect: [0, 0, w, h], clear_alpha: Some(0.0) };
    r.render_to_view_region(&view, FORMAT, &camera, t, region).unwrap();
    let px = read_rgba8(&ctx, &tex).unwrap();
    let mask = r.render(&camera, t).unwrap().mask;
    let covered = mask.pixels().iter().filter(|&&m| m).count();
    assert!(covered > 0 && covered < mask.pixels().len(), "the test needs both kinds of pixel ({covered})");
    for (i, &m) in mask.pixels().iter().enumerate() {
        assert_eq!(px[i * 4 + 3], if m { 255 } else { 0 }, "alpha of pixel {i}");
    }
}
