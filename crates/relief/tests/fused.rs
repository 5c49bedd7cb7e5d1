//! The fused frame: its vector shading kernel gives the scalar twin's bits; its records are
//! the float renderer's (same raster rows, same trace); its image differs from the float
//! renderer's only by the 8-bit textures and output, within a stated PSNR; and it does not
//! depend on the thread count or on a reused frame.

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use renderlab_core::counter::Tally;
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::srgb8::srgb8_encode_table;
use renderlab_core::ShadePoint;
use renderlab_core::{Camera, Image, Scene, SceneObject};
use renderlab_raster::rasterize;
use renderlab_relief::fused::lanes::{ShadeConsts, ShadeLanes, LANES};
use renderlab_relief::fused::{render_fused, render_fused_records, FusedFrame, Textures8};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::render::render;
use renderlab_relief::render::shadow::soft_shadow;
use renderlab_relief::simd::{shade_groups, shade_lanes};
use renderlab_relief::ReliefHit;
use renderlab_relief::{FrameInput, Kernel, KernelChoice, ReliefMaterial, Shading, Technique};
use renderlab_texture::{Texture, Wrap};

fn bricks(size: u32) -> ReliefMaterial {
    let m = renderlab_texture::materials::material("bricks", size).expect("built-in material");
    ReliefMaterial::new(&m, &ComplexityParams::default(), true)
}

fn wall(size: u32) -> Scene {
    let m = renderlab_texture::materials::material("bricks", size).expect("built-in material");
    Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![m])
}

fn camera(angle: f32, w: u32, h: u32) -> Camera {
    Camera::orbit(BRICKS_WALL_CENTRE, 7.0, angle, w, h)
}

/// Textures of odd sizes with random-looking content, so wrap and level edges are exercised.
fn odd_textures() -> Textures8 {
    let albedo = Image::from_fn(37, 23, |x, y| {
        let h = (x * 7919 + y * 104_729) % 1000;
        Vec3::new(h as f32 / 999.0, ((h * 3) % 1000) as f32 / 999.0, ((x + y) % 5) as f32 / 4.0)
    });
    let normal = Image::from_fn(37, 23, |x, y| {
        Vec3::new((x as f32 * 0.3).sin() * 0.5, (y as f32 * 0.2).cos() * 0.5, 0.7)
    });
    Textures8::new(&Texture::from_rgb(&albedo, Wrap::Repeat), &Texture::from_rgb(&normal, Wrap::Repeat))
}

fn lanes_strategy() -> impl Strategy<Value = ShadeLanes> {
    let coord = prop_oneof![8 => -3.0f32..3.0, 1 => Just(f32::NAN), 1 => Just(1.0e9f32), 1 => Just(-0.0f32)];
    let deriv =
        prop_oneof![8 => -0.05f32..0.05, 1 => Just(f32::INFINITY), 1 => Just(0.0f32), 1 => -5.0f32..5.0];
    let unit = -1.0f32..1.0;
    (
        prop::array::uniform8(coord.clone()),
        prop::array::uniform8(coord),
        prop::array::uniform4(prop::array::uniform8(deriv)),
        prop::array::uniform3(prop::array::uniform8(unit.clone())),
        prop::array::uniform3(prop::array::uniform8(unit)),
        prop::array::uniform8(0.0f32..=1.0),
    )
        .prop_map(|(u, v, d, l, view, shadow)| ShadeLanes {
            u,
            v,
            dudx: d[0],
            dvdx: d[1],
            dudy: d[2],
            dvdy: d[3],
            lx: l[0],
            ly: l[1],
            lz: l[2],
            vx: view[0],
            vy: view[1],
            vz: view[2],
            shadow,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// The AVX2 kernel (one group of eight pixels, or two shaded together) and the scalar twin
    /// give the same pixels, bit for bit, lit and unlit, with a whole and a fractional
    /// exponent, on odd-sized textures, and with every lane of one group magnified or at the
    /// last level (where the vector kernel skips the second level's fetches).
    #[test]
    fn vector_shading_equals_the_scalar_twin(
        p in lanes_strategy(),
        q in lanes_strategy(),
        lit in any::<bool>(),
        whole in any::<bool>(),
        magnified in any::<bool>(),
    ) {
        let mut p = p;
        if magnified {
            // Footprints below a texel (level 0, blend weight 0) or infinite (the last level).
            for d in [&mut p.dudx, &mut p.dvdx, &mut p.dudy, &mut p.dvdy] {
                for x in d.iter_mut() {
                    *x *= 1e-3;
                }
            }
        }
        let tex = odd_textures();
        prop_assert!(tex.albedo.same_shape(&tex.normal), "the odd textures have one shape");
        let k = ShadeConsts {
            albedo: &tex.albedo,
            normal: &tex.normal,
            shading: if lit { Shading::Lit } else { Shading::Unlit },
            ambient: 0.2,
            exponent: if whole { 32.0 } else { 17.3 },
            strength: 0.2,
            encode: srgb8_encode_table(),
        };
        let mut scalar = [0u32; LANES];
        shade_lanes(&p, &k, &mut scalar, false);
        let mut vector = [0u32; LANES];
        if renderlab_relief::cpu::has_avx2() {
            shade_lanes(&p, &k, &mut vector, true);
            prop_assert_eq!(scalar, vector);
            // Two groups shaded together: each group's pixels as shaded alone.
            let mut scalar_q = [0u32; LANES];
            shade_lanes(&q, &k, &mut scalar_q, false);
            let (mut a, mut b) = ([0u32; LANES], [0u32; LANES]);
            shade_groups([&p, &q], &k, [&mut a, &mut b], true);
            prop_assert_eq!((scalar, scalar_q), (a, b));
        } else {
            eprintln!("skipped: no AVX2 here");
        }
    }
}

/// A hit and its light for the soft-shadow pass: ordinary ones mostly, and the edges (light
/// at or under the horizon, a hit on the top surface, NaN, huge UVs).
fn shadow_case() -> impl Strategy<Value = (ReliefHit, ShadePoint)> {
    let coord = prop_oneof![8 => -3.0f32..3.0, 1 => Just(f32::NAN), 1 => -1.0e9f32..1.0e9];
    let depth = prop_oneof![8 => 0.0f32..1.0, 1 => Just(0.0f32), 1 => Just(f32::NAN)];
    let light = prop_oneof![
        8 => (-1.0f32..1.0, -1.0f32..1.0, 0.01f32..1.0),
        1 => (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..0.0),
        1 => (Just(0.3f32), Just(f32::NAN), Just(1e-9f32)),
    ];
    (coord.clone(), coord, depth, light).prop_map(|(u, v, depth, (lx, ly, lz))| {
        let hit = ReliefHit { uv: Vec2::new(u, v), depth, layers: 32 };
        let point = ShadePoint { light_ts: Vec3::new(lx, ly, lz), ..ShadePoint::default() };
        (hit, point)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The fused frame's soft-shadow pass on the packed map gives the scalar function's
    /// factors bit for bit (and its fetch count), on rows of every length.
    #[test]
    fn vector_soft_shadows_equal_the_scalar_function(
        cases in proptest::collection::vec(shadow_case(), 0..40),
        samples in prop_oneof![Just(0u32), 1u32..24],
    ) {
        let mat = bricks(32);
        let (hits, points): (Vec<ReliefHit>, Vec<ShadePoint>) = cases.into_iter().unzip();
        let mut expected = Vec::new();
        let mut scalar_count = Tally::default();
        for (h, p) in hits.iter().zip(&points) {
            expected.push(soft_shadow(&mat.packed, mat.height_scale, h.uv, h.depth, p.light_ts, samples, &mut scalar_count));
        }
        let mut got = vec![f32::NAN; hits.len()];
        let mut count = Tally::default();
        renderlab_relief::simd::soft_shadow_row(&mat.inputs(), samples, &hits, &points, &mut got, true, &mut count);
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&expected), bits(&got));
        prop_assert_eq!(scalar_count, count);
    }
}

fn psnr(a: &Image<Vec3>, b: &Image<Vec3>, mask: &[bool]) -> f64 {
    let (mut se, mut n) = (0.0f64, 0usize);
    for ((x, y), &m) in a.pixels().iter().zip(b.pixels()).zip(mask) {
        if m {
            let d = (*x - *y).to_array();
            se += d.iter().map(|v| (*v as f64).powi(2)).sum::<f64>() / 3.0;
            n += 1;
        }
    }
    10.0 * (n as f64 / se).log10()
}

/// Against the float renderer on the rasterized G-buffer: the same UV, depth, layers and
/// mask for every pixel (one raster, one trace), and an image within the 8-bit precision
/// (PSNR ≥ 38 dB over the covered pixels, every technique family).
#[test]
fn records_equal_the_float_renderer_and_the_image_is_within_8_bit_precision() {
    let (w, h) = (160, 100);
    let mats = [bricks(128)];
    let scene = wall(128);
    for angle in [0.0, 60.0] {
        let cam = camera(angle, w, h);
        let g = rasterize(&scene, &cam);
        let input = FrameInput::new(w, h, g.pixels());
        for name in [
            "basic",
            "normal",
            "parallax",
            "steep:16",
            "pom:16",
            "adaptive",
            "pom-shadow",
            "pom-horizon",
            "cone-newton",
            "relief",
            "adaptive-relief",
        ] {
            let t = Technique::parse(name).expect("technique");
            for kernel in [Kernel::Scalar, t.kernel(KernelChoice::Auto).expect("kernel")] {
                let float =
                    render(input, &mats, t, kernel, scene.lighting, scene.background, true).expect("renders");
                let (frame, rec) =
                    render_fused_records(&scene, &cam, &mats, t, kernel, true).expect("renders");
                assert_eq!(rec.mask, float.mask.pixels(), "{name}");
                assert_eq!(rec.uv, float.uv.pixels(), "{name}");
                assert_eq!(rec.depth, float.depth.pixels(), "{name}");
                assert_eq!(rec.layers, float.layers.pixels(), "{name}");
                assert_eq!(rec.fetches, float.fetches, "{name}");
                let p = psnr(&frame.to_linear(), &float.image, &rec.mask);
                assert!(p >= 38.0, "{name} at {angle}°: {p:.1} dB");
                // Every pixel showing no surface is the background's, timed run or recorded.
                let mut timed = FusedFrame::default();
                render_fused(&scene, &cam, &mats, t, kernel, true, &mut timed).expect("renders");
                let background = FusedFrame::new(1, 1);
                let mut empty = FusedFrame::default();
                render_fused(&scene, &camera(180.0, w, h), &mats, t, kernel, true, &mut empty)
                    .expect("renders");
                let bg = empty.pixels[0];
                assert_ne!(bg, background.pixels[0], "the scene's background is not black");
                for f in [&frame, &timed] {
                    assert!(
                        f.pixels.iter().zip(&rec.mask).all(|(&p, &m)| m || p == bg),
                        "{name} at {angle}°"
                    );
                }
            }
        }
    }
}

/// Vector and scalar shading give the same frame; 1, 2 and 3 threads give the same frame; a
/// reused frame of another size is replaced; the timed and the recorded runs agree.
#[test]
fn fused_frames_are_bit_identical_across_kernels_threads_and_reuse() {
    let mats = [bricks(64)];
    let scene = wall(64);
    let cam = camera(45.0, 123, 77);
    for name in ["pom:8", "basic", "normal", "parallax", "pom-shadow:16:8", "pom-horizon:16:8", "relief"] {
        let t = Technique::parse(name).expect("technique");
        let kernel = t.kernel(KernelChoice::Auto).expect("kernel");
        let (recorded, _) = render_fused_records(&scene, &cam, &mats, t, kernel, true).expect("renders");
        let mut frames = Vec::new();
        for (threads, vector) in [(1, true), (2, false), (3, true)] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
            let mut f = FusedFrame::new(5, 5);
            pool.install(|| render_fused(&scene, &cam, &mats, t, kernel, vector, &mut f)).expect("renders");
            frames.push(f);
        }
        for f in &frames {
            assert_eq!(f, &recorded, "{name}");
        }
        assert!(recorded.pixels.iter().any(|&p| p != recorded.pixels[0]), "not a blank frame");
    }
}

/// A camera that sees nothing gives the background everywhere; an empty frame is empty.
#[test]
fn background_and_empty_frames() {
    let mats = [bricks(16)];
    let scene = wall(16);
    let away = Camera::look_at(Vec3::new(0.0, 1.0, -50.0), Vec3::new(0.0, 1.0, -60.0), 16, 9);
    let t = Technique::parse("basic").expect("technique");
    let (f, rec) = render_fused_records(&scene, &away, &mats, t, Kernel::Scalar, true).expect("renders");
    assert!(rec.mask.iter().all(|&m| !m));
    let bg = renderlab_core::color::linear_to_srgb8(scene.background);
    let px = bg[0] as u32 | (bg[1] as u32) << 8 | (bg[2] as u32) << 16 | 0xff00_0000;
    assert!(f.pixels.iter().all(|&p| p == px));
    let mut empty = FusedFrame::new(3, 3);
    let cam = camera(0.0, 0, 0);
    render_fused(&scene, &cam, &mats, t, Kernel::Scalar, true, &mut empty).expect("renders");
    assert!(empty.pixels.is_empty());
    let _ = Vec2::ZERO;
}
