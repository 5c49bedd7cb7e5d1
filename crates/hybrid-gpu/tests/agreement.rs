//! Each stage of the GPU deferred frame against the same stage of the CPU's
//! (`deferred::frame::render`), on every built-in scene at 160×90 (shadow maps of 256
//! texels). Both frames are rendered once per scene and shared by the tests.
//!
//! The GPU computes the CPU's operations in f32 (the CPU rasterizer sets up in f64), with
//! the GPU's own fill rule and transcendental functions; the bounds below say what that
//! allows and why.

mod common;

use glam::Vec3;
use renderlab_core::Image;
use renderlab_hybrid::deferred::{direct_lighting, render, PreparedScene, RasterFrame, Unshadowed};
use renderlab_hybrid_gpu::{GpuDeferred, GpuRasterFrame};
use renderlab_scene::procedural::{self, RELIEF_TEXTURE_SIZE};
use std::sync::OnceLock;

const W: u32 = 160;
const H: u32 = 90;

/// One scene's frames.
struct Frames {
    name: &'static str,
    /// Pixel footprint per unit of view distance: `2 tan(fov/2) / height`.
    footprint: f32,
    eye: Vec3,
    cpu: RasterFrame,
    gpu: GpuRasterFrame,
    /// The direct term without shadows, CPU and GPU.
    unshadowed: (Vec<Vec3>, Vec<Vec3>),
}

/// Every built-in scene's frames, or `None` without an adapter (skipped, see `common`).
fn frames() -> Option<&'static [Frames]> {
    static FRAMES: OnceLock<Option<Vec<Frames>>> = OnceLock::new();
    FRAMES
        .get_or_init(|| {
            let ctx = common::context()?;
            let settings = common::settings();
            let frames = procedural::names()
                .into_iter()
                .map(|name| {
                    let (scene, camera) = common::scene(name, W, H);
                    let prepared = PreparedScene::new(&scene);
                    let cpu = render(&prepared, &camera, &settings).unwrap();
                    let mut gpu = GpuDeferred::new(&ctx, &prepared, &settings).unwrap();
                    let frame = gpu.render(&camera).unwrap();
                    gpu.set_shadows(false);
                    let gpu_unshadowed = gpu.render(&camera).unwrap().terms.direct;
                    let cpu_unshadowed =
                        direct_lighting(&scene, &cpu.geometry.gbuffer, &Unshadowed, settings.area_samples);
                    Frames {
                        name,
                        footprint: 2.0 * (camera.fov_y_deg.to_radians() * 0.5).tan() / H as f32,
                        eye: camera.position,
                        cpu,
                        gpu: frame,
                        unshadowed: (cpu_unshadowed, gpu_unshadowed),
                    }
                })
                .collect();
            Some(frames)
        })
        .as_deref()
}

/// At most this fraction of pixels may see a different surface (or none): the GPU's
/// rasterizer snaps vertices to 1/256 pixel and applies its own fill rule, the CPU's its
/// fixed-point one, so only pixels whose centre lies within that snapping of an edge can
/// differ — a thin band along silhouettes and shared edges.
const COVERAGE_FRACTION: f64 = 0.002;

#[test]
fn the_g_buffer_sees_the_same_surfaces_at_the_same_points() {
    let Some(frames) = frames() else { return };
    for f in frames {
        let g = &f.cpu.geometry;
        let n = g.gbuffer.opaque.len();
        let mut differ = 0usize;
        let mut same = 0usize;
        for i in 0..n {
            if !same_surface(f, i) {
                differ += 1;
                continue;
            }
            let (Some(a), Some(b)) = (&g.gbuffer.opaque[i], &f.gpu.gbuffer[i]) else { continue };
            same += 1;
            // The same triangle at the same pixel centre: the points differ by the f32
            // rounding of a ray–plane intersection, well under 1/20 of the pixel's footprint
            // on the surface (grazing surfaces stretch it, hence the cosine).
            let d = (a.position - f.eye).length();
            let cos = a.geometric_normal.dot((f.eye - a.position).normalize()).abs().max(0.05);
            let bound = 0.05 * f.footprint * d / cos;
            assert!(
                (a.position - b.position).length() <= bound,
                "{}: pixel {i} at {} vs {} (bound {bound})",
                f.name,
                a.position,
                b.position
            );
            // Texture coordinates follow the points (bounded absolutely: the built-in
            // scenes' coordinates stay below 100). A texture moves by at most its value range
            // per texel, so the bilinear lookups move by at most `|Δuv| · size` (the built-in
            // textures are RELIEF_TEXTURE_SIZE square): base colour by that, a mapped normal
            // by twice that (its components span [-1, 1]), beside the rounding.
            let duv = (a.uv - b.uv).length();
            assert!(duv < 1e-3, "{}: pixel {i} uv {} vs {}", f.name, a.uv, b.uv);
            let texels = duv * RELIEF_TEXTURE_SIZE as f32;
            let dn = (a.normal - b.normal).length();
            assert!(dn < 1e-3 + 2.0 * texels, "{}: pixel {i} normal {} vs {}", f.name, a.normal, b.normal);
            // The geometric normal is stored octahedron-encoded in 16-bit snorms: steps of 2/32767.
            assert!((a.geometric_normal - b.geometric_normal).length() < 2e-4, "{}: pixel {i}", f.name);
            let dc = (a.base_color - b.base_color).abs().max_element();
            assert!(dc < 1e-4 + texels, "{}: pixel {i} base {} vs {}", f.name, a.base_color, b.base_color);
            assert!((a.roughness - b.roughness).abs() < 1e-3 && (a.metallic - b.metallic).abs() < 1e-3);
            assert_eq!(
                (a.material, a.front_face, a.ior, a.transmission),
                (b.material, b.front_face, b.ior, b.transmission)
            );
            assert_eq!(a.emissive, b.emissive, "{}: pixel {i}", f.name);
        }
        assert!(
            differ as f64 <= COVERAGE_FRACTION * n as f64,
            "{}: {differ} of {n} pixels see another surface",
            f.name
        );
        assert!(same > n / 2, "{}: only {same} pixels compared", f.name);
    }
}

#[test]
fn the_translucent_layers_are_the_same_surfaces_in_the_same_order() {
    let Some(frames) = frames() else { return };
    for f in frames {
        let cpu = &f.cpu.geometry.translucent_layers;
        let gpu = &f.gpu.translucent_layers;
        assert_eq!(cpu.len(), gpu.len());
        let mut differ = 0usize;
        for (a, b) in cpu.iter().zip(gpu) {
            match (a, b) {
                (Some(a), Some(b)) if a.material == b.material && a.front_face == b.front_face => {
                    // Within one pixel's footprint: the layer's surface is the same one (the
                    // G-buffer test bounds the points themselves more tightly).
                    let d = (a.position - f.eye).length();
                    assert!((a.position - b.position).length() <= f.footprint * d, "{}", f.name);
                }
                (None, None) => {}
                _ => differ += 1,
            }
        }
        assert!(
            differ as f64 <= COVERAGE_FRACTION * cpu.len() as f64,
            "{}: {differ} layer entries differ",
            f.name
        );
    }
}

/// Whether both renderers see the same triangle at pixel `i`.
fn same_surface(f: &Frames, i: usize) -> bool {
    f.cpu.geometry.visibility[i].map(|v| (v.instance, v.triangle)) == f.gpu.visibility[i]
}

/// PSNR of `test` against `reference` over the pixels where both renderers see the same
/// triangle: a pixel on an edge that the two rasterizers give to different surfaces (at most
/// [`COVERAGE_FRACTION`] of them, bounded by the G-buffer test) is a coverage difference, not
/// a lighting one, and one such pixel on a bright edge of a dark frame costs 10 dB.
fn psnr_same_surface(f: &Frames, test: &[Vec3], reference: &[Vec3]) -> f64 {
    let same = Image::from_fn(W, H, |x, y| same_surface(f, (y * W + x) as usize));
    let img = |v: &[Vec3]| Image::from_fn(W, H, |x, y| v[(y * W + x) as usize]);
    renderlab_measure::metrics::psnr(&img(test), &img(reference), Some(&same))
}

#[test]
fn direct_light_agrees_without_and_with_the_shadow_maps() {
    let Some(frames) = frames() else { return };
    for f in frames {
        // Unshadowed, every term is the same arithmetic on the same shading points: only
        // rounding differs (tens of dB above what a viewer or the stage comparisons see).
        let (cpu, gpu) = &f.unshadowed;
        let p = psnr_same_surface(f, gpu, cpu);
        assert!(p >= 60.0, "{}: unshadowed direct light PSNR {p:.1} dB", f.name);
        // With the maps: the same maps texel for texel where the rasterizers agree; a texel
        // that flips on an edge moves one PCF tap (1/9 of a light) at a few pixels.
        let p = psnr_same_surface(f, &f.gpu.terms.direct, &f.cpu.terms.direct);
        assert!(p >= 50.0, "{}: shadowed direct light PSNR {p:.1} dB", f.name);
        // And the maps do shadow: the shadowed term is not the unshadowed one.
        let shadowed =
            f.gpu.terms.direct.iter().zip(gpu).filter(|(s, u)| (**s - **u).max_element() < -1e-3).count();
        assert!(shadowed > 0, "{}: no pixel is shadowed", f.name);
    }
}

#[test]
fn ambient_ssao_and_reflections_agree() {
    let Some(frames) = frames() else { return };
    for f in frames {
        let (c, g) = (&f.cpu.terms, &f.gpu.terms);
        let p = common::psnr(&g.diffuse_indirect, &c.diffuse_indirect, W, H);
        assert!(p >= 60.0, "{}: ambient PSNR {p:.1} dB", f.name);
        // SSAO counts samples: a sample whose depth test flips changes AO by 1/16 at one
        // pixel; the mean difference stays far below that.
        let n = c.ambient_occlusion.len() as f32;
        let mean =
            c.ambient_occlusion.iter().zip(&g.ambient_occlusion).map(|(a, b)| (a - b).abs()).sum::<f32>() / n;
        assert!(mean < 1e-3, "{}: SSAO mean difference {mean}", f.name);
        // SSR: a march that lands one pixel over reflects a neighbour.
        let p = common::psnr(&g.specular_indirect, &c.specular_indirect, W, H);
        assert!(p >= 50.0, "{}: reflections PSNR {p:.1} dB", f.name);
    }
}

#[test]
fn the_final_frame_and_its_tone_mapping_agree() {
    let Some(frames) = frames() else { return };
    let settings = common::settings();
    for f in frames {
        let p = psnr_same_surface(f, &f.gpu.hdr, &f.cpu.hdr);
        assert!(p >= 50.0, "{}: final frame PSNR {p:.1} dB", f.name);
        // The same curve and encoding; `pow` on the device may round a value sitting on a
        // code boundary the other way: one code, at a few channels.
        // Over the pixels where both see the same triangle, as the PSNR above.
        let cpu = f.cpu.to_srgb8(&settings);
        let mut off = 0usize;
        for (i, (a, b)) in cpu.pixels().iter().zip(f.gpu.srgb.pixels()).enumerate() {
            if !same_surface(f, i) {
                continue;
            }
            for k in 0..3 {
                let d = (a[k] as i32 - b[k] as i32).abs();
                assert!(d <= 8, "{}: a channel {} vs {}", f.name, a[k], b[k]);
                off += (d > 1) as usize;
            }
        }
        assert!(
            off as f64 <= 0.002 * 3.0 * (W * H) as f64,
            "{}: {off} channels more than one code apart",
            f.name
        );
    }
}
