//! The run: rasterize each view, time every technique, then measure its error.

use super::config::{resolve, Backend, ReliefBenchConfig};
use super::gpu_findings::gpu_findings;
use super::gpu_phase::{choose_pipelines, time_gpu_phase, GpuConfig, PhaseCost};
use super::gpu_side::{self, GpuAnalysis};
use super::page::{write_report, GpuPart, ImageSet};
use super::record::{label, slug, Measured, RecordBackend, ReliefRecord, ReliefSummary};
use super::uv_error::{mean_and_p95, offset_depth_error, uv_error_map, write_frame_images, FrameImages};
use super::verdicts::{findings, headline};
use crate::fixtures::{benchmark_camera, benchmark_scene};
use crate::lab::Progress;
use crate::metrics::compare;
use crate::results::{write_csv, write_json};
use crate::timing::{measure, measure_round_robin, Timing};
use glam::Vec2;
use rayon::prelude::*;
use renderlab_core::io::save_color;
use renderlab_core::{Camera, CoreError, Material, Scene};
use renderlab_gpu::ReliefRenderer;
use renderlab_raster::{rasterize, GBuffer};
use renderlab_relief::fused::{render_fused, render_fused_records, FusedFrame};
use renderlab_relief::render::patch::median_world_per_uv;
use renderlab_relief::render::{check, render, render_reference, trace_only};
use renderlab_relief::{
    patches_from_scene, Frame, FrameInput, Kernel, KernelChoice, Map, PatchInfo, ReliefMaterial, Shading,
    Technique,
};
use std::path::Path;

/// A rasterized view: the G-buffer the relief renderer shades, and the patch behind each
/// pixel (for the pixel-depth offset).
pub struct View {
    /// View angle, degrees.
    pub angle: f32,
    /// Per-pixel surface points.
    pub gbuffer: GBuffer,
    /// Per-pixel patches ([`patches_from_scene`]).
    pub patches: Vec<PatchInfo>,
}

impl View {
    /// Rasterizes `scene` from `camera`.
    pub fn new(scene: &Scene, camera: &Camera, angle: f32) -> Self {
        let gbuffer = rasterize(scene, camera);
        let patches = patches_from_scene(scene, gbuffer.pixels());
        Self { angle, gbuffer, patches }
    }

    /// The renderer's view of it.
    pub fn input(&self) -> FrameInput<'_> {
        FrameInput::new(self.gbuffer.width(), self.gbuffer.height(), self.gbuffer.pixels())
            .with_patches(&self.patches)
    }

    /// The relief's full depth in world units for a material of depth scale `height_scale`
    /// (UV per unit depth): the scale times the median world units per UV of the covered
    /// pixels (0 when none is covered).
    pub fn relief_depth(&self, height_scale: f32) -> f32 {
        height_scale * median_world_per_uv(&self.patches)
    }
}

/// Runs the relief benchmark on `material` (the thesis: bricks, alone on its wall) and writes
/// everything under `out`.
///
/// Per angle, three phases that never overlap:
///
/// 1. **CPU**: every CPU method timed in turn, repetition after repetition, so that a passing
///    disturbance does not fall on one method alone; then each one's trace alone.
/// 2. **GPU** (with a GPU backend, [`ReliefBenchConfig::backend`]): every technique on every
///    pipeline of the run timed with nothing else running (`gpu_phase.rs`): steady
///    batches warmed up until successive rounds agree, then whole frames with read-back in
///    turn, whose median the paired CPU method's median is divided by for `cpu_over_gpu`
///    (`both`).
/// 3. **Untimed**: the references, then the counted render, the metrics and the images of
///    every method at once, spread over the threads, and each GPU configuration's debug
///    frame. The order changes no figure and no byte of an image.
///
/// With a GPU backend the device is opened first (no adapter, or a frame larger than its
/// textures, is an error before any work unless [`ReliefBenchConfig::gpu_required`] is off,
/// in which case the summary says the GPU was skipped), and the pipelines are chosen
/// ([`ReliefBenchConfig::pipelines`]; `auto` probes once).
pub fn run_relief_bench(
    material: &Material,
    cfg: &ReliefBenchConfig,
    out: &Path,
    progress: Progress,
) -> crate::Result<ReliefSummary> {
    cfg.complexity.validate()?;
    let (gpu_ctx, gpu_note) = gpu_side::open(cfg)?;
    let methods = resolve(&cfg.techniques)?;
    let needs_cone = methods.iter().any(|(t, _)| t.needs_map(Map::Cone));
    progress(0, 1, "preparing material (pyramids, complexity map, cone map)");
    let mat = ReliefMaterial::with_cone_size(material, &cfg.complexity, needs_cone.then_some(cfg.cone_size));
    for &(t, kernel) in &methods {
        check(t, kernel, std::slice::from_ref(&mat))?;
    }
    // The output directory is made only once every setting has been checked.
    let img_dir = out.join("img");
    std::fs::create_dir_all(&img_dir).map_err(|source| CoreError::Write { path: img_dir.clone(), source })?;
    let scene = benchmark_scene(material.clone());
    let mats = std::slice::from_ref(&mat);
    let mut renderer = match &gpu_ctx {
        Some(ctx) => Some(ReliefRenderer::new(ctx, &scene, mats)?),
        None => None,
    };
    let (pipelines, probe) = match &mut renderer {
        Some(r) => {
            progress(0, 1, "choosing the GPU pipelines");
            choose_pipelines(r, cfg)?
        }
        None => (Vec::new(), None),
    };
    // The GPU configurations at an angle: each technique once, whatever its CPU kernels, on
    // each pipeline.
    let gpu_configs = |angle: f32| -> Vec<GpuConfig> {
        let mut v: Vec<GpuConfig> = Vec::new();
        for &(t, _) in &methods {
            if cfg.on_gpu(t, angle) && v.iter().all(|&(g, _)| g != t) {
                v.extend(pipelines.iter().map(|&p| (t, p)));
            }
        }
        v
    };
    let cpu_count = if cfg.backend.cpu() { methods.len() } else { 0 };
    let total: usize = cfg.angles.iter().map(|&a| cpu_count + gpu_configs(a).len()).sum();
    let mut done = 0;
    let (mut records, mut gpu_records) = (Vec::new(), Vec::new());
    let mut images: Vec<ImageSet> = Vec::new();
    let mut gpu_cost = PhaseCost::default();
    // Per angle: the error of a depth buffer without the pixel-depth offset (the flat top
    // surface), a fraction of the relief's depth.
    let mut flat_depth: Vec<(f32, f64)> = Vec::new();
    for &angle in &cfg.angles {
        let camera = benchmark_camera(angle, cfg.width, cfg.height);
        let view = View::new(&scene, &camera, angle);
        // One framebuffer serves every timed frame, as a renderer reuses its own.
        let mut frame = FusedFrame::new(cfg.width, cfg.height);
        let mut timings: Vec<(Timing, Timing)> = Vec::with_capacity(cpu_count);
        if cpu_count > 0 {
            progress(done, total, &format!("{angle}°: {} CPU methods, timed in turn", methods.len()));
            // The whole frame a user waits for: scene to 8-bit pixels, rasterization included.
            let passes = measure_round_robin(cfg.warmup, cfg.reps, methods.len(), |k| {
                let (t, kernel) = methods[k];
                render_fused(&scene, &camera, mats, t, kernel, true, &mut frame)
            })?;
            for (&(t, kernel), pass) in methods.iter().zip(passes) {
                progress(done, total, &format!("{angle}°: {}", label(t, kernel)));
                let (trace, _) = measure(0, cfg.reps, || trace_only(view.input(), mats, t, kernel));
                timings.push((pass, trace));
                done += 1;
            }
        }
        let configs = if renderer.is_some() { gpu_configs(angle) } else { Vec::new() };
        let gpu_times = match &mut renderer {
            Some(r) if !configs.is_empty() => {
                progress(
                    done,
                    total,
                    &format!("{angle}°: GPU, {} configurations, timed in turn", configs.len()),
                );
                let times = time_gpu_phase(r, &camera, &configs, cfg, &mut gpu_cost)?;
                done += configs.len();
                times
            }
            _ => Vec::new(),
        };
        // Each GPU configuration's CPU partner under `both`: its technique's method on the
        // fastest CPU kernel, with that method's whole-frame median.
        let partner: Vec<Option<(usize, f64)>> = configs
            .iter()
            .map(|&(t, _)| {
                let i = paired_method(&methods, t).filter(|_| cfg.backend == Backend::Both)?;
                Some((i, timings.get(i)?.0.median_ms))
            })
            .collect();
        // A CPU method's ratio: against the fastest whole frame among its technique's
        // pipelines.
        let cpu_ratio = |i: usize| -> Option<f64> {
            let fastest = partner
                .iter()
                .zip(&gpu_times)
                .filter(|(p, _)| p.is_some_and(|(j, _)| j == i))
                .map(|(_, g)| g.wall.median_ms)
                .reduce(f64::min)?;
            Some(timings[i].0.median_ms / fastest)
        };
        progress(done, total, &format!("{angle}°: references, errors and images"));
        let mut refs: Vec<(Shading, Frame)> = Vec::new();
        for &(t, _) in &methods {
            let shading = t.shading();
            if refs.iter().all(|(s, _)| *s != shading) {
                let r = render_reference(view.input(), mats, t, scene.lighting, scene.background);
                if cfg.write_images {
                    let name = format!("reference_{}_{}.png", shading_name(shading), angle);
                    save_color(img_dir.join(&name), &r.image)?;
                }
                refs.push((shading, r));
            }
        }
        if let Some((_, r)) = refs.first() {
            let (w, h) = (view.gbuffer.width(), view.gbuffer.height());
            let points = view.gbuffer.pixels();
            let top = renderlab_core::Image::from_fn(w, h, |x, y| {
                points[(y * w + x) as usize].map_or(0.0, |sp| sp.depth)
            });
            let covered = renderlab_core::Image::from_fn(w, h, |x, y| points[(y * w + x) as usize].is_some());
            let relief = view.relief_depth(material.height_scale);
            flat_depth.push((angle, offset_depth_error(&top, &covered, &r.view_depth, &r.mask, relief)));
        }
        let ctx = Analysis {
            view: &view,
            scene: &scene,
            camera: &camera,
            mats,
            refs: &refs,
            material,
            img_dir: &img_dir,
            cfg,
        };
        let analysed: Vec<(ReliefRecord, Option<ImageSet>, Option<Frame>)> = methods
            .par_iter()
            .zip(&timings)
            .enumerate()
            .map(|(i, (&(t, kernel), &(pass, trace)))| {
                let ratio = cpu_ratio(i);
                ctx.analyse(t, kernel, pass, trace, ratio, ratio.is_some())
            })
            .collect::<crate::Result<_>>()?;
        if let (Some(r), Some(gctx)) = (&mut renderer, &gpu_ctx) {
            let relief_depth = view.relief_depth(material.height_scale);
            let g = GpuAnalysis { report: &gctx.report, material, img_dir: &img_dir, cfg, relief_depth };
            for ((&config, &times), paired) in configs.iter().zip(&gpu_times).zip(&partner) {
                let cpu = paired.and_then(|(i, ms)| analysed[i].2.as_ref().map(|f| (&f.image, &f.mask, ms)));
                let reference = reference_for(&refs, config.0);
                let (rec, set) = g.record(r, &camera, config, angle, times, reference, cpu)?;
                gpu_records.push(rec);
                images.extend(set);
            }
        }
        for (rec, set, _) in analysed {
            records.push(rec);
            images.extend(set);
        }
    }
    progress(done, total, "writing results and report");
    let all: Vec<ReliefRecord> = records.iter().chain(&gpu_records).cloned().collect();
    write_json(out.join("results.json"), &all)?;
    write_csv(out.join("results.csv"), &all)?;
    let gpu_pipelines: Vec<&'static str> = pipelines.iter().map(|p| p.name()).collect();
    let mut findings = findings(&records, &cfg.angles);
    findings.extend(depth_offset_finding(&records, &flat_depth));
    if let Some(reason) = &probe {
        findings.push(format!("GPU pipeline chosen by the start-up probe: {reason}."));
    }
    findings.extend(gpu_findings(&records, &gpu_records, &cfg.angles, &cfg.steady));
    if let (Some(ctx), true) = (&gpu_ctx, gpu_cost.frames > 0) {
        findings.push(gpu_cost.finding(ctx.report.timestamps));
    }
    findings.extend(gpu_note.clone());
    let headline = headline(&records, &cfg.angles);
    let index = out.join("index.html");
    let gpu = GpuPart {
        records: &gpu_records,
        note: gpu_note.as_deref(),
        adapter: gpu_ctx.as_ref().map(|c| &c.report),
        probe: probe.as_deref(),
    };
    write_report(&index, material, cfg, &records, gpu, &findings, &images)?;
    progress(total, total, "done");
    records.extend(gpu_records);
    Ok(ReliefSummary { records, findings, headline, index, gpu_note, gpu_pipelines, pipeline_probe: probe })
}

/// What the pixel-depth offset buys: per angle, the mean depth error of the flat top surface
/// (a depth buffer without the offset) against the best and the median CPU technique's
/// offset depth, as fractions of the relief's depth.
fn depth_offset_finding(records: &[ReliefRecord], flat: &[(f32, f64)]) -> Option<String> {
    let parts: Vec<String> = flat
        .iter()
        .filter_map(|&(angle, flat_err)| {
            let mut errs: Vec<(f64, String)> = records
                .iter()
                .filter(|r| r.angle_deg == angle && r.family != "basic" && r.family != "normal")
                .map(|r| (r.depth_error, label(r.technique, r.kernel)))
                .collect();
            errs.sort_by(|a, b| a.0.total_cmp(&b.0));
            let best = errs.first()?;
            let median = &errs[errs.len() / 2];
            Some(format!(
                "{angle}°: flat {:.1} %, {} {:.3} %, median ({}) {:.2} %",
                flat_err * 100.0,
                best.1,
                best.0 * 100.0,
                median.1,
                median.0 * 100.0
            ))
        })
        .collect();
    (!parts.is_empty()).then(|| {
        format!(
            "Pixel-depth offset: mean depth error against the exact hit, in % of the relief's depth, without the offset (the flat top surface) and with it: {}.",
            parts.join("; ")
        )
    })
}

/// The method a GPU configuration of `t` is paired with: the one on `t`'s fastest kernel
/// here (the kernel `auto` picks), else `t`'s first.
fn paired_method(methods: &[(Technique, Kernel)], t: Technique) -> Option<usize> {
    let best = t.kernel(KernelChoice::Auto).ok();
    methods
        .iter()
        .position(|&(m, k)| m == t && Some(k) == best)
        .or_else(|| methods.iter().position(|&(m, _)| m == t))
}

/// What the untimed half of a run needs to turn one technique's timings into a record.
struct Analysis<'a> {
    view: &'a View,
    scene: &'a Scene,
    camera: &'a Camera,
    mats: &'a [ReliefMaterial],
    refs: &'a [(Shading, Frame)],
    material: &'a Material,
    img_dir: &'a Path,
    cfg: &'a ReliefBenchConfig,
}

impl Analysis<'_> {
    /// Renders `t`'s fused frame once more with its per-pixel records and counters,
    /// measures its error against the reference of its shading and its precision against
    /// the float renderer's frame, and writes its images; hands the frame back when `keep`
    /// (a GPU frame is to be compared with it). `cpu_over_gpu` is the ratio of its whole
    /// frame to the GPU's (`--backend both`).
    fn analyse(
        &self,
        t: Technique,
        kernel: Kernel,
        pass: Timing,
        trace: Timing,
        cpu_over_gpu: Option<f64>,
        keep: bool,
    ) -> crate::Result<(ReliefRecord, Option<ImageSet>, Option<Frame>)> {
        let (view, scene, angle) = (self.view, self.scene, self.view.angle);
        let (fused, rec) = render_fused_records(scene, self.camera, self.mats, t, kernel, true)?;
        let frame = fused.with_records(rec);
        let float = render(view.input(), self.mats, t, kernel, scene.lighting, scene.background, false)?;
        let psnr_vs_float = crate::metrics::psnr(&frame.image, &float.image, Some(&frame.mask));
        let reference = reference_for(self.refs, t);
        let cmp = compare(&frame.image, &reference.image, Some(&frame.mask));
        // UV error is counted in texels of the height map, where the relief is defined (the
        // albedo may have another resolution).
        let height = &self.material.height;
        let tex_size = Vec2::new(height.width() as f32, height.height() as f32);
        let uv_map = uv_error_map(&frame.uv, &frame.mask, &reference.uv, tex_size);
        let (uv_mean, uv_p95) = mean_and_p95(&uv_map, &frame.mask);
        // The fused frame keeps no eye distances: the float frame's hits are the same.
        let relief = view.relief_depth(self.material.height_scale);
        let depth_error = offset_depth_error(
            &float.view_depth,
            &float.mask,
            &reference.view_depth,
            &reference.mask,
            relief,
        );
        let covered = frame.mask.pixels().iter().filter(|&&m| m).count();
        let mean_layers = if covered == 0 {
            0.0
        } else {
            frame.layers.pixels().iter().map(|&l| l as f64).sum::<f64>() / covered as f64
        };
        let measured = Measured {
            technique: t,
            kernel,
            angle_deg: angle,
            frame: pass,
            metrics: cmp.metrics,
            mean_layers,
            uv_error: (uv_mean, uv_p95),
            depth_error,
            covered_pixels: covered,
        };
        let rec = ReliefRecord {
            trace_ms: trace.median_ms,
            cpu_over_gpu,
            samples_per_pixel: frame.fetches_per_pixel(),
            psnr_vs_float_db: Some(psnr_vs_float),
            ..ReliefRecord::measured(
                RecordBackend::Cpu,
                format!("CPU ({} threads)", rayon::current_num_threads()),
                measured,
            )
        };
        if !self.cfg.write_images {
            return Ok((rec, None, keep.then_some(frame)));
        }
        let dir = self.img_dir;
        let base = format!("{}_{}", slug(t, kernel), angle);
        write_frame_images(
            dir,
            &base,
            FrameImages { image: &frame.image, layers: &frame.layers, mask: &frame.mask },
            &uv_map,
            &cmp.flip_map,
            t.layers(),
        )?;
        let set = ImageSet { angle, label: label(t, kernel), base, has_layers: t.layers() > 0 };
        Ok((rec, Some(set), keep.then_some(frame)))
    }
}

/// The reference of `t`'s shading among `refs` (the run renders one per shading it needs).
fn reference_for(refs: &[(Shading, Frame)], t: Technique) -> &Frame {
    &refs.iter().find(|(s, _)| *s == t.shading()).expect("a reference per shading").1
}

fn shading_name(s: Shading) -> &'static str {
    match s {
        Shading::Unlit => "unlit",
        Shading::Lit => "lit",
        Shading::LitShadowed => "shadowed",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shader_pairs_with_its_fastest_cpu_kernel() {
        let pom = Technique::parse("pom:32").unwrap();
        let basic = Technique::parse("basic").unwrap();
        let methods = [(basic, Kernel::Scalar), (pom, Kernel::Scalar), (pom, Kernel::Simd)];
        let fastest = if pom.kernel(KernelChoice::Auto).unwrap() == Kernel::Simd { 2 } else { 1 };
        assert_eq!(paired_method(&methods, pom), Some(fastest));
        assert_eq!(paired_method(&methods, basic), Some(0));
        assert_eq!(paired_method(&methods[..2], pom), Some(1), "the first when the fastest is not measured");
        assert_eq!(paired_method(&methods[..1], pom), None);
    }
}
