//! The GPU's texture filters against the CPU filters of the same name, on the texture lab's
//! test scenes (small frames: in CI the GPU is lavapipe, a CPU). Both filter the same texture
//! coordinates and Jacobians (the scene's exact mapping, computed on the CPU) from the same
//! pyramid, so the differences below are the filters' own.
//!
//! Without an adapter these tests fail with a clear message when `CI` is set and report
//! themselves skipped otherwise.
//!
//! # The bounds, and why
//!
//! The scenes' textures hold values in [0, 1], so a texel difference is at most 1.
//! - **Nearest** picks `⌊u·w⌋` as the CPU does; a GPU converts the coordinate to fixed point
//!   with `subTexelPrecisionBits` (≥ 4, usually 8) fractional bits, so a coordinate within
//!   2⁻⁹ texel of a texel border may pick the neighbour: about 2·2⁻⁸ < 1 % of pixels for
//!   coordinates spread evenly. Bound: every other pixel identical, at most 1 % different.
//! - **Bilinear** weighs the four texels with weights of the same precision: at most 2⁻⁹ of
//!   the texel difference per axis, so |Δ| ≤ 2⁻⁸ per pixel and channel.
//! - **Trilinear**: the level must agree (the CPU's rule is Vulkan's, `λ = log₂ max(ρx, ρy)`):
//!   |Δλ| ≤ 1/16, the resolution of the level fraction at the minimum `mipmapPrecisionBits`
//!   (4); it also holds lavapipe, which evaluates `log₂` piecewise linearly between powers of
//!   two (an error of at most ½·0.0861 = 0.043 level, reached where the mantissa is 1/ln 2 −
//!   1). The colour then moves by at most 1/16 of the largest difference between adjacent
//!   levels' bilinear values within ±1/16 of the CPU's level (trilinear is linear in λ
//!   between levels), plus the bilinear bound: checked pixel by pixel.
//! - **EWA** runs the CPU's operations in WGSL on exact texels (`textureLoad`: no sampler
//!   arithmetic), so only f32 rounding differs (fused multiply–adds, a GPU's `exp` and `sqrt`
//!   within a few ulp): a weight `2^(−y)` moves by a few ulp of its exponent (the CPU's short
//!   series is within 4·10⁻⁷ of `exp2`, the GPU's `exp2` within its own ulp), which moves the
//!   result by far less than 2⁻⁸; a level or span decision flips only where its
//!   quantity lies within rounding of the threshold. Bounds: PSNR ≥ 60 dB, and at most 0.1 %
//!   of pixels beyond 2⁻⁸.
//! - **Hardware anisotropic** filtering is implementation-defined: how many probes, where,
//!   weighted how (lavapipe's, Mesa's `lp_build_sample_aniso`, is in fact an EWA with a unit
//!   reconstruction circle on one level, taking its footprint from the quad's derivatives). So
//!   its PSNR against the CPU's `anisoN:box` (the GPU's textbook behaviour) is reported, not
//!   bounded; the sanity bounds only say that it filters the footprint at the right place:
//!   its image must be closer to the CPU's `anisoN:box` than the unfiltered nearest-texel
//!   image is, by at least 3 dB (a filter that ignored the footprint or sampled the wrong
//!   place would be no closer than unfiltered sampling), and its mean over the surface must
//!   be the CPU's within 0.005 (every normalised filter keeps a texture's mean over a region
//!   far larger than one footprint). The footprint comes from the 2×2 quad's derivatives,
//!   so pixels whose quad leaves the surface are left out.

mod common;

use common::context;
use glam::{Vec2, Vec3};
use renderlab_core::counter::NoCount;
use renderlab_core::Image;
use renderlab_gpu::{FilterRenderer, GpuError, GpuFilter};
use renderlab_measure::metrics::psnr;
use renderlab_texture::filter::{bilinear_level, lod};
use renderlab_texture::filter::{lab_filters, GpuForm, HardwareSampler, Levels};
use renderlab_texture::scene::{SceneKind, Surface, TestScene};
use renderlab_texture::{Bilinear, FilterSpec, Nearest, Texture, Trilinear};

/// Frame size: small, since CI's GPU is a CPU.
const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;

/// The bilinear weights' worst case on a GPU with 8-bit sub-texel precision (see the docs).
const WEIGHTS: f32 = 1.0 / 256.0;

/// The level's bound (see the docs).
const LEVEL: f32 = 1.0 / 16.0;

/// The scenes: the ground plane to the horizon with checks and with the zone plate, the
/// thesis's quad with checks and with the circuit board, a square tilted 70°.
fn scenes() -> Vec<SceneKind> {
    vec![
        SceneKind::Checkerboard,
        SceneKind::ZonePlate,
        SceneKind::ThesisQuad,
        SceneKind::ThesisCircuit,
        SceneKind::TiltedQuad(70.0),
    ]
}

/// One scene, its surface and the pixels that show it.
struct Case {
    scene: TestScene,
    surface: Surface,
    mask: Image<bool>,
}

impl Case {
    fn new(kind: SceneKind) -> Case {
        let scene = TestScene::new(kind, WIDTH, HEIGHT).expect("built-in scene");
        let surface = scene.surface();
        let mask = Image::from_fn(WIDTH, HEIGHT, |x, y| surface.pixels.get(x, y).hit);
        Case { scene, surface, mask }
    }

    fn name(&self) -> String {
        self.scene.kind.name()
    }

    /// The CPU's image through `spec`.
    fn cpu(&self, spec: &FilterSpec) -> Image<Vec3> {
        self.scene.render_spec(&self.surface, spec)
    }

    /// Surface pixels whose whole 2×2 quad shows the surface.
    fn quads(&self) -> Image<bool> {
        Image::from_fn(WIDTH, HEIGHT, |x, y| {
            let (qx, qy) = (x & !1, y & !1);
            (0..2).all(|i| (0..2).all(|j| self.mask.get((qx + i).min(WIDTH - 1), (qy + j).min(HEIGHT - 1))))
        })
    }

    /// Writes both images for a look, when `RENDERLAB_GPU_TEST_IMAGES` names a folder.
    fn save(&self, what: &str, gpu: &Image<Vec3>, cpu: &Image<Vec3>) {
        if let Some(dir) = std::env::var_os("RENDERLAB_GPU_TEST_IMAGES") {
            let dir = std::path::Path::new(&dir);
            let stem = format!("filter_{}_{}", self.name(), what.replace(':', "-"));
            renderlab_core::io::save_color(dir.join(format!("{stem}_gpu.png")), gpu).expect("writable");
            renderlab_core::io::save_color(dir.join(format!("{stem}_cpu.png")), cpu).expect("writable");
        }
    }
}

/// Largest per-channel difference at each pixel of `mask`.
fn differences(a: &Image<Vec3>, b: &Image<Vec3>, mask: &Image<bool>) -> Vec<(u32, u32, f32)> {
    let mut out = Vec::new();
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            if mask.get(x, y) {
                out.push((x, y, (a.get(x, y) - b.get(x, y)).abs().max_element()));
            }
        }
    }
    out
}

/// Mean of the red channel over `mask`.
fn mean(img: &Image<Vec3>, mask: &Image<bool>) -> f64 {
    let v: Vec<f64> =
        img.pixels().iter().zip(mask.pixels()).filter(|(_, &m)| m).map(|(c, _)| c.x as f64).collect();
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// The GPU twin of the catalogue filter named `name`.
fn gpu_twin(name: &str) -> GpuFilter {
    GpuFilter::from_spec(&name.parse().expect("a catalogue filter")).expect("a GPU twin")
}

/// The GPU filter renderer of `case`.
fn gpu_filter<'a>(ctx: &'a renderlab_gpu::GpuContext, case: &Case) -> FilterRenderer<'a> {
    FilterRenderer::new(ctx, &case.scene, &case.surface).expect("scene uploads")
}

#[test]
fn nearest_and_bilinear_agree() {
    let Some(ctx) = context() else { return };
    let mut failures = Vec::new();
    for kind in scenes() {
        let case = Case::new(kind);
        let mut r = gpu_filter(&ctx, &case);
        for spec in [FilterSpec::Nearest(Nearest), FilterSpec::Bilinear(Bilinear)] {
            let g = GpuFilter::from_spec(&spec).expect("a GPU twin");
            let gpu = r.render(&g).unwrap_or_else(|e| panic!("{}: {e}", g.name()));
            let cpu = case.cpu(&spec);
            case.save(&g.name(), &gpu, &cpu);
            let d = differences(&gpu, &cpu, &case.mask);
            let max = d.iter().map(|t| t.2).fold(0.0, f32::max);
            let differ = d.iter().filter(|t| t.2 > 1e-6).count() as f64 / d.len() as f64;
            println!(
                "{:>20} {:>8}: PSNR {:7.2} dB, max |Δ| {max:.2e}, {:.3} % of pixels differ",
                case.name(),
                g.name(),
                psnr(&gpu, &cpu, Some(&case.mask)),
                differ * 100.0
            );
            let ok = match spec {
                FilterSpec::Nearest(_) => differ <= 0.01,
                _ => max <= WEIGHTS + 1e-6,
            };
            if !ok {
                failures.push(format!(
                    "{} {}: max |Δ| {max}, {:.3} % differ",
                    case.name(),
                    g.name(),
                    differ * 100.0
                ));
            }
        }
    }
    assert!(failures.is_empty(), "GPU and CPU filters disagree:\n{}", failures.join("\n"));
}

/// How far trilinear filtering at `uv` may move when its level moves by `LEVEL` from `l`: the
/// largest difference between adjacent levels' bilinear values over the levels touched.
fn level_sensitivity(tex: &Texture, uv: Vec2, l: f32) -> f32 {
    let top = (tex.level_count() - 1) as f32;
    let (lo, hi) = ((l - LEVEL).max(0.0).floor() as usize, (l + LEVEL).min(top).ceil() as usize);
    (lo..hi)
        .map(|i| {
            let a = bilinear_level(tex, i, uv, &mut NoCount);
            let b = bilinear_level(tex, i + 1, uv, &mut NoCount);
            (b - a).truncate().abs().max_element()
        })
        .fold(0.0, f32::max)
}

#[test]
fn trilinear_chooses_the_cpu_level_and_agrees() {
    let Some(ctx) = context() else { return };
    let mut failures = Vec::new();
    for kind in scenes() {
        let case = Case::new(kind);
        let mut r = gpu_filter(&ctx, &case);
        let levels = r.levels().expect("level probe");
        let gpu = r.render(&gpu_twin("trilinear")).expect("trilinear");
        let cpu = case.cpu(&FilterSpec::Trilinear(Trilinear));
        case.save("trilinear", &gpu, &cpu);
        let tex = &case.scene.texture;
        let (mut level_max, mut level_sum, mut beyond) = (0.0f32, 0.0f64, 0usize);
        let d = differences(&gpu, &cpu, &case.mask);
        for &(x, y, diff) in &d {
            let p = case.surface.pixels.get(x, y);
            let l = lod(tex, p.duv_dx, p.duv_dy);
            let dl = (levels.get(x, y) - l).abs();
            level_max = level_max.max(dl);
            level_sum += dl as f64;
            if diff > LEVEL * level_sensitivity(tex, p.uv, l) + WEIGHTS + 1e-6 {
                beyond += 1;
            }
        }
        println!(
            "{:>20} trilinear: PSNR {:6.2} dB, max |Δ| {:.4}, level |Δλ| max {level_max:.4} mean {:.4}, {beyond} pixels beyond the bound",
            case.name(),
            psnr(&gpu, &cpu, Some(&case.mask)),
            d.iter().map(|t| t.2).fold(0.0, f32::max),
            level_sum / d.len() as f64
        );
        if level_max > LEVEL {
            failures.push(format!("{}: level differs by {level_max}", case.name()));
        }
        if beyond > 0 {
            failures.push(format!("{}: {beyond} pixels beyond the level's bound", case.name()));
        }
    }
    assert!(failures.is_empty(), "GPU and CPU trilinear disagree:\n{}", failures.join("\n"));
}

#[test]
fn ewa_agrees() {
    let Some(ctx) = context() else { return };
    let mut failures = Vec::new();
    let spec: FilterSpec = "ewa".parse().expect("EWA");
    for kind in scenes() {
        let case = Case::new(kind);
        let mut r = gpu_filter(&ctx, &case);
        let g = GpuFilter::from_spec(&spec).expect("a GPU twin");
        let gpu = r.render(&g).expect("EWA");
        let cpu = case.cpu(&spec);
        case.save("ewa", &gpu, &cpu);
        let d = differences(&gpu, &cpu, &case.mask);
        let far = d.iter().filter(|t| t.2 > WEIGHTS).count() as f64 / d.len() as f64;
        let p = psnr(&gpu, &cpu, Some(&case.mask));
        println!(
            "{:>20} ewa: PSNR {p:7.2} dB, max |Δ| {:.2e}, {:.3} % beyond 2⁻⁸",
            case.name(),
            d.iter().map(|t| t.2).fold(0.0, f32::max),
            far * 100.0
        );
        if p < 60.0 || far > 0.001 {
            failures.push(format!("{}: PSNR {p:.2} dB, {:.3} % beyond 2⁻⁸", case.name(), far * 100.0));
        }
    }
    assert!(failures.is_empty(), "GPU and CPU EWA disagree:\n{}", failures.join("\n"));
}

#[test]
fn hardware_anisotropic_against_the_cpu() {
    let Some(ctx) = context() else { return };
    println!("adapter: {}", ctx.report);
    let mut failures = Vec::new();
    for kind in scenes() {
        let case = Case::new(kind);
        let quads = case.quads();
        let mut r = gpu_filter(&ctx, &case);
        let nearest = case.cpu(&FilterSpec::Nearest(Nearest));
        let ewa = case.cpu(&"ewa".parse().expect("EWA"));
        for n in [4u16, 16] {
            let g = gpu_twin(&format!("aniso{n}:box"));
            let gpu = r.render(&g).expect("anisotropic");
            let cpu = case.cpu(&g.cpu_twin());
            case.save(&g.name(), &gpu, &cpu);
            let p = psnr(&gpu, &cpu, Some(&quads));
            let baseline = psnr(&nearest, &cpu, Some(&quads));
            let (mg, mc) = (mean(&gpu, &quads), mean(&cpu, &quads));
            println!(
                "{:>20} {:>10} vs {:>11}: PSNR {p:6.2} dB (nearest's: {baseline:6.2} dB; against ewa: {:6.2} dB), mean {mg:.4} vs {mc:.4}",
                case.name(),
                g.name(),
                g.cpu_twin().name(),
                psnr(&gpu, &ewa, Some(&quads))
            );
            if p < baseline + 3.0 || (mg - mc).abs() > 0.005 {
                failures.push(format!(
                    "{} {}: PSNR {p:.2} dB against nearest's {baseline:.2} dB, means {mg:.4} and {mc:.4}",
                    case.name(),
                    g.name()
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "the hardware's anisotropic filter fails its sanity bounds:\n{}",
        failures.join("\n")
    );
}

/// The catalogue's filters map to GPU filters, or are refused with the reason (no device
/// needed).
#[test]
fn filter_specs_map_to_gpu_filters_or_are_refused() {
    let map = |s: &str| GpuFilter::from_spec(&s.parse().expect("a catalogue filter"));
    let sampler = |linear, levels| GpuForm::Sampler(HardwareSampler { linear, levels });
    assert_eq!(map("nearest").unwrap().form(), sampler(false, Levels::Base));
    assert_eq!(map("nearest").unwrap().name(), "nearest");
    assert_eq!(map("trilinear").unwrap().form(), sampler(true, Levels::Gradients));
    assert_eq!(map("trilinear").unwrap().cpu_twin(), FilterSpec::Trilinear(Trilinear));
    assert_eq!(map("aniso1:box").unwrap(), map("trilinear").unwrap());
    assert_eq!(map("aniso16:box").unwrap().form(), sampler(true, Levels::Quad { anisotropy: 16 }));
    assert_eq!(map("aniso16:box").unwrap().name(), "hw-aniso16");
    assert_eq!(map("aniso16:box").unwrap().cpu_twin().name(), "aniso16:box");
    assert_eq!(map("ewa:texels=64").unwrap().name(), "ewa:texels=64");
    for (bad, why) in [("bicubic", "bicubic"), ("aniso16", "equal weights"), ("aniso32:box", "16 probes")] {
        let e = map(bad).expect_err("no GPU twin");
        assert!(matches!(e, GpuError::NoGpuFilter(..)), "{e}");
        assert!(e.to_string().contains(bad) && e.to_string().contains(why), "{e}");
    }
}

/// Every filter of the registry (at the settings the lab measures): the GPU side accepts
/// exactly those whose entry states a GPU form, under the entry's name, and each renders a
/// small frame with the surface's pixels finite and opaque where it shows.
#[test]
fn every_registry_filter_with_a_gpu_form_is_accepted_and_renders() {
    let ctx = context();
    let case = Case::new(SceneKind::ThesisQuad);
    let mut r = ctx.as_ref().map(|c| gpu_filter(c, &case));
    let module = renderlab_gpu::filter::module_source();
    for w in renderlab_texture::filter::wgsl_sources() {
        assert!(module.contains(w.source), "the filter module holds every WGSL filter");
    }
    for spec in lab_filters() {
        match (spec.gpu(), GpuFilter::from_spec(&spec)) {
            (Ok(twin), Ok(g)) => {
                assert_eq!((g.name(), g.cpu_twin(), g.form()), (twin.name, twin.cpu, twin.form));
                if let Some(r) = r.as_mut() {
                    let img = r.render(&g).unwrap_or_else(|e| panic!("{}: {e}", g.name()));
                    assert!(img.pixels().iter().all(|c| c.is_finite()), "{}", g.name());
                }
            }
            (Err(why), Err(e)) => assert!(e.to_string().contains(&why), "{spec}: {e}"),
            (a, b) => panic!("{spec}: the entry says {a:?}, the GPU side {b:?}"),
        }
    }
}
