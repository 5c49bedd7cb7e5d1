//! The run: the paths, the octave curves, the clouds, the water and smoke animations and the
//! statistics, each written as it is computed; the page last.

use super::clouds::{clouds_streamed, CloudsConfig};
use super::motion::{water_and_smoke, MotionConfig};
use super::page::{self, stat_rows, Clouds as CloudsPage, Figure, Page, PathFigures};
use super::paths::{max_distance_from_diagonal, noise_path, sample_line, thesis_paths};
use super::stats::{StatRow, Stats};
use crate::error::Result;
use crate::heatmap::gray_image;
use crate::lab::Progress;
use crate::plot::line_svg;
use crate::report::format_number;
use crate::results::{write_csv, write_json};
use renderlab_core::io::save_rgb8;
use renderlab_noise::Fractal;
use std::path::{Path, PathBuf};

/// Settings of a whole noise-lab run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NoiseLabConfig {
    /// The clouds experiment (the path experiments always use the thesis's settings).
    pub clouds: CloudsConfig,
    /// The water and smoke animations.
    pub motion: MotionConfig,
}

/// What a noise-lab run wrote and found.
#[derive(Clone, Debug)]
pub struct NoiseSummary {
    /// The lab's `index.html`.
    pub index: PathBuf,
    /// The clouds PNG.
    pub clouds_png: PathBuf,
    /// Every file written (figures, images, results, index).
    pub files: Vec<PathBuf>,
    /// Statistics per experiment.
    pub stats: Vec<StatRow>,
    /// One-sentence findings for the index page and the console.
    pub findings: Vec<String>,
}

/// Runs the lab with the thesis's settings and writes everything to `out_dir` (which must
/// exist): SVG figures, clouds PNGs, `results.json`, `results.csv` and `index.html`.
pub fn run_noise_lab(out_dir: &Path, progress: Progress) -> Result<NoiseSummary> {
    run_noise_lab_with(out_dir, &NoiseLabConfig::default(), progress)
}

/// The plural ending of `n` octaves.
fn octaves_label(n: u32) -> String {
    format!("{n} octave{}", if n == 1 { "" } else { "s" })
}

/// Like [`run_noise_lab`] with the clouds settings of `cfg`.
pub fn run_noise_lab_with(out_dir: &Path, cfg: &NoiseLabConfig, progress: Progress) -> Result<NoiseSummary> {
    let total = 5;
    let mut files = Vec::new();
    let mut stats = Vec::new();

    // --- The 3D paths ------------------------------------------------------------------
    progress(0, total, "3D paths");
    let mut path_rows = Vec::new();
    let mut path_figures = Vec::new();
    for e in thesis_paths() {
        let path = noise_path(&e.axes, e.points)?;
        let dist = max_distance_from_diagonal(&path);
        let mut figures = Vec::new();
        for (j, name) in [(1usize, "y"), (2, "z")] {
            let pts: Vec<(f64, f64)> = path.iter().map(|p| (f64::from(p[0]), f64::from(p[j]))).collect();
            let file = format!("path_{}_x{name}.svg", e.key);
            let svg = line_svg(
                &format!("{} — x–{name}", short_title(e.title)),
                "x",
                name,
                &[(String::new(), pts)],
                true,
            );
            files.push(write_text(out_dir, &file, &svg)?);
            figures
                .push(Figure { file, caption: format!("{}: projection onto the x–{name} plane", e.title) });
        }
        path_figures.push(PathFigures { title: e.title, distance: format_number(dist, 4), figures });
        for (a, name) in ["x", "y", "z"].iter().enumerate() {
            let v: Vec<f32> = path.iter().map(|p| p[a]).collect();
            stats.push(StatRow::new(
                short_title(e.title),
                format!("{name} (frequency {}, seed {})", e.axes[a].frequency, e.axes[a].seed),
                Stats::of(&v),
            ));
        }
        path_rows.push((e.key, dist));
    }

    // --- Octaves -----------------------------------------------------------------------
    progress(1, total, "octaves");
    let fig34 = &thesis_paths()[2];
    let fig34_path = noise_path(&fig34.axes, fig34.points)?;
    let t_of = |i: usize| i as f64 / fig34.points as f64;
    let axis_curves: Vec<(String, Vec<(f64, f64)>)> = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(a, name)| {
            (
                format!("{name}: frequency {}, seed {}", fig34.axes[a].frequency, fig34.axes[a].seed),
                fig34_path.iter().enumerate().map(|(i, p)| (t_of(i), f64::from(p[a]))).collect(),
            )
        })
        .collect();
    let octave_axes = "octaves_fig3_4_axes.svg";
    files.push(write_text(
        out_dir,
        octave_axes,
        &line_svg("Fig. 3.4 coordinates: frequency 1, 2, 3", "t", "noise", &axis_curves, false),
    )?);
    // 2000 samples over two cells: 8 samples per cell of the 8th octave (frequency 128), so
    // the finest octave shown is resolved rather than aliased.
    let (n, span) = (2000usize, 2.0f32);
    let mut sum_curves = Vec::new();
    for octaves in [1u32, 2, 4, 8] {
        let f = Fractal::thesis(100, octaves)?;
        let v = sample_line(&f, 0.0, span / n as f32, n)?;
        stats.push(StatRow::new("Octave sum", octaves_label(octaves), Stats::of(&v)));
        sum_curves.push((
            octaves_label(octaves),
            v.iter()
                .enumerate()
                .map(|(i, &y)| (i as f64 * f64::from(span) / n as f64, f64::from(y)))
                .collect(),
        ));
    }
    let octave_sum = "octaves_thesis_sum.svg";
    files.push(write_text(
        out_dir,
        octave_sum,
        &line_svg("Thesis octave sum, seed 100, frequency 1", "x", "P(x)", &sum_curves, false),
    )?);

    // --- Clouds ------------------------------------------------------------------------
    progress(2, total, "clouds");
    let c = &cfg.clouds;
    let freqs: Vec<String> =
        (0..c.layers).map(|k| format_freq(f64::from(c.frequency) * 2f64.powi(k as i32))).collect();
    let seeds: Vec<String> = (0..c.layers).map(|k| c.seed.wrapping_add(k).to_string()).collect();
    let weights: Vec<String> = (0..c.layers).map(|k| format_freq(0.5f64.powi(k as i32))).collect();
    let mut layer_figures = Vec::new();
    let clouds = clouds_streamed(c, &mut |k, img| {
        let name = format!("clouds_layer{}.png", k + 1);
        let path = out_dir.join(&name);
        save_rgb8(&path, &gray_image(img, -1.0, 1.0))?;
        files.push(path);
        layer_figures.push(Figure {
            file: name,
            caption: format!("layer {}: frequency {}, weight {}", k + 1, freqs[k], weights[k]),
        });
        stats.push(StatRow::new(
            "Clouds",
            format!("layer {} (frequency {})", k + 1, freqs[k]),
            Stats::of(img.pixels()),
        ));
        Ok(())
    })?;
    let clouds_png = out_dir.join("clouds.png");
    save_rgb8(&clouds_png, &gray_image(&clouds.image, 0.0, 1.0))?;
    files.push(clouds_png.clone());
    stats.push(StatRow::new("Clouds", "weighted sum", clouds.raw_stats));
    stats.push(StatRow::new("Clouds", "normalised image", Stats::of(clouds.image.pixels())));
    let (raw_min, raw_max) =
        (format_number(f64::from(clouds.raw_range.0), 3), format_number(f64::from(clouds.raw_range.1), 3));

    // --- Water and smoke -----------------------------------------------------------------
    progress(3, total, "water and smoke");
    let motion = water_and_smoke(out_dir, &cfg.motion, &|d, t, m| progress(d, t, m))?;
    files.extend(motion.files);

    progress(4, total, "report");
    files.push(write_results(out_dir, &stats)?);
    files.push(out_dir.join("results.csv"));
    let index = out_dir.join("index.html");
    page::write(
        &index,
        &Page {
            paths: path_figures,
            octave_axes,
            octave_sum,
            clouds: CloudsPage {
                layers: c.layers,
                size: c.size,
                frequencies: freqs.join(", "),
                weights: weights.join(", "),
                seeds: seeds.join(", "),
                raw_min: raw_min.clone(),
                raw_max: raw_max.clone(),
                image: "clouds.png",
                layer_figures,
            },
            water: motion.water,
            smoke: motion.smoke_page,
            stats: stat_rows(&stats),
        },
    )?;
    files.push(index.clone());
    let straight = path_rows.iter().find(|r| r.0 == "fig3_2").map_or(f64::NAN, |r| r.1);
    let wandering = path_rows.iter().find(|r| r.0 == "fig3_3").map_or(f64::NAN, |r| r.1);
    let mut findings = vec![
        format!(
            "Equal seeds on every axis give x = y = z (largest distance from the diagonal {}), \
             distinct seeds a 3D path (largest distance {}).",
            format_number(straight, 4),
            format_number(wandering, 3)
        ),
        format!(
            "Clouds: {} layers on {s}×{s}, weighted sum in [{raw_min}, {raw_max}] before normalisation.",
            c.layers,
            s = c.size
        ),
    ];
    findings.extend(motion.findings);
    progress(total, total, "done");
    Ok(NoiseSummary { index, clouds_png, files, stats, findings })
}

/// The figure number part of an experiment title (`Fig. 3.2`).
fn short_title(title: &str) -> &str {
    title.split(':').next().unwrap_or(title)
}

/// A frequency or weight without trailing zeros (3, 0.5, 0.125).
fn format_freq(v: f64) -> String {
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Writes `results.json` and `results.csv`; returns the JSON path.
fn write_results(out_dir: &Path, stats: &[StatRow]) -> Result<PathBuf> {
    let json = out_dir.join("results.json");
    write_json(&json, stats)?;
    write_csv(out_dir.join("results.csv"), stats)?;
    Ok(json)
}

/// Writes `text` to `out_dir/name` atomically and returns the path.
fn write_text(out_dir: &Path, name: &str, text: &str) -> Result<PathBuf> {
    let path = out_dir.join(name);
    renderlab_core::io::write_atomic(&path, |out| out.write_all(text.as_bytes()))?;
    Ok(path)
}
