//! `relief bench`, `relief render`, `complexity` and `materials`.

use super::checks::{check_out_dir, check_out_file, create_dir, frame_size};
use crate::args::*;
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use glam::Vec3;
use renderlab_core::error::check_range;
use renderlab_core::memory::{gib, BUDGET};
use renderlab_core::{io, Material};
use renderlab_lab::fixtures::{benchmark_camera, benchmark_scene, room_camera, thesis_room};
use renderlab_lab::relief_lab::{
    debug_view, default_techniques, run_relief_bench, Backend, DebugView as Debug, Method, ReliefBenchConfig,
    View,
};
use renderlab_relief::maps::complexity::{complexity_map, ComplexityParams};
use renderlab_relief::memory::ReliefMemory;
use renderlab_relief::render::render as render_frame;
use renderlab_relief::{KernelChoice, Map, ReliefMaterial, Technique};
use renderlab_texture::materials::{material as builtin_material, DEFAULT_MATERIAL, MATERIAL_NAMES};

/// The complexity-map parameters of the flags, checked.
fn params(f: &ComplexityFlags) -> Result<ComplexityParams> {
    let p = ComplexityParams { dilation_iterations: f.dilate, gamma: f.gamma, levels: f.levels };
    p.validate()?;
    Ok(p)
}

/// The largest `--texture-size`.
const MAX_TEXTURE_SIZE: u32 = 8192;

/// The relief depth of your own maps when `--height-scale` is not given.
const OWN_HEIGHT_SCALE: f32 = 0.05;

/// Checks `--height-scale` where it is given: the same range for your maps and the built-in
/// materials, which it applies to alike.
pub(crate) fn height_scale(own: &OwnMapsArgs) -> Result<Option<f32>> {
    own.height_scale.map(|s| check_range("--height-scale", s, 0.0, 1.0)).transpose().map_err(Into::into)
}

/// The material of the user's own maps, if they gave them (`--height-scale` checked).
pub(crate) fn load_own_material(own: &OwnMapsArgs) -> Result<Option<Material>> {
    let scale = height_scale(own)?.unwrap_or(OWN_HEIGHT_SCALE);
    let (Some(a), Some(h)) = (&own.albedo, &own.height_map) else { return Ok(None) };
    let albedo = io::load_color(a)?;
    let height = io::load_height(h)?;
    let normal = own.normal_map.as_ref().map(io::load_normal_map).transpose()?;
    let name = a.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "user".into());
    Ok(Some(Material::from_maps(name, albedo, height, normal, scale)?))
}

/// A built-in material at `--height-scale` where it is given: its normal map is derived
/// again from its height at that depth, as it is at its own.
fn with_height_scale(m: Material, scale: Option<f32>) -> Result<Material> {
    match scale {
        Some(s) if s != m.height_scale => Ok(Material::from_maps(m.name, m.albedo, m.height, None, s)?),
        _ => Ok(m),
    }
}

/// Checks `--texture-size` against the built-in materials' range.
fn check_texture_size(size: u32) -> Result<()> {
    if !(16..=MAX_TEXTURE_SIZE).contains(&size) {
        bail!("--texture-size: {size} must lie in 16..={MAX_TEXTURE_SIZE}");
    }
    Ok(())
}

/// Refuses a texture size of `materials` materials and a frame (`None`: a window's, not
/// counted) whose estimated peak memory ([`ReliefMemory`]) exceeds the budget, in one line
/// naming the largest texture size that fits.
pub(crate) fn check_memory(
    fit: ReliefMemory,
    size: u32,
    materials: u64,
    frame: Option<(u32, u32)>,
) -> Result<()> {
    let (w, h) = frame.unwrap_or((0, 0));
    let pixels = u64::from(w) * u64::from(h);
    let need = fit.estimate(size, materials, pixels);
    if need <= BUDGET {
        return Ok(());
    }
    let largest = fit.largest_texture(materials, pixels);
    let what = if materials == 1 { String::new() } else { format!(" ({materials} materials)") };
    if largest < 16 {
        bail!(
            "--width/--height {w}x{h}: the frame needs about {:.1} GiB, over the {} GiB memory budget",
            gib(fit.frame(pixels)),
            BUDGET >> 30
        );
    }
    let with = if frame.is_some() { format!(" with a {w}x{h} frame") } else { String::new() };
    bail!(
        "--texture-size {size}{what}{with} needs about {:.1} GiB, over the {} GiB memory budget; the largest texture size here is {}",
        gib(need),
        BUDGET >> 30,
        largest.min(MAX_TEXTURE_SIZE)
    );
}

/// Loads the material the user asked for: your maps, or the built-in `--material` (an
/// unknown name is refused before its maps are built).
fn load_material(m: &MaterialArgs) -> Result<Material> {
    if let Some(own) = load_own_material(&m.own)? {
        return Ok(own);
    }
    check_texture_size(m.texture_size)?;
    let name = m.material.as_deref().unwrap_or(DEFAULT_MATERIAL);
    check_material_name(name)?;
    with_height_scale(builtin_material(name, m.texture_size)?, height_scale(&m.own)?)
}

/// Refuses an unknown `--material` in one line naming the flag.
fn check_material_name(name: &str) -> Result<()> {
    if !MATERIAL_NAMES.contains(&name) {
        bail!("--material: '{name}' is not one of {}", MATERIAL_NAMES.join(", "));
    }
    Ok(())
}

/// The methods `relief bench` measures: the given techniques on `kernel` (default auto), or
/// the lab's default list, whose kernels `kernel` replaces where a technique offers it.
fn methods(list: &[Technique], kernel: Option<KernelChoice>) -> Vec<Method> {
    if list.is_empty() {
        let mut methods = default_techniques();
        if let Some(choice) = kernel {
            for m in &mut methods {
                let offered = match choice {
                    KernelChoice::Auto => true,
                    KernelChoice::Exactly(k) => m.technique.descriptor().kernels.contains(&k),
                };
                if offered {
                    m.kernel = choice;
                }
            }
        }
        return methods;
    }
    list.iter().map(|&technique| Method { technique, kernel: kernel.unwrap_or_default() }).collect()
}

/// Checks `--angles`.
fn check_angles(angles: &[f32]) -> Result<()> {
    if angles.is_empty() {
        bail!("--angles: give at least one angle");
    }
    for &a in angles {
        check_range("--angles", a, 0.0, 89.0)?;
    }
    Ok(())
}

/// `renderlab relief bench`.
pub(super) fn bench(a: BenchArgs) -> Result<()> {
    let (width, height) = a.resolution.unwrap_or((a.width, a.height));
    if a.resolution.is_some() {
        frame_size(width, height).context("--resolution")?;
    } else {
        frame_size(width, height)?;
    }
    check_angles(&a.angles)?;
    if a.reps == 0 || a.reps > 1000 {
        bail!("--reps: {} must lie in 1..=1000", a.reps);
    }
    if a.warmup > 100 {
        bail!("--warmup: {} must lie in 0..=100", a.warmup);
    }
    let backend = match a.backend {
        BenchBackend::Cpu => Backend::Cpu,
        BenchBackend::Gpu => Backend::Gpu,
        BenchBackend::Both => Backend::Both,
    };
    if !(16..=4096).contains(&a.cone_size) {
        bail!("--cone-size: {} must lie in 16..=4096", a.cone_size);
    }
    check_out_dir("--out", &a.out)?;
    let cfg = ReliefBenchConfig {
        width,
        height,
        angles: a.angles.clone(),
        techniques: methods(&a.techniques, a.kernel),
        warmup: a.warmup,
        reps: a.reps,
        complexity: params(&a.complexity)?,
        write_images: !a.no_images,
        cone_size: a.cone_size,
        backend,
        gpu_subset: None,
        gpu_required: true,
    };
    if a.material.own.albedo.is_none() {
        check_texture_size(a.material.texture_size)?;
        let memory = match backend {
            Backend::Cpu => ReliefMemory::BENCH_CPU,
            _ => ReliefMemory::BENCH_GPU,
        };
        check_memory(memory, a.material.texture_size, 1, Some((width, height)))?;
    }
    // Every input is read before --out is created.
    let material = load_material(&a.material)?;
    create_dir(&a.out)?;
    let p = Progress::new("relief");
    let summary = run_relief_bench(&material, &cfg, &a.out, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    println!("wrote {} ({} measurements)", summary.index.display(), summary.records.len());
    Ok(())
}

/// `renderlab relief render`: one image, shaded or a debug view.
pub(super) fn render(a: RenderArgs) -> Result<()> {
    frame_size(a.width, a.height)?;
    check_range("--angle", a.angle, 0.0, 89.0)?;
    check_out_file("--out", &a.out)?;
    let technique = a.technique;
    let kernel = technique.kernel(a.kernel)?;
    let cp = params(&a.complexity)?;
    let memory = match a.backend {
        crate::args::Backend::Cpu => ReliefMemory::RENDER_CPU,
        crate::args::Backend::Gpu | crate::args::Backend::Auto => ReliefMemory::RENDER_GPU,
    };
    if a.material.own.albedo.is_none() {
        let materials = if a.scene == SceneChoice::Room { 4 } else { 1 };
        check_texture_size(a.material.texture_size)?;
        check_memory(memory, a.material.texture_size, materials, Some((a.width, a.height)))?;
    }
    let (scene, camera) = match a.scene {
        SceneChoice::Bench => {
            let m = load_material(&a.material)?;
            (benchmark_scene(m), benchmark_camera(a.angle, a.width, a.height))
        }
        SceneChoice::Room => {
            if a.material.material.is_some() || a.material.own.albedo.is_some() {
                bail!(
                    "--material/--albedo: the room scene has its four built-in materials (use --scene bench)"
                );
            }
            check_texture_size(a.material.texture_size)?;
            let scale = height_scale(&a.material.own)?;
            let mut room = thesis_room(a.material.texture_size)?;
            if scale.is_some() {
                for m in &mut room.materials {
                    *m = with_height_scale(m.clone(), scale)?;
                }
            }
            (room, room_camera(a.width, a.height))
        }
    };
    let mats: Vec<ReliefMaterial> =
        scene.materials.iter().map(|m| ReliefMaterial::new(m, &cp, technique.needs_map(Map::Cone))).collect();
    // `--backend gpu|auto` draws and writes the image, or leaves it to the CPU path below.
    if crate::gpu::relief_render(&a, &scene, &camera, &mats)? {
        return Ok(());
    }
    let view = View::new(&scene, &camera, a.angle);
    let debug = match a.debug {
        DebugView::None => None,
        DebugView::Layers => Some(Debug::Layers),
        DebugView::Complexity => Some(Debug::Complexity),
        DebugView::Reference => Some(Debug::Reference),
        DebugView::Error => Some(Debug::Error),
    };
    let out = match debug {
        Some(which) => debug_view(which, &view, &scene, &mats, technique, kernel)?,
        None => {
            let started = std::time::Instant::now();
            let f =
                render_frame(view.input(), &mats, technique, kernel, scene.lighting, scene.background, true)?;
            let ms = started.elapsed().as_secs_f64() * 1e3;
            println!(
                "{technique} ({kernel} kernel): {} pixels, {:.2} height fetches per pixel, {ms:.0} ms (counted run)",
                f.mask.pixels().iter().filter(|&&m| m).count(),
                f.fetches_per_pixel()
            );
            f.image
        }
    };
    io::save_color(&a.out, &out)?;
    println!("wrote {}", a.out.display());
    Ok(())
}

/// `renderlab complexity`: a height map's complexity map.
pub(super) fn complexity(a: ComplexityArgs) -> Result<()> {
    let p = params(&a.params)?;
    check_out_file("OUT", &a.out)?;
    let h = io::load_height(&a.height)?;
    let c = complexity_map(&h, &p);
    io::save_gray(&a.out, &c, false)?;
    println!("Complexity map saved as {}.", a.out.display());
    Ok(())
}

/// `renderlab materials`: every built-in material's maps.
pub(super) fn materials(a: MaterialsArgs) -> Result<()> {
    if !(16..=MAX_TEXTURE_SIZE).contains(&a.size) {
        bail!("--size: {} must lie in 16..={MAX_TEXTURE_SIZE}", a.size);
    }
    check_out_dir("--out", &a.out)?;
    create_dir(&a.out)?;
    for name in MATERIAL_NAMES {
        let m = builtin_material(name, a.size)?;
        io::save_color(a.out.join(format!("{name}_albedo.png")), &m.albedo)?;
        io::save_gray(a.out.join(format!("{name}_height.png")), &m.height, true)?;
        let n = m.normal.map(|n| n * 0.5 + Vec3::splat(0.5));
        let n8 = n.map(|c| [(c.x * 255.0 + 0.5) as u8, (c.y * 255.0 + 0.5) as u8, (c.z * 255.0 + 0.5) as u8]);
        io::save_rgb8(a.out.join(format!("{name}_normal.png")), &n8)?;
        println!("wrote {name} ({0}x{0})", a.size);
    }
    Ok(())
}
