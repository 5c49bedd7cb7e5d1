//! The animated part of the noise lab: the water sequence and the smoke plume, each written
//! as an APNG animation with a few stills, and the measurement that separates the two ways of
//! animating smoke.
//!
//! The thesis animates smoke by adding `animation_factor · t` to the noise. That changes every
//! voxel by the same amount, so the plume only grows denser (and, once clamped, saturates): its
//! shape is frozen. Moving the sample point through the noise domain (rise plus curl-noise
//! swirl, [`renderlab_noise::smoke`]) changes the shape while the mean density stays put. The
//! lab measures both per frame: the mean density of the grid, and the Pearson correlation of
//! the grid with the first frame's (1 = the same shape up to brightness; falling values = the
//! smoke moves).

use super::page::{Figure, Smoke, SmokeAnimation, Water, WaterStill};
use crate::error::Result;
use crate::report::format_number;
use crate::results::{write_csv, write_json};
use renderlab_core::apng::ApngWriter;
use renderlab_noise::smoke::{Animation, DensityGrid, SmokeFilter, SmokeVolume};
use renderlab_noise::{SmokeParams, WaterParams};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Sizes and lengths of the water and smoke animations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionConfig {
    /// Water frame width and height in pixels.
    pub water_size: (u32, u32),
    /// Water frames in the animation.
    pub water_frames: u32,
    /// Smoke frame width and height in pixels.
    pub smoke_size: (u32, u32),
    /// Smoke density grid per side.
    pub smoke_grid: u32,
    /// Smoke frames per animation (one animation per animation method).
    pub smoke_frames: u32,
    /// Playback rate of the water animation (frames per second; the frames are 1/24 s apart).
    pub water_fps: u32,
    /// Playback rate of the smoke animations (frames per second; the frames are 1/24 s apart).
    pub smoke_fps: u32,
    /// Seconds between smoke frames (the smoke moves slowly: a larger step shows more motion).
    pub smoke_time_step: f32,
}

impl Default for MotionConfig {
    /// The report's settings: about 12 s of work on 2 cores.
    fn default() -> Self {
        MotionConfig {
            water_size: (480, 270),
            water_frames: 48,
            smoke_size: (192, 192),
            smoke_grid: 96,
            smoke_frames: 24,
            water_fps: 24,
            smoke_fps: 12,
            smoke_time_step: 1.0 / 6.0,
        }
    }
}

impl MotionConfig {
    /// Small, short animations for a quick look and for tests (well under a second).
    pub fn quick() -> Self {
        MotionConfig {
            water_size: (160, 90),
            water_frames: 4,
            smoke_size: (48, 48),
            smoke_grid: 32,
            smoke_frames: 4,
            smoke_time_step: 0.5,
            ..MotionConfig::default()
        }
    }
}

/// One smoke frame's measurements.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SmokeFrameStats {
    /// `advect` or `thesis`.
    pub animation: String,
    /// Frame index.
    pub frame: u32,
    /// Time in seconds.
    pub t: f32,
    /// Mean density over the grid.
    pub mean_density: f64,
    /// Pearson correlation of the grid with the first frame's grid.
    pub correlation_with_first: f64,
    /// Seconds to build the density, light grid and image of this frame.
    pub seconds: f64,
}

/// What the animated part wrote and found.
#[derive(Clone, Debug)]
pub struct MotionSummary {
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Per-frame smoke statistics (also in `smoke_frames.json` / `.csv`).
    pub smoke: Vec<SmokeFrameStats>,
    /// One-sentence findings.
    pub findings: Vec<String>,
    /// The water animation as the page shows it.
    pub water: Water,
    /// The smoke animations as the page shows them.
    pub smoke_page: Smoke,
}

/// Pearson correlation of two equally long value lists (0 when either is constant).
pub fn correlation(a: &[f32], b: &[f32]) -> f64 {
    let n = a.len().min(b.len());
    if n == 0 {
        return 0.0;
    }
    let mean = |v: &[f32]| v[..n].iter().map(|&x| f64::from(x)).sum::<f64>() / n as f64;
    let (ma, mb) = (mean(a), mean(b));
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (&x, &y) in a[..n].iter().zip(&b[..n]) {
        let (dx, dy) = (f64::from(x) - ma, f64::from(y) - mb);
        sab += dx * dy;
        saa += dx * dx;
        sbb += dy * dy;
    }
    if saa == 0.0 || sbb == 0.0 {
        0.0
    } else {
        sab / (saa * sbb).sqrt()
    }
}

fn mean_of(g: &DensityGrid) -> f64 {
    g.sum() / g.values().len().max(1) as f64
}

/// Renders the water animation and the two smoke animations into `out_dir` and returns what
/// was written, with what the page shows of it. `progress` receives the frame count.
pub fn water_and_smoke(
    out_dir: &Path,
    cfg: &MotionConfig,
    progress: &dyn Fn(usize, usize, &str),
) -> Result<MotionSummary> {
    let mut files = Vec::new();
    let total = (cfg.water_frames + 2 * cfg.smoke_frames) as usize;

    // --- Water -------------------------------------------------------------------------
    let water = WaterParams { width: cfg.water_size.0, height: cfg.water_size.1, ..Default::default() };
    let water_anim = out_dir.join("water.png");
    let mut anim =
        ApngWriter::create(&water_anim, water.width, water.height, cfg.water_frames, cfg.water_fps)?;
    let started = std::time::Instant::now();
    let mut stills = Vec::new();
    let still_at = [0, cfg.water_frames / 2, cfg.water_frames.saturating_sub(1)];
    renderlab_noise::water::render_water_sequence(&water, 0.0, cfg.water_frames, |i, img| -> Result<()> {
        anim.push(&img)?;
        if still_at.contains(&i) {
            let name = format!("water_frame{i}.png");
            let path = out_dir.join(&name);
            renderlab_core::io::save_color(&path, &img)?;
            files.push(path);
            stills.push(WaterStill {
                file: name,
                frame: i,
                t: format_number(f64::from(i as f32 * water.time_step), 3),
            });
        }
        progress(i as usize + 1, total, "water frames");
        Ok(())
    })?;
    anim.finish()?;
    let water_ms = started.elapsed().as_secs_f64() * 1e3 / f64::from(cfg.water_frames);
    files.push(water_anim);
    let water_page = Water {
        octaves: water.octaves,
        wavelength: water.wavelength.to_string(),
        amplitude: water.amplitude.to_string(),
        wind_x: water.wind[0].to_string(),
        wind_y: water.wind[1].to_string(),
        frames: cfg.water_frames,
        time_step: format_number(f64::from(water.time_step), 4),
        width: water.width,
        height: water.height,
        animation: "water.png",
        fps: cfg.water_fps,
        ms_per_frame: format_number(water_ms, 1),
        stills,
    };

    // --- Smoke -------------------------------------------------------------------------
    let base = SmokeParams {
        width: cfg.smoke_size.0,
        height: cfg.smoke_size.1,
        grid: cfg.smoke_grid,
        time_step: cfg.smoke_time_step,
        ..Default::default()
    };
    base.validate()?;
    let mut smoke_stats = Vec::new();
    // The first frame of the animation with the base parameters, reused as its filter still.
    let mut base_first_frame = None;
    let mut anim_items = Vec::new();
    let mut done = cfg.water_frames as usize;
    for (key, animation) in [
        ("advect", Animation::Advect),
        ("thesis", Animation::ThesisLiteral { animation_factor: THESIS_FACTOR }),
    ] {
        let params = SmokeParams { animation, ..base };
        let name = format!("smoke_{key}.png");
        let path = out_dir.join(&name);
        let mut anim =
            ApngWriter::create(&path, params.width, params.height, cfg.smoke_frames, cfg.smoke_fps)?;
        let mut first: Option<Vec<f32>> = None;
        let mut ms = 0.0;
        for i in 0..cfg.smoke_frames {
            let t = i as f32 * params.time_step;
            let started = std::time::Instant::now();
            let volume = SmokeVolume::build(&params, t)?;
            let img = volume.render();
            if i == 0 && params == base {
                base_first_frame = Some(img.clone());
            }
            let seconds = started.elapsed().as_secs_f64();
            ms += seconds * 1e3;
            anim.push(&img)?;
            let values = volume.density().values();
            let corr = match &first {
                None => 1.0,
                Some(f) => correlation(f, values),
            };
            smoke_stats.push(SmokeFrameStats {
                animation: key.to_string(),
                frame: i,
                t,
                mean_density: mean_of(volume.density()),
                correlation_with_first: corr,
                seconds,
            });
            if first.is_none() {
                first = Some(values.to_vec());
            }
            done += 1;
            progress(done, total, "smoke frames");
        }
        anim.finish()?;
        files.push(path);
        anim_items.push(SmokeAnimation {
            key,
            file: name,
            ms_per_frame: format_number(ms / f64::from(cfg.smoke_frames), 0),
        });
    }

    let last = |key: &str| smoke_stats.iter().rev().find(|s| s.animation == key).cloned();
    let first_of = |key: &str| smoke_stats.iter().find(|s| s.animation == key).cloned();
    let mut rows = Vec::new();
    let step = (cfg.smoke_frames / 6).max(1);
    for s in smoke_stats.iter().filter(|s| s.frame % step == 0 || s.frame + 1 == cfg.smoke_frames) {
        rows.push(vec![
            s.animation.clone(),
            s.frame.to_string(),
            format_number(f64::from(s.t), 3),
            format_number(s.mean_density, 4),
            format_number(s.correlation_with_first, 4),
        ]);
    }
    let json = out_dir.join("smoke_frames.json");
    write_json(&json, &smoke_stats)?;
    write_csv(out_dir.join("smoke_frames.csv"), &smoke_stats)?;
    files.push(json);
    files.push(out_dir.join("smoke_frames.csv"));

    // Filters side by side on the first frame: the thesis's Gaussian or median.
    let mut filter_items = Vec::new();
    for (key, filter, label) in [
        ("none", SmokeFilter::None, "no filter"),
        ("gaussian", SmokeFilter::Gaussian { sigma: 0.8 }, "Gaussian, σ = 0.8 voxels"),
        ("median", SmokeFilter::Median3, "3×3×3 median"),
    ] {
        let params = SmokeParams { filter, ..base };
        let img = match &base_first_frame {
            Some(img) if params == base => img.clone(),
            _ => SmokeVolume::build(&params, 0.0)?.render(),
        };
        let name = format!("smoke_filter_{key}.png");
        let path = out_dir.join(&name);
        renderlab_core::io::save_color(&path, &img)?;
        files.push(path);
        filter_items.push(Figure { file: name, caption: label.to_string() });
    }
    let smoke_page = Smoke {
        grid: base.grid,
        octaves: base.octaves,
        anisotropy: base.anisotropy.to_string(),
        frames: cfg.smoke_frames,
        time_step: format_number(f64::from(cfg.smoke_time_step), 3),
        rise_speed: base.rise_speed.to_string(),
        thesis_factor: THESIS_FACTOR.to_string(),
        animations: anim_items,
        frames_table: rows,
        filters: filter_items,
    };

    let mut findings = Vec::new();
    if let (Some(a0), Some(a1), Some(t0), Some(t1)) =
        (first_of("advect"), last("advect"), first_of("thesis"), last("thesis"))
    {
        findings.push(format!(
            "Smoke over {} s: moving through the noise domain changes the shape (correlation with \
             frame 0 falls to {}) at nearly constant mean density ({} → {}); the thesis's noise + k·t \
             keeps the shape (correlation {}) while the mean density climbs {} → {}.",
            format_number(f64::from(a1.t), 2),
            format_number(a1.correlation_with_first, 3),
            format_number(a0.mean_density, 4),
            format_number(a1.mean_density, 4),
            format_number(t1.correlation_with_first, 3),
            format_number(t0.mean_density, 4),
            format_number(t1.mean_density, 4),
        ));
    }
    Ok(MotionSummary { files, smoke: smoke_stats, findings, water: water_page, smoke_page })
}

/// The thesis's `animation_factor` used in the lab's literal animation (density per second).
pub const THESIS_FACTOR: f32 = 0.25;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn correlation_is_one_for_affine_copies_and_zero_for_constants() {
        let a: Vec<f32> = (0..100).map(|i| ((i * 37) % 11) as f32).collect();
        let b: Vec<f32> = a.iter().map(|&x| 3.0 * x + 2.0).collect();
        assert!((correlation(&a, &b) - 1.0).abs() < 1e-12);
        let c: Vec<f32> = a.iter().map(|&x| -x).collect();
        assert!((correlation(&a, &c) + 1.0).abs() < 1e-12);
        assert_eq!(correlation(&a, &[5.0; 100]), 0.0);
        assert_eq!(correlation(&[], &[]), 0.0);
    }

    #[test]
    fn smoke_measurements_separate_the_two_animations() {
        let dir = tempfile::tempdir().unwrap();
        let cfg = MotionConfig { water_size: (32, 18), smoke_size: (24, 24), ..MotionConfig::quick() };
        let s = water_and_smoke(dir.path(), &cfg, &|_, _, _| {}).unwrap();
        for f in [
            "water.png",
            "smoke_advect.png",
            "smoke_thesis.png",
            "smoke_frames.csv",
            "smoke_filter_median.png",
        ] {
            assert!(dir.path().join(f).is_file(), "{f}");
        }
        let last = |k: &str| s.smoke.iter().rev().find(|r| r.animation == k).unwrap().clone();
        let first = |k: &str| s.smoke.iter().find(|r| r.animation == k).unwrap().clone();
        let (a0, a1, t0, t1) = (first("advect"), last("advect"), first("thesis"), last("thesis"));
        // Advection changes the shape, the thesis's formula barely does but adds density.
        assert!(a1.correlation_with_first < t1.correlation_with_first, "{a1:?} {t1:?}");
        assert!(t1.correlation_with_first > 0.9, "{t1:?}");
        assert!(t1.mean_density > t0.mean_density * 1.05, "{t0:?} {t1:?}");
        assert!((a1.mean_density / a0.mean_density - 1.0).abs() < 0.25, "{a0:?} {a1:?}");
    }
}
