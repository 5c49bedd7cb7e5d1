//! `relief bench`, `relief render`, `complexity` and `materials`.

use super::{create_dir, frame_size};
use crate::args::*;
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use glam::Vec3;
use renderlab_core::error::check_range;
use renderlab_core::{io, Material};
use renderlab_lab::fixtures::{benchmark_camera, benchmark_scene, room_camera, thesis_room};
use renderlab_lab::relief_lab::{
    debug_view, default_techniques, run_relief_bench, Backend, DebugView as Debug, Method, ReliefBenchConfig,
    View,
};
use renderlab_relief::maps::complexity::{complexity_map, ComplexityParams};
use renderlab_relief::render::render as render_frame;
use renderlab_relief::{KernelChoice, Map, ReliefMaterial, Technique};
use renderlab_texture::materials::{material as builtin_material, MATERIAL_NAMES};

/// The complexity-map parameters of the flags, checked.
fn params(f: &ComplexityFlags) -> Result<ComplexityParams> {
    let p = ComplexityParams { dilation_iterations: f.dilate, gamma: f.gamma, levels: f.levels };
    p.validate()?;
    Ok(p)
}

/// The material of the user's own maps, if they gave them (`--height-scale` checked).
pub(crate) fn load_own_material(own: &OwnMapsArgs) -> Result<Option<Material>> {
    let (Some(a), Some(h)) = (&own.albedo, &own.height_map) else { return Ok(None) };
    check_range("--height-scale", own.height_scale, 0.0, 1.0)?;
    let albedo = io::load_color(a)?;
    let height = io::load_height(h)?;
    let normal = own.normal_map.as_ref().map(io::load_normal_map).transpose()?;
    let name = a.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "user".into());
    Ok(Some(Material::from_maps(name, albedo, height, normal, own.height_scale)?))
}

/// Loads the material the user asked for.
fn load_material(m: &MaterialArgs) -> Result<Material> {
    if let Some(own) = load_own_material(&m.own)? {
        return Ok(own);
    }
    if m.texture_size > 8192 {
        bail!("--texture-size: {} is larger than 8192", m.texture_size);
    }
    Ok(builtin_material(&m.material, m.texture_size)?)
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
    if !(16..=4096).contains(&a.cone_size) {
        bail!("--cone-size: {} must lie in 16..=4096", a.cone_size);
    }
    create_dir(&a.out)?;
    let material = load_material(&a.material)?;
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
    io::check_output(&a.out)?;
    let technique = a.technique;
    let kernel = technique.kernel(a.kernel)?;
    let cp = params(&a.complexity)?;
    let (scene, camera) = match a.scene {
        SceneChoice::Bench => {
            let m = load_material(&a.material)?;
            (benchmark_scene(m), benchmark_camera(a.angle, a.width, a.height))
        }
        SceneChoice::Room => {
            let size = a.material.texture_size.min(8192);
            (thesis_room(size)?, room_camera(a.width, a.height))
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
    io::check_output(&a.out)?;
    let h = io::load_height(&a.height)?;
    let c = complexity_map(&h, &p);
    io::save_gray(&a.out, &c, false)?;
    println!("Complexity map saved as {}.", a.out.display());
    Ok(())
}

/// `renderlab materials`: every built-in material's maps.
pub(super) fn materials(a: MaterialsArgs) -> Result<()> {
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
