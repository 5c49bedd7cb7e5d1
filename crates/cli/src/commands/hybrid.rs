//! `hybrid render`, `hybrid bench` and `merge`.

use crate::args::*;
use crate::progress::Progress;
use anyhow::{anyhow, bail, Context, Result};
use renderlab_core::{io, Image};
use renderlab_hybrid::{memory, HybridRenderer, StageConfig};
use renderlab_lab::hybrid_lab::{
    merge_runs, run_hybrid_bench, scenes, Existing, HybridBenchConfig, HybridSummary, RunSettings, Shard,
    SweepKind,
};

/// The largest side `--resolution` accepts.
const MAX_SIDE: u32 = 16384;

/// Checks a `--resolution` (parsed by [`parse_size`]): each side in 1..=[`MAX_SIDE`], and
/// the frame within the renderer's memory budget (`bench`: a run's frame and reference at
/// once), refused in one line before any work.
fn resolution((w, h): (u32, u32), bench: bool) -> Result<(u32, u32)> {
    if w > MAX_SIDE || h > MAX_SIDE {
        bail!("--resolution {w}x{h}: each side must lie in 1..={MAX_SIDE}");
    }
    check_memory("--resolution", w, h, bench)?;
    scenes::check_resolution(w, h).map_err(|e| anyhow!("--resolution: {e}"))?;
    Ok((w, h))
}

/// Refuses a frame whose estimated peak memory ([`memory::estimate`]) exceeds
/// [`memory::BUDGET`], naming the largest frame of that aspect that fits.
fn check_memory(what: &str, w: u32, h: u32, bench: bool) -> Result<()> {
    let kind = if bench { memory::Run::Bench } else { memory::Run::Render };
    let need = memory::estimate(kind, u64::from(w) * u64::from(h));
    if need > memory::BUDGET {
        let (fw, fh) = memory::largest_frame(kind, w, h);
        bail!(
            "{what} {w}x{h} needs about {:.1} GiB, over the {} GiB memory budget; the largest frame of this aspect is {fw}x{fh} ({} Mpixel at most)",
            renderlab_core::memory::gib(need),
            memory::BUDGET >> 30,
            memory::max_pixels(kind) / 1_000_000
        );
    }
    Ok(())
}

/// Refuses a scene whose meshes' `triangles` and frame together exceed [`memory::BUDGET`]
/// ([`memory::estimate_with_scene`]), once the scene is loaded and before the renderer
/// builds anything for it.
fn check_scene_memory(spec: &str, triangles: u64, w: u32, h: u32) -> Result<()> {
    let need = memory::estimate_with_scene(memory::Run::Render, u64::from(w) * u64::from(h), triangles);
    if need > memory::BUDGET {
        bail!(
            "{spec}: {triangles} triangles at {w}x{h} need about {:.1} GiB, over the {} GiB memory budget (about {} bytes per triangle); use a smaller frame or a lighter scene",
            renderlab_core::memory::gib(need),
            memory::BUDGET >> 30,
            memory::PER_TRIANGLE
        );
    }
    Ok(())
}

/// `renderlab hybrid render`: one image.
pub(super) fn render(a: HybridRenderArgs) -> Result<()> {
    super::checks::check_out_file("--out", &a.out)?;
    let size = a.resolution.map(|s| resolution(s, false)).transpose()?;
    let config = StageConfig::from_flags(|name| a.stages.get(name)).map_err(|e| anyhow!(e))?;
    if let Some(spp) = a.reference {
        if !(1..=1 << 20).contains(&spp) {
            bail!("--reference: {spp} must lie in 1..=1048576");
        }
    }
    let (scene, warnings) = scenes::resolve(&a.scene)?;
    for w in &warnings {
        eprintln!("renderlab: warning: {}: {w}", a.scene);
    }
    let name = match &a.camera {
        Some(n) => n.clone(),
        None => scene.cameras[0].name.clone(),
    };
    let own = scene.cameras.iter().find(|c| c.name == name).map(|c| (c.camera.width, c.camera.height));
    let (w, h) = size.or(own).unwrap_or((1, 1));
    check_memory(&format!("camera {name:?} of {}:", a.scene), w, h, false)?;
    let triangles: u64 = scene.meshes.iter().map(|m| m.triangles.len() as u64).sum();
    check_scene_memory(&a.scene, triangles, w, h)?;
    let camera = scenes::camera(&scene, &name, w, h)?;
    let renderer = HybridRenderer::new(&scene)?;
    let started = std::time::Instant::now();
    let (hdr, what) = match a.reference {
        Some(spp) => {
            let r = renderer.reference(&camera, spp, a.seed)?;
            let what = format!(
                "path-traced reference, {} spp, {} rays; noise floor: PSNR between halves {:.2} dB (linear, peak 1), full reference about {:.2} dB",
                r.spp, r.rays, r.noise.psnr_halves, r.noise.psnr_full
            );
            (r.hdr, what)
        }
        None => {
            let f = renderer.render(&camera, &config, a.seed)?;
            let ms: Vec<String> =
                f.stage_ms.in_frame_order().iter().map(|(pass, ms)| format!("{pass} {ms:.1}")).collect();
            let what = format!("{}: {} rays; ms: {}", config.label(), f.rays.total(), ms.join(", "));
            (f.hdr, what)
        }
    };
    let seconds = started.elapsed().as_secs_f64();
    let image = Image::from_vec(w, h, hdr)?;
    io::save_color(&a.out, &image)?;
    println!("{} {} at {w}x{h}, {what}; {seconds:.2} s", scene.name, name);
    println!("wrote {}", a.out.display());
    Ok(())
}

/// `renderlab hybrid bench`: the sweeps.
pub(super) fn bench(a: HybridBenchArgs) -> Result<()> {
    let (width, height) = resolution(a.resolution, true)?;
    super::checks::check_out_dir("--out", &a.out)?;
    let cfg = HybridBenchConfig {
        scenes: if a.scenes.is_empty() {
            scenes::BUILTIN.iter().map(|s| s.to_string()).collect()
        } else {
            a.scenes.clone()
        },
        cameras: a.cameras.clone(),
        run: RunSettings {
            width,
            height,
            sweep: match a.sweep {
                SweepChoice::Thesis => SweepKind::Thesis,
                SweepChoice::Report => SweepKind::Report,
            },
            reference_spp: a.reference_spp,
            warmup: a.warmup,
            reps: a.reps,
            seed: a.seed,
            write_images: !a.no_images,
        },
        shard: a.shard.unwrap_or(Shard::WHOLE),
        existing: if a.resume { Existing::Resume } else { Existing::Refuse },
    };
    // Settings are checked (and scenes loaded) before anything is written.
    cfg.validate().context("hybrid bench")?;
    let p = Progress::new("hybrid");
    let summary = run_hybrid_bench(&cfg, &a.out, &|d, t, m| p.update(d, t, m));
    p.finish();
    print_summary(&summary?, "run");
    Ok(())
}

/// `renderlab merge`: the shards of one run into one report.
pub(super) fn merge(a: MergeArgs) -> Result<()> {
    let summary = merge_runs(&a.parts, &a.out)?;
    print_summary(&summary, &format!("merge of {} parts", a.parts.len()));
    Ok(())
}

fn print_summary(s: &HybridSummary, what: &str) {
    for f in &s.findings {
        println!("{f}");
    }
    println!("{}", s.headline);
    if s.manifest.shard != Shard::WHOLE {
        println!(
            "this is shard {}: combine all {} with `renderlab merge DIR1 … DIR{} --out DIR`",
            s.manifest.shard, s.manifest.shard.count, s.manifest.shard.count
        );
    }
    println!("wrote {} ({what}, {} rows)", s.index.display(), s.records.len());
}
