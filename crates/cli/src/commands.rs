//! The subcommands' implementations: validate arguments, call the libraries, report.

use crate::args::*;
use crate::progress::{LabBars, Progress};
use anyhow::{bail, Context, Result};
use glam::Vec3;
use renderlab_core::error::check_range;
use renderlab_core::image::check_dimensions;
use renderlab_core::{io, Image, Material};
use renderlab_lab::fixtures::{benchmark_camera, benchmark_scene, room_camera, thesis_room};
use renderlab_lab::heatmap::heat_image;
use renderlab_lab::noise_lab::{run_noise_lab_with, CloudsConfig, NoiseLabConfig, MAX_CLOUDS_SIZE};
use renderlab_lab::noise_motion::MotionConfig;
use renderlab_lab::relief_lab::{default_techniques, run_relief_bench, Method, ReliefBenchConfig, View};
use renderlab_lab::suite::{run_report, Preset};
use renderlab_lab::texture_lab::{run_texture_bench, SigmaStudy, TextureBenchConfig};
use renderlab_relief::maps::complexity::{complexity_map, ComplexityParams};
use renderlab_relief::render::{render, render_reference};
use renderlab_relief::techniques::basic::Basic;
use renderlab_relief::{Kernel, KernelChoice, Map, ReliefMaterial, Technique};
use renderlab_texture::filter::FilterSpec;
use renderlab_texture::materials::{material as builtin_material, MATERIAL_NAMES};
use renderlab_texture::reference::Sampling;
use renderlab_texture::scene::{SceneKind, TestScene};
use std::path::Path;

/// Dispatches a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Report(a) => report(a),
        Command::Relief(ReliefCommand::Bench(a)) => relief_bench(a),
        Command::Relief(ReliefCommand::Render(a)) => relief_render(a),
        Command::Texture(TextureCommand::Bench(a)) => texture_bench(a),
        Command::Texture(TextureCommand::Render(a)) => texture_render(a),
        Command::Complexity(a) => complexity(a),
        Command::Materials(a) => materials(a),
        Command::Noise(a) => noise(a),
        Command::Water(a) => water(a),
        Command::Smoke(a) => smoke(a),
    }
}

fn params(f: &ComplexityFlags) -> Result<ComplexityParams> {
    let p = ComplexityParams { dilation_iterations: f.dilate, gamma: f.gamma, levels: f.levels };
    p.validate()?;
    Ok(p)
}

fn frame_size(width: u32, height: u32) -> Result<()> {
    check_dimensions("--width/--height", width as u64, height as u64)?;
    if width < 8 || height < 8 {
        bail!("--width/--height: {width}x{height} is too small (at least 8x8)");
    }
    Ok(())
}

/// Loads the material the user asked for.
fn load_material(m: &MaterialArgs) -> Result<Material> {
    match (&m.albedo, &m.height_map) {
        (Some(a), Some(h)) => {
            check_range("--height-scale", m.height_scale, 0.0, 1.0)?;
            let albedo = io::load_color(a)?;
            let height = io::load_height(h)?;
            let normal = match &m.normal_map {
                Some(n) => Some(io::load_normal_map(n)?),
                None => None,
            };
            let name =
                a.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "user".into());
            Ok(Material::from_maps(name, albedo, height, normal, m.height_scale)?)
        }
        _ => {
            if m.texture_size > 8192 {
                bail!("--texture-size: {} is larger than 8192", m.texture_size);
            }
            Ok(builtin_material(&m.material, m.texture_size)?)
        }
    }
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

fn check_angles(angles: &[f32]) -> Result<()> {
    if angles.is_empty() {
        bail!("--angles: give at least one angle");
    }
    for &a in angles {
        check_range("--angles", a, 0.0, 89.0)?;
    }
    Ok(())
}

fn relief_bench(a: BenchArgs) -> Result<()> {
    frame_size(a.width, a.height)?;
    check_angles(&a.angles)?;
    if a.reps == 0 || a.reps > 1000 {
        bail!("--reps: {} must lie in 1..=1000", a.reps);
    }
    if a.warmup > 100 {
        bail!("--warmup: {} must lie in 0..=100", a.warmup);
    }
    let cfg = ReliefBenchConfig {
        width: a.width,
        height: a.height,
        angles: a.angles.clone(),
        techniques: methods(&a.techniques, a.kernel),
        warmup: a.warmup,
        reps: a.reps,
        complexity: params(&a.complexity)?,
        write_images: !a.no_images,
        cone_size: a.cone_size,
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

fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create directory", dir.display()))
}

fn relief_render(a: RenderArgs) -> Result<()> {
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
    let lit =
        |t: Technique, k: Kernel| render(view.input(), &mats, t, k, scene.lighting, scene.background, false);
    // Heat maps come display-encoded; decode them so `save_color` (PNG or EXR) can take them.
    let table = renderlab_core::color::srgb8_to_linear_table();
    let rgb8 = |img: Image<[u8; 3]>| -> Image<Vec3> {
        img.map(|c| Vec3::new(table[c[0] as usize], table[c[1] as usize], table[c[2] as usize]))
    };
    let out = match a.debug {
        DebugView::None => {
            let started = std::time::Instant::now();
            let f = render(view.input(), &mats, technique, kernel, scene.lighting, scene.background, true)?;
            let ms = started.elapsed().as_secs_f64() * 1e3;
            println!(
                "{technique} ({kernel} kernel): {} pixels, {:.2} height fetches per pixel, {ms:.0} ms (counted run)",
                f.mask.pixels().iter().filter(|&&m| m).count(),
                f.fetches_per_pixel()
            );
            f.image
        }
        DebugView::Reference => {
            render_reference(view.input(), &mats, technique, scene.lighting, scene.background).image
        }
        DebugView::Layers => {
            let f = lit(technique, kernel)?;
            let max = technique.layers().max(1) as f32;
            rgb8(heat_image(&f.layers.map(|l| l as f32), max, Some(&f.mask)))
        }
        DebugView::Complexity => {
            let f = lit(Technique::Basic(Basic), Kernel::Scalar)?;
            let c = Image::from_fn(a.width, a.height, |x, y| match view.gbuffer.get(x, y) {
                Some(sp) => mats[sp.material as usize].inputs().complexity_at(sp.uv),
                None => 0.0,
            });
            rgb8(heat_image(&c, 1.0, Some(&f.mask)))
        }
        DebugView::Error => {
            let f = lit(technique, kernel)?;
            let r = render_reference(view.input(), &mats, technique, scene.lighting, scene.background);
            let size = glam::Vec2::new(mats[0].height.width() as f32, mats[0].height.height() as f32);
            let e =
                Image::from_fn(a.width, a.height, |x, y| ((f.uv.get(x, y) - r.uv.get(x, y)) * size).length());
            rgb8(heat_image(&e, 4.0, Some(&f.mask)))
        }
    };
    io::save_color(&a.out, &out)?;
    println!("wrote {}", a.out.display());
    Ok(())
}

fn complexity(a: ComplexityArgs) -> Result<()> {
    let p = params(&a.params)?;
    io::check_output(&a.out)?;
    let h = io::load_height(&a.height)?;
    let c = complexity_map(&h, &p);
    io::save_gray(&a.out, &c, false)?;
    println!("Complexity map saved as {}.", a.out.display());
    Ok(())
}

fn materials(a: MaterialsArgs) -> Result<()> {
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

/// Checks the `noise` flags; every error is one line naming the flag.
fn noise_config(a: &NoiseArgs) -> Result<NoiseLabConfig> {
    if a.size == 0 || a.size > MAX_CLOUDS_SIZE {
        bail!("--size: {} must lie in 1..={MAX_CLOUDS_SIZE}", a.size);
    }
    let max = renderlab_noise::MAX_OCTAVES;
    if a.octaves == 0 || a.octaves > max {
        bail!("--octaves: {} must lie in 1..={max}", a.octaves);
    }
    if !(a.frequency.is_finite() && a.frequency > 0.0) {
        bail!("--frequency: {} must be a finite positive number", a.frequency);
    }
    let last = f64::from(a.frequency) * 2f64.powi(a.octaves as i32 - 1);
    if last > renderlab_noise::MAX_FREQUENCY {
        bail!(
            "--octaves/--frequency: the last layer's frequency {last} exceeds 2^24 (use fewer octaves \
             or a lower frequency)"
        );
    }
    let clouds = CloudsConfig { size: a.size, seed: a.seed, layers: a.octaves, frequency: a.frequency };
    let motion = if a.quick { MotionConfig::quick() } else { MotionConfig::default() };
    Ok(NoiseLabConfig { clouds, motion })
}

fn noise(a: NoiseArgs) -> Result<()> {
    let cfg = noise_config(&a)?;
    create_dir(&a.out)?;
    let p = Progress::new("noise");
    let summary = run_noise_lab_with(&a.out, &cfg, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    println!("wrote {} and {}", summary.clouds_png.display(), summary.index.display());
    Ok(())
}

/// Most frames `water` renders in one run.
const MAX_WATER_FRAMES: u32 = 10_000;
/// Most pixels (frames × width × height) `water` renders in one run, so that a typo cannot
/// start a job of days.
const MAX_WATER_PIXELS: u64 = 1 << 33;

/// Parses `WIDTHxHEIGHT`.
fn parse_size(flag: &str, s: &str) -> Result<(u32, u32)> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .with_context(|| format!("{flag}: '{s}' is not WIDTHxHEIGHT (e.g. 640x360)"))?;
    let side = |v: &str| -> Result<u32> {
        v.trim().parse::<u32>().with_context(|| format!("{flag}: '{s}' is not WIDTHxHEIGHT (e.g. 640x360)"))
    };
    Ok((side(w)?, side(h)?))
}

/// Maps a water-parameter error to the command-line flag that set the parameter.
fn water_flag_error(e: renderlab_noise::NoiseError) -> anyhow::Error {
    use renderlab_noise::NoiseError as E;
    let flag = match &e {
        E::Size { .. } => "--size",
        E::Octaves { .. } => "--octaves",
        E::Parameter { name, .. } => match *name {
            "time_step" => "--time-step",
            "wind" => "--wind",
            "amplitude" => "--amplitude",
            "choppiness" => "--choppiness",
            "camera_height" => "--camera-height",
            "pitch_deg" => "--pitch",
            "t" => "--start/--frames/--time-step",
            _ => "water parameters",
        },
        _ => "water parameters",
    };
    anyhow::anyhow!("{flag}: {e}")
}

fn water_params(a: &WaterArgs) -> Result<renderlab_noise::WaterParams> {
    if a.frames == 0 || a.frames > MAX_WATER_FRAMES {
        bail!("--frames: {} must lie in 1..={MAX_WATER_FRAMES}", a.frames);
    }
    let (width, height) = parse_size("--size", &a.size)?;
    if !(8..=renderlab_noise::water::MAX_WATER_SIDE).contains(&width)
        || !(8..=renderlab_noise::water::MAX_WATER_SIDE).contains(&height)
    {
        bail!(
            "--size: {width}x{height}: each side must lie in 8..={}",
            renderlab_noise::water::MAX_WATER_SIDE
        );
    }
    let total = u64::from(a.frames) * u64::from(width) * u64::from(height);
    if total > MAX_WATER_PIXELS {
        bail!("--frames/--size: {total} pixels in all exceeds {MAX_WATER_PIXELS} (fewer frames or smaller frames)");
    }
    let [vx, vy] = a.wind[..] else {
        bail!("--wind: give two numbers VX,VY (got {})", a.wind.len());
    };
    if !a.start.is_finite() {
        bail!("--start: {} must be finite", a.start);
    }
    let params = renderlab_noise::WaterParams {
        width,
        height,
        seed: a.seed,
        time_step: a.time_step,
        wind: [vx, vy],
        octaves: a.octaves,
        amplitude: a.amplitude,
        choppiness: a.choppiness,
        camera_height: a.camera_height,
        pitch_deg: a.pitch,
        ..Default::default()
    };
    params.validate().map_err(water_flag_error)?;
    Ok(params)
}

/// Where `water` and `smoke` put each frame: `DIR/frame_NNNN.png` and the looping animation
/// `DIR/animation.png` (APNG), which appears only once its last frame is in.
struct FrameSink<'a> {
    dir: &'a Path,
    animation: renderlab_core::apng::ApngWriter,
}

impl<'a> FrameSink<'a> {
    fn new(dir: &'a Path, width: u32, height: u32, frames: u32, fps: u32) -> Result<Self> {
        check_fps(fps)?;
        let animation =
            renderlab_core::apng::ApngWriter::create(dir.join("animation.png"), width, height, frames, fps)?;
        Ok(FrameSink { dir, animation })
    }

    fn push(&mut self, i: u32, img: &Image<Vec3>) -> Result<()> {
        let path = self.dir.join(format!("frame_{i:04}.png"));
        io::save_color(&path, img).with_context(|| format!("writing {}", path.display()))?;
        self.animation.push(img)?;
        Ok(())
    }

    fn finish(self) -> Result<()> {
        Ok(self.animation.finish()?)
    }
}

/// Renders a `water` or `smoke` sequence into `out` (PNG frames and the APNG, see
/// [`FrameSink`]) with a progress bar, mapping a noise-parameter error to its flag with
/// `flag_error`. Returns the milliseconds per frame.
fn write_sequence(
    name: &str,
    out: &Path,
    (width, height): (u32, u32),
    (frames, fps): (u32, u32),
    flag_error: fn(renderlab_noise::NoiseError) -> anyhow::Error,
    render: impl FnOnce(&mut dyn FnMut(u32, Image<Vec3>) -> Result<()>) -> Result<()>,
) -> Result<f64> {
    create_dir(out)?;
    let p = Progress::new(name);
    let started = std::time::Instant::now();
    let mut sink = FrameSink::new(out, width, height, frames, fps)?;
    render(&mut |i, img| {
        sink.push(i, &img)?;
        p.update(i as usize + 1, frames as usize, "frames");
        Ok(())
    })
    .map_err(|e| match e.downcast::<renderlab_noise::NoiseError>() {
        Ok(n) => flag_error(n),
        Err(e) => e,
    })?;
    sink.finish()?;
    p.finish();
    Ok(started.elapsed().as_secs_f64() * 1e3 / f64::from(frames))
}

fn check_fps(fps: u32) -> Result<()> {
    if !(1..=1000).contains(&fps) {
        bail!("--fps: {fps} must lie in 1..=1000");
    }
    Ok(())
}

fn water(a: WaterArgs) -> Result<()> {
    let params = water_params(&a)?;
    check_fps(a.fps)?;
    let last = f64::from(a.start) + f64::from(a.frames - 1) * f64::from(params.time_step);
    if last.abs() > f64::from(renderlab_noise::water::MAX_WATER_TIME) {
        bail!("--start/--frames/--time-step: the last frame's time {last} exceeds 10000 s");
    }
    let per = write_sequence(
        "water",
        &a.out,
        (params.width, params.height),
        (a.frames, a.fps),
        water_flag_error,
        |sink| renderlab_noise::water::render_water_sequence(&params, a.start, a.frames, sink),
    )?;
    println!(
        "wrote {} frames ({}x{}) and animation.png to {} ({per:.1} ms per frame)",
        a.frames,
        params.width,
        params.height,
        a.out.display()
    );
    Ok(())
}

/// Most frames `smoke` renders in one run.
const MAX_SMOKE_FRAMES: u32 = 10_000;
/// Most pixels (frames × width × height) `smoke` renders in one run.
const MAX_SMOKE_PIXELS: u64 = 1 << 31;
/// Most voxels (frames × grid³) `smoke` builds in one run.
const MAX_SMOKE_VOXELS: u64 = 1 << 36;

/// Maps a smoke-parameter error to the command-line flag that set the parameter.
fn smoke_flag_error(e: renderlab_noise::NoiseError) -> anyhow::Error {
    use renderlab_noise::NoiseError as E;
    let flag = match &e {
        E::Size { .. } => "--size",
        E::Octaves { .. } => "--octaves",
        E::Parameter { name, .. } => match *name {
            "grid" => "--grid",
            "time_step" => "--time-step",
            "rise_speed" => "--rise-speed",
            "swirl" => "--swirl",
            "sigma" => "--sigma",
            "density" => "--density",
            "absorption" => "--absorption",
            "scattering" => "--scattering",
            "light_direction" => "--light",
            "step" => "--step",
            "shadow_steps" => "--shadow-steps",
            "animation_factor" => "--animation-factor",
            "t" => "--start/--frames/--time-step",
            _ => "smoke parameters",
        },
        _ => "smoke parameters",
    };
    anyhow::anyhow!("{flag}: {e}")
}

fn smoke_params(a: &SmokeArgs) -> Result<renderlab_noise::SmokeParams> {
    use renderlab_noise::smoke::{Animation, SmokeFilter, MAX_SMOKE_SIDE};
    if a.frames == 0 || a.frames > MAX_SMOKE_FRAMES {
        bail!("--frames: {} must lie in 1..={MAX_SMOKE_FRAMES}", a.frames);
    }
    let (width, height) = parse_size("--size", &a.size)?;
    if !(8..=MAX_SMOKE_SIDE).contains(&width) || !(8..=MAX_SMOKE_SIDE).contains(&height) {
        bail!("--size: {width}x{height}: each side must lie in 8..={MAX_SMOKE_SIDE}");
    }
    let total = u64::from(a.frames) * u64::from(width) * u64::from(height);
    if total > MAX_SMOKE_PIXELS {
        bail!("--frames/--size: {total} pixels in all exceeds {MAX_SMOKE_PIXELS} (fewer or smaller frames)");
    }
    let voxels = u64::from(a.frames) * u64::from(a.grid).pow(3);
    if voxels > MAX_SMOKE_VOXELS {
        bail!("--frames/--grid: {voxels} voxels in all exceeds {MAX_SMOKE_VOXELS} (fewer frames or a smaller grid)");
    }
    let [lx, ly, lz] = a.light[..] else {
        bail!("--light: give three numbers X,Y,Z (got {})", a.light.len());
    };
    if !a.start.is_finite() {
        bail!("--start: {} must be finite", a.start);
    }
    let params = renderlab_noise::SmokeParams {
        width,
        height,
        grid: a.grid,
        seed: a.seed,
        octaves: a.octaves,
        density: a.density,
        rise_speed: a.rise_speed,
        swirl: a.swirl,
        filter: match a.filter {
            SmokeFilterChoice::None => SmokeFilter::None,
            SmokeFilterChoice::Gaussian => SmokeFilter::Gaussian { sigma: a.sigma },
            SmokeFilterChoice::Median => SmokeFilter::Median3,
        },
        absorption: a.absorption,
        scattering: a.scattering,
        light_direction: Vec3::new(lx, ly, lz),
        step: a.step,
        shadow_steps: a.shadow_steps,
        animation: match a.animation {
            SmokeAnimation::Advect => Animation::Advect,
            SmokeAnimation::Thesis => Animation::ThesisLiteral { animation_factor: a.animation_factor },
        },
        time_step: a.time_step,
        ..Default::default()
    };
    params.validate().map_err(smoke_flag_error)?;
    Ok(params)
}

fn smoke(a: SmokeArgs) -> Result<()> {
    let params = smoke_params(&a)?;
    check_fps(a.fps)?;
    let last = f64::from(a.start) + f64::from(a.frames - 1) * f64::from(params.time_step);
    if a.start.abs() > renderlab_noise::smoke::MAX_SMOKE_TIME
        || last.abs() > f64::from(renderlab_noise::smoke::MAX_SMOKE_TIME)
    {
        bail!("--start/--frames/--time-step: frame times must stay within ±10000 s (last: {last})");
    }
    let per = write_sequence(
        "smoke",
        &a.out,
        (params.width, params.height),
        (a.frames, a.fps),
        smoke_flag_error,
        |sink| renderlab_noise::smoke::render_smoke_sequence(&params, a.start, a.frames, sink),
    )?;
    println!(
        "wrote {} frames ({}x{}, grid {}³) and animation.png to {} ({per:.1} ms per frame)",
        a.frames,
        params.width,
        params.height,
        params.grid,
        a.out.display()
    );
    Ok(())
}

fn report(a: ReportArgs) -> Result<()> {
    let preset = if a.quick { Preset::Quick } else { Preset::Report };
    let bars = LabBars::default();
    let suite = run_report(&a.out, preset, &|lab, d, t, m| bars.update(lab, d, t, m));
    bars.finish();
    let suite = suite?;
    for lab in &suite.labs {
        for f in &lab.summary.findings {
            println!("{f}");
        }
    }
    for lab in &suite.labs {
        println!("{} lab: {:.1} s", lab.name, lab.summary.seconds);
    }
    println!("wrote {} in {:.1} s", suite.index.display(), suite.seconds);
    Ok(())
}

/// Checks the `texture bench` flags and builds the lab's configuration.
fn texture_config(a: &TextureBenchArgs) -> Result<TextureBenchConfig> {
    if !(8..=4096).contains(&a.width) || !(8..=4096).contains(&a.height) {
        bail!("--width/--height: {}x{}: each side must lie in 8..=4096", a.width, a.height);
    }
    if a.reps == 0 || a.reps > 1000 {
        bail!("--reps: {} must lie in 1..=1000", a.reps);
    }
    if a.warmup > 100 {
        bail!("--warmup: {} must lie in 0..=100", a.warmup);
    }
    if !(a.tolerance >= 0.0005 && a.tolerance <= 0.2) {
        bail!("--tolerance: {} must lie in 0.0005..=0.2", a.tolerance);
    }
    if !(8..=128).contains(&a.max_strata) {
        bail!("--max-strata: {} must lie in 8..=128", a.max_strata);
    }
    let defaults = TextureBenchConfig::default();
    let filters = if a.filters.is_empty() { defaults.filters.clone() } else { a.filters.clone() };
    let scenes = if a.scenes.is_empty() {
        SceneKind::defaults()
    } else {
        a.scenes
            .iter()
            .map(|s| SceneKind::parse(s).map_err(|e| anyhow::anyhow!("--scenes: {e}")))
            .collect::<Result<_>>()?
    };
    Ok(TextureBenchConfig {
        width: a.width,
        height: a.height,
        scenes,
        filters,
        reps: a.reps,
        warmup: a.warmup,
        model: a.model,
        sampling: Sampling { max_strata: a.max_strata, tolerance: a.tolerance, ..defaults.sampling },
        sigma_study: if a.no_sigma_study { None } else { sigma_study(a, defaults.sigma_study.clone())? },
        write_images: !a.no_images,
        texture: user_texture(a.texture.as_deref())?,
        ..TextureBenchConfig::default()
    })
}

/// The σ study's scenes from `--sigma-scenes`, or the default study.
fn sigma_study(a: &TextureBenchArgs, default: Option<SigmaStudy>) -> Result<Option<SigmaStudy>> {
    let Some(mut study) = default else { return Ok(None) };
    if !a.sigma_scenes.is_empty() {
        study.scenes = a
            .sigma_scenes
            .iter()
            .map(|s| SceneKind::parse(s).map_err(|e| anyhow::anyhow!("--sigma-scenes: {e}")))
            .collect::<Result<_>>()?;
    }
    Ok(Some(study))
}

fn texture_bench(a: TextureBenchArgs) -> Result<()> {
    let cfg = texture_config(&a)?;
    create_dir(&a.out)?;
    let p = Progress::new("texture");
    let summary = run_texture_bench(&cfg, &a.out, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    println!(
        "wrote {} ({} records) in {:.1} s",
        summary.index.display(),
        summary.records.len(),
        summary.seconds
    );
    Ok(())
}

/// Loads the user's `--texture` (linear RGBA, opaque) with its file name as the label.
fn user_texture(path: Option<&Path>) -> Result<Option<(String, Image<glam::Vec4>)>> {
    let Some(path) = path else { return Ok(None) };
    let img = io::load_color(path)?;
    let label =
        path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    Ok(Some((label, img.map(|c| c.extend(1.0)))))
}

fn texture_render(a: TextureRenderArgs) -> Result<()> {
    use renderlab_texture::reference::{reference, PixelFilter};
    if !(8..=4096).contains(&a.width) || !(8..=4096).contains(&a.height) {
        bail!("--width/--height: {}x{}: each side must lie in 8..=4096", a.width, a.height);
    }
    if a.samples == 0 || a.samples > 128 {
        bail!("--samples: {} must lie in 1..=128", a.samples);
    }
    io::check_output(&a.out)?;
    let kind = SceneKind::parse(&a.scene).map_err(|e| anyhow::anyhow!("--scene: {e}"))?;
    let choice = match a.filter.as_str() {
        "reference" | "reference-box" => None,
        f => Some(f.parse::<FilterSpec>().map_err(|e| anyhow::anyhow!("--filter: {e}"))?),
    };
    let user = user_texture(a.texture.as_deref())?;
    let mut scene = TestScene::new(kind, a.width, a.height)?;
    if let Some((label, img)) = user {
        scene = scene.with_texture(img, &label);
    }
    let surface = scene.surface();
    let started = std::time::Instant::now();
    let img = match choice {
        None => {
            let pf = if a.filter == "reference" { PixelFilter::GAUSSIAN } else { PixelFilter::Box };
            reference(&scene, pf, a.samples, 1)?.image
        }
        Some(f) => scene.render_spec(&surface, &f),
    };
    let ms = started.elapsed().as_secs_f64() * 1e3;
    io::save_color(&a.out, &img)?;
    println!(
        "{} with {}: {}x{}, {ms:.0} ms; wrote {}",
        kind.name(),
        a.filter,
        a.width,
        a.height,
        a.out.display()
    );
    Ok(())
}
