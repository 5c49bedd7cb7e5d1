//! The Perlin-noise lab: the texturing thesis's noise experiments (its §3.1, Fig. 3.2–3.5)
//! reproduced as figures, with the statistics the thesis did not give.
//!
//! * **3D paths** (Fig. 3.2–3.4): 1000 points whose x, y and z are three 1D noise functions of
//!   one parameter `t ∈ [0, 1)`. The thesis's Python package (`perlin-noise`) calls its
//!   *frequency* "octaves", so "octaves = 10" is one noise layer with 10 lattice cells per unit
//!   (see [`renderlab_noise::fractal`]). With the same seed and frequency on every axis the
//!   three functions are the same function, so every point has x = y = z and the "path" is a
//!   straight line along the diagonal; distinct seeds give distinct gradient tables and a path
//!   that wanders in 3D. The paths are drawn as x–y and x–z projections.
//! * **Octaves**: the Fig. 3.4 axes (frequencies 1, 2, 3) as functions of `t`, beside the
//!   thesis's own octave sum `P_i = P_{i−1} + noise(2^i·x)/2^i` for 1, 2, 4 and 10 octaves.
//! * **Clouds** (Fig. 3.5): four independently seeded 2D layers at frequencies 3, 6, 12, 24,
//!   weighted 1, ½, ¼, ⅛, summed on a 100×100 grid and min–max normalised to [0, 1]; written
//!   as grey PNGs with each layer beside it.
//! * **Water** (§3.2) and **smoke** (§3.3): animations (APNG) and stills, from
//!   [`crate::noise_motion`], with the per-frame measurements that separate the two ways of
//!   animating smoke.
//!
//! Everything is a pure function of the seeds and sizes, so the figures are identical on every
//! run and thread count. The still experiments take well under a second, the animations about
//! 12 s on 2 cores at the default [`crate::noise_motion::MotionConfig`].

use crate::error::Result;
use crate::heatmap::gray_image;
use crate::lab::Progress;
use crate::plot::PALETTE;
use crate::report::{format_number, Report};
use crate::results::{write_csv, write_json};
use plotters::prelude::*;
use renderlab_core::io::save_rgb8;
use renderlab_core::Image;
use renderlab_noise::{batch, normalize_min_max, Fractal, FractalKind, FractalParams, NoiseError, Perlin};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Points per path in the thesis's experiments.
pub const PATH_POINTS: usize = 1000;
/// Largest path accepted (points), so that a typo cannot allocate without bound.
pub const MAX_PATH_POINTS: usize = 1 << 24;
/// Largest clouds image side accepted, in pixels.
pub const MAX_CLOUDS_SIZE: u32 = 4096;

/// One coordinate of a path: a 1D noise function with its own frequency and seed (the Python
/// package's `PerlinNoise(octaves=frequency, seed=seed)`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AxisNoise {
    /// Lattice cells per unit of `t` (the Python package's "octaves").
    pub frequency: f32,
    /// Seed of this axis's permutation table.
    pub seed: u32,
}

/// One of the thesis's 3D-path experiments.
#[derive(Clone, Debug, PartialEq)]
pub struct PathExperiment {
    /// Short file-name-safe key (e.g. `fig3_2`).
    pub key: &'static str,
    /// Human-readable title with the thesis's figure number.
    pub title: &'static str,
    /// The noise function of x, y and z.
    pub axes: [AxisNoise; 3],
    /// Number of points (`t = i / points`).
    pub points: usize,
}

/// The thesis's three path experiments: Fig. 3.2 (frequency 10, seed 100 on every axis),
/// Fig. 3.3 (seeds 100, 101, 102) and Fig. 3.4 (frequencies 1, 2, 3 with seeds 100, 200, 300).
pub fn thesis_paths() -> Vec<PathExperiment> {
    let ax = |frequency, seed| AxisNoise { frequency, seed };
    vec![
        PathExperiment {
            key: "fig3_2",
            title: "Fig. 3.2: frequency 10, seed 100 on every axis",
            axes: [ax(10.0, 100), ax(10.0, 100), ax(10.0, 100)],
            points: PATH_POINTS,
        },
        PathExperiment {
            key: "fig3_3",
            title: "Fig. 3.3: frequency 10, seeds 100 / 101 / 102",
            axes: [ax(10.0, 100), ax(10.0, 101), ax(10.0, 102)],
            points: PATH_POINTS,
        },
        PathExperiment {
            key: "fig3_4",
            title: "Fig. 3.4: frequencies 1 / 2 / 3, seeds 100 / 200 / 300",
            axes: [ax(1.0, 100), ax(2.0, 200), ax(3.0, 300)],
            points: PATH_POINTS,
        },
    ]
}

/// Samples one 1D noise function at `t = origin + i·step` for `i < n`.
fn sample_line(fractal: &Fractal, origin: f32, step: f32, n: usize) -> Result<Vec<f32>> {
    let mut out = vec![0.0f32; n];
    batch::fill(fractal, [origin], [step], [n], &mut out)?;
    Ok(out)
}

/// One noise layer (a single octave) at `frequency` with `seed` on every axis.
fn layer(seed: u32, frequency: f32) -> Result<Fractal> {
    Ok(Fractal::new(Perlin::new(seed), FractalParams::new(1, frequency, 2.0, 0.5)?, FractalKind::Thesis))
}

/// The path of `axes` at `t = i / points`, `i < points`: point `i` is
/// `(x(t), y(t), z(t))`. Errors for a frequency that is not finite and positive or too high,
/// and for 0 or more than [`MAX_PATH_POINTS`] points.
pub fn noise_path(axes: &[AxisNoise; 3], points: usize) -> Result<Vec<[f32; 3]>> {
    if points == 0 || points > MAX_PATH_POINTS {
        return Err(
            NoiseError::Size { dims: vec![points], reason: "path points must lie in 1..=2^24" }.into()
        );
    }
    let step = 1.0 / points as f32;
    let mut coords = Vec::with_capacity(3);
    for a in axes {
        coords.push(sample_line(&layer(a.seed, a.frequency)?, 0.0, step, points)?);
    }
    Ok((0..points).map(|i| [coords[0][i], coords[1][i], coords[2][i]]).collect())
}

/// Largest distance of a path's points from the diagonal line x = y = z through the origin:
/// exactly 0 when the path lies on that line.
pub fn max_distance_from_diagonal(path: &[[f32; 3]]) -> f64 {
    path.iter()
        .map(|p| {
            let p = p.map(f64::from);
            let m = (p[0] + p[1] + p[2]) / 3.0;
            ((p[0] - m).powi(2) + (p[1] - m).powi(2) + (p[2] - m).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}

/// Settings of the clouds image (Fig. 3.5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CloudsConfig {
    /// Image side in pixels (thesis: 100); the image always covers the unit square.
    pub size: u32,
    /// Seed of the first layer; layer `k` uses `seed + k`.
    pub seed: u32,
    /// Number of layers (thesis: 4); layer `k` has frequency `frequency·2^k` and weight `2^−k`.
    pub layers: u32,
    /// Frequency of the first layer (thesis: 3).
    pub frequency: f32,
}

impl Default for CloudsConfig {
    /// The thesis's Fig. 3.5: 100×100, layers 3, 6, 12, 24 weighted 1, ½, ¼, ⅛, seed 100.
    fn default() -> Self {
        Self { size: 100, seed: 100, layers: 4, frequency: 3.0 }
    }
}

/// The clouds image and its layers.
#[derive(Clone, Debug)]
pub struct Clouds {
    /// The weighted sum, min–max normalised to [0, 1].
    pub image: Image<f32>,
    /// Each layer's raw noise (in [−1, 1]), unweighted, in layer order.
    pub layers: Vec<Image<f32>>,
    /// Range `(min, max)` of the weighted sum before normalisation.
    pub raw_range: (f32, f32),
    /// Statistics of the weighted sum before normalisation.
    pub raw_stats: Stats,
}

/// Computes the clouds of `cfg`, keeping every layer in [`Clouds::layers`]. Pixel `(i, j)`
/// samples the unit square at `(i/size, j/size)`, as the thesis's program does. Errors (naming
/// the parameter) for a size outside 1..=[`MAX_CLOUDS_SIZE`], a layer count outside 1..=32, or
/// a frequency that is not finite and positive or whose last layer would exceed
/// [`renderlab_noise::MAX_FREQUENCY`].
pub fn clouds(cfg: &CloudsConfig) -> Result<Clouds> {
    let mut layers = Vec::with_capacity(cfg.layers.min(renderlab_noise::MAX_OCTAVES) as usize);
    let mut c = clouds_streamed(cfg, &mut |_, img| {
        layers.push(img.clone());
        Ok(())
    })?;
    c.layers = layers;
    Ok(c)
}

/// Like [`clouds`], but hands each layer to `on_layer(k, raw noise)` as soon as it is computed
/// and keeps none ([`Clouds::layers`] is empty), so that memory stays at two images however
/// many layers there are (4096² pixels × 23 layers would otherwise hold 1.5 GB).
pub fn clouds_streamed(
    cfg: &CloudsConfig,
    on_layer: &mut dyn FnMut(usize, &Image<f32>) -> Result<()>,
) -> Result<Clouds> {
    if cfg.size == 0 || cfg.size > MAX_CLOUDS_SIZE {
        return Err(NoiseError::Size {
            dims: vec![cfg.size as usize; 2],
            reason: "clouds size must lie in 1..=4096",
        }
        .into());
    }
    // Validates the layer count and that the last layer's frequency stays representable.
    FractalParams::new(cfg.layers, cfg.frequency, 2.0, 0.5)?;
    let n = cfg.size as usize;
    let step = 1.0 / cfg.size as f32;
    let mut sum = vec![0.0f32; n * n];
    let mut img = Image::new(cfg.size, cfg.size, 0.0f32);
    for k in 0..cfg.layers {
        let f = (f64::from(cfg.frequency) * 2f64.powi(k as i32)) as f32;
        let v = img.pixels_mut();
        batch::fill_par(&layer(cfg.seed.wrapping_add(k), f)?, [0.0, 0.0], [step, step], [n, n], v)?;
        let w = 0.5f32.powi(k as i32);
        sum.iter_mut().zip(v.iter()).for_each(|(s, x)| *s += w * x);
        on_layer(k as usize, &img)?;
    }
    let raw_stats = Stats::of(&sum);
    let raw_range = normalize_min_max(&mut sum).unwrap_or((0.0, 0.0));
    Ok(Clouds { image: Image::from_vec(cfg.size, cfg.size, sum)?, layers: Vec::new(), raw_range, raw_stats })
}

/// Mean, standard deviation, minimum and maximum of the finite values of a sample.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Stats {
    /// Arithmetic mean.
    pub mean: f64,
    /// Population standard deviation.
    pub std: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Stats {
    /// Statistics of the finite entries of `values` (all NaN when there is none).
    pub fn of(values: &[f32]) -> Stats {
        let finite = || values.iter().filter(|v| v.is_finite()).map(|&v| f64::from(v));
        let n = finite().count();
        if n == 0 {
            return Stats { mean: f64::NAN, std: f64::NAN, min: f64::NAN, max: f64::NAN };
        }
        let mean = finite().sum::<f64>() / n as f64;
        let var = finite().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
        Stats {
            mean,
            std: var.sqrt(),
            min: finite().fold(f64::INFINITY, f64::min),
            max: finite().fold(f64::NEG_INFINITY, f64::max),
        }
    }
}

/// One row of the lab's statistics table (and of `results.csv`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StatRow {
    /// Which experiment (e.g. `Fig. 3.3`).
    pub experiment: String,
    /// Which quantity (an axis, a layer or the sum).
    pub quantity: String,
    /// Its statistics.
    #[serde(flatten)]
    pub stats: Stats,
}

/// Settings of a whole noise-lab run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NoiseLabConfig {
    /// The clouds experiment (the path experiments always use the thesis's settings).
    pub clouds: CloudsConfig,
    /// The water and smoke animations.
    pub motion: crate::noise_motion::MotionConfig,
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

/// Like [`run_noise_lab`] with the clouds settings of `cfg`.
pub fn run_noise_lab_with(out_dir: &Path, cfg: &NoiseLabConfig, progress: Progress) -> Result<NoiseSummary> {
    let total = 5;
    let mut files = Vec::new();
    let mut stats = Vec::new();
    let mut report = Report::new("Perlin noise: the thesis's experiments");
    report.paragraph(
        "The texturing thesis (chapter 3, summary §2.6 and §3.3) shows four pictures made with the \
         Python package perlin-noise: three 3D paths of 1000 points and a 100×100 image of \"clouds\". \
         It reports no numbers. Here each experiment is recomputed with renderlab-noise (improved \
         Perlin noise, quintic fade), drawn, and summarised by its statistics. One detail matters \
         for reading the thesis: the package's parameter \"octaves\" is a frequency (lattice cells \
         per unit), not a number of octaves. \"Octaves = 10\" is a single noise layer with 10 cells \
         over t ∈ [0, 1); the true octave sum of the thesis's formula is shown separately below.",
    );

    // --- The 3D paths ------------------------------------------------------------------
    progress(0, total, "3D paths");
    report.section("3D paths (Fig. 3.2–3.4)");
    report.paragraph(
        "Each path has 1000 points; point i is (x(t), y(t), z(t)) at t = i/1000, where each \
         coordinate is its own 1D noise function with the frequency and seed given. The thesis \
         drew them as 3D scatter plots; here each is shown as two projections, x–y and x–z, with \
         equal scales on both axes and the diagonal drawn dashed.",
    );
    report.paragraph(
        "Why Fig. 3.2 is a straight line: a noise function is a pure function of its seed, its \
         frequency and its argument. With seed 100 and frequency 10 on all three axes, x, y and z \
         are the same function of the same t, so x(t) = y(t) = z(t) exactly for every point: all \
         points lie on the diagonal x = y = z, and the path only runs back and forth along it (the \
         thesis's \"linear law\"). Distinct seeds (Fig. 3.3) build distinct permutation tables, \
         hence different gradients on each axis, and the coordinates become independent: the path \
         leaves the diagonal and wanders through 3D within the same range. Note also that gradient \
         noise is 0 on every lattice point, so each path passes through the origin whenever \
         frequency·t is a whole number for every axis: in Fig. 3.2 and 3.3 every tenth of t is a \
         loop out of the origin and back, which gives Fig. 3.3 its petals. Within one cell a \
         coordinate is g₀·s·(1 − fade(s)) + g₁·(s − 1)·fade(s) for the cell's two end gradients; \
         where two axes' end gradients happen to stand in the same ratio, that loop collapses into \
         a straight spoke (one shows in Fig. 3.3's x–y projection).",
    );
    let mut path_rows = Vec::new();
    for e in thesis_paths() {
        let path = noise_path(&e.axes, e.points)?;
        let dist = max_distance_from_diagonal(&path);
        let mut grid = Vec::new();
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
            grid.push((file, format!("{}: projection onto the x–{name} plane", e.title)));
        }
        report.paragraph(&format!(
            "{}. Largest distance of a point from the diagonal x = y = z: {}.",
            e.title,
            format_number(dist, 4)
        ));
        report.image_grid(&grid, 2);
        for (a, name) in ["x", "y", "z"].iter().enumerate() {
            let v: Vec<f32> = path.iter().map(|p| p[a]).collect();
            stats.push(StatRow {
                experiment: short_title(e.title).to_string(),
                quantity: format!("{name} (frequency {}, seed {})", e.axes[a].frequency, e.axes[a].seed),
                stats: Stats::of(&v),
            });
        }
        path_rows.push((e.key, dist));
    }

    // --- Octaves -----------------------------------------------------------------------
    progress(1, total, "octaves");
    report.section("Octaves");
    report.paragraph(
        "Top: the three coordinate functions of Fig. 3.4 as functions of t. The package's \
         \"octaves\" 1, 2 and 3 are frequencies: one, two and three lattice cells over [0, 1), each \
         curve 0 at its lattice points. Bottom: what the thesis's formula P_i = P_{i−1} + \
         noise(2^i·x)/2^i actually computes, for 1, 2, 4 and 8 octaves of the same noise (seed \
         100) over two cells: each octave adds detail at twice the frequency and half the \
         amplitude, so the curve keeps its large shape and gains a rougher, \"stepped\" look; \
         from 4 octaves on the added detail is barely visible at this scale (octave 5 has \
         amplitude 1/16). Every curve passes through 0 at each whole x: the thesis's sum reuses \
         the same noise at every octave, and every octave's lattice contains the integers, so all \
         octaves vanish together there (renderlab-noise's fBm shifts each octave's lattice to \
         avoid this).",
    );
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
    let f1 = "octaves_fig3_4_axes.svg";
    files.push(write_text(
        out_dir,
        f1,
        &line_svg("Fig. 3.4 coordinates: frequency 1, 2, 3", "t", "noise", &axis_curves, false),
    )?);
    // 2000 samples over two cells: 8 samples per cell of the 8th octave (frequency 128), so
    // the finest octave shown is resolved rather than aliased.
    let (n, span) = (2000usize, 2.0f32);
    let mut sum_curves = Vec::new();
    for octaves in [1u32, 2, 4, 8] {
        let f = Fractal::thesis(100, octaves)?;
        let v = sample_line(&f, 0.0, span / n as f32, n)?;
        stats.push(StatRow {
            experiment: "Octave sum".into(),
            quantity: format!("{octaves} octave{}", if octaves == 1 { "" } else { "s" }),
            stats: Stats::of(&v),
        });
        sum_curves.push((
            format!("{octaves} octave{}", if octaves == 1 { "" } else { "s" }),
            v.iter()
                .enumerate()
                .map(|(i, &y)| (i as f64 * f64::from(span) / n as f64, f64::from(y)))
                .collect(),
        ));
    }
    let f2 = "octaves_thesis_sum.svg";
    files.push(write_text(
        out_dir,
        f2,
        &line_svg("Thesis octave sum, seed 100, frequency 1", "x", "P(x)", &sum_curves, false),
    )?);
    report.image_grid(
        &[
            (f1, "The Fig. 3.4 coordinate functions: the package's \"octaves\" are frequencies"),
            (f2, "The thesis's octave sum (doubling frequency, halving amplitude)"),
        ],
        1,
    );

    // --- Clouds ------------------------------------------------------------------------
    progress(2, total, "clouds");
    let c = &cfg.clouds;
    report.section("Clouds (Fig. 3.5)");
    let freqs: Vec<String> =
        (0..c.layers).map(|k| format_freq(f64::from(c.frequency) * 2f64.powi(k as i32))).collect();
    let seeds: Vec<String> = (0..c.layers).map(|k| c.seed.wrapping_add(k).to_string()).collect();
    let weights: Vec<String> = (0..c.layers).map(|k| format_freq(0.5f64.powi(k as i32))).collect();
    let mut layer_items = Vec::new();
    let clouds = clouds_streamed(c, &mut |k, img| {
        let name = format!("clouds_layer{}.png", k + 1);
        let path = out_dir.join(&name);
        save_rgb8(&path, &gray_image(img, -1.0, 1.0))?;
        files.push(path);
        layer_items.push((name, format!("layer {}: frequency {}, weight {}", k + 1, freqs[k], weights[k])));
        stats.push(StatRow {
            experiment: "Clouds".into(),
            quantity: format!("layer {} (frequency {})", k + 1, freqs[k]),
            stats: Stats::of(img.pixels()),
        });
        Ok(())
    })?;
    report.paragraph(&format!(
        "{} layers of 2D noise at frequencies {} with weights {} (seeds {}), summed on a {s}×{s} \
         grid over the unit square and min–max normalised to [0, 1] (the thesis's step 7), shown in \
         grey as the thesis's imshow(cmap='gray') does. The weighted sum ranged over [{}, {}] \
         before normalisation. Below it, each layer on its own (raw noise, −1 black to +1 white).",
        c.layers,
        freqs.join(", "),
        weights.join(", "),
        seeds.join(", "),
        format_number(f64::from(clouds.raw_range.0), 3),
        format_number(f64::from(clouds.raw_range.1), 3),
        s = c.size,
    ));
    let clouds_png = out_dir.join("clouds.png");
    save_rgb8(&clouds_png, &gray_image(&clouds.image, 0.0, 1.0))?;
    files.push(clouds_png.clone());
    let caption = format!("Clouds: {} layers, {s}×{s} pixels (shown 420 px wide)", c.layers, s = c.size);
    report.raw_html(&scaled_figures(&[("clouds.png".to_string(), caption)], 1, 420));
    report.raw_html(&scaled_figures(&layer_items, 4, 200));
    stats.push(StatRow {
        experiment: "Clouds".into(),
        quantity: "weighted sum".into(),
        stats: clouds.raw_stats,
    });
    stats.push(StatRow {
        experiment: "Clouds".into(),
        quantity: "normalised image".into(),
        stats: Stats::of(clouds.image.pixels()),
    });

    // --- Water and smoke -----------------------------------------------------------------
    progress(3, total, "water and smoke");
    let motion = crate::noise_motion::water_and_smoke(out_dir, &cfg.motion, &mut report, &|d, t, m| {
        progress(d, t, m)
    })?;
    files.extend(motion.files);

    progress(4, total, "report");
    // --- Statistics ----------------------------------------------------------------------
    report.section("Statistics");
    report.paragraph(
        "Mean, standard deviation, minimum and maximum of each quantity drawn above (over the \
         1000 path points, the 2000 samples of an octave-sum curve, or the pixels of an image). Single noise \
         layers lie in [−1, 1] by construction; the normalised clouds span exactly [0, 1].",
    );
    let rows = stats
        .iter()
        .map(|r| {
            vec![
                r.experiment.clone(),
                r.quantity.clone(),
                format_number(r.stats.mean, 4),
                format_number(r.stats.std, 4),
                format_number(r.stats.min, 4),
                format_number(r.stats.max, 4),
            ]
        })
        .collect();
    report.table(&["experiment", "quantity", "mean", "std", "min", "max"], rows);
    files.push(write_results(out_dir, &stats)?);
    files.push(out_dir.join("results.csv"));

    let index = out_dir.join("index.html");
    report.write(&index)?;
    files.push(index.clone());
    let straight = path_rows.iter().find(|r| r.0 == "fig3_2").map_or(f64::NAN, |r| r.1);
    let wandering = path_rows.iter().find(|r| r.0 == "fig3_3").map_or(f64::NAN, |r| r.1);
    let findings = vec![
        format!(
            "Equal seeds on every axis give x = y = z (largest distance from the diagonal {}), \
             distinct seeds a 3D path (largest distance {}).",
            format_number(straight, 4),
            format_number(wandering, 3)
        ),
        format!(
            "Clouds: {} layers on {s}×{s}, weighted sum in [{}, {}] before normalisation.",
            c.layers,
            format_number(f64::from(clouds.raw_range.0), 3),
            format_number(f64::from(clouds.raw_range.1), 3),
            s = c.size
        ),
    ];
    let mut findings = findings;
    findings.extend(motion.findings);
    progress(total, total, "done");
    Ok(NoiseSummary { index, clouds_png, files, stats, findings })
}

/// Small images shown enlarged (`width` CSS pixels, pixels kept square and sharp), `columns`
/// per row, each linking to the file itself: a 100×100 image would otherwise show at 100 px.
fn scaled_figures(items: &[(String, String)], columns: usize, width: u32) -> String {
    use crate::report::escape_html;
    let mut h = format!("<div class=\"grid\" style=\"--cols: {columns}\">\n");
    for (path, caption) in items {
        let (src, cap) = (escape_html(path), escape_html(caption));
        h.push_str(&format!(
            "<figure><a href=\"{src}\"><img src=\"{src}\" alt=\"{cap}\" \
             style=\"width: {width}px; max-width: 100%; image-rendering: pixelated\"></a>\
             <figcaption>{cap}</figcaption></figure>\n"
        ));
    }
    h.push_str("</div>");
    h
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

const FONT: &str = "Helvetica, Arial, sans-serif";

/// Line chart of dense curves (no point markers, which would bury a 1000-point path) as an
/// SVG document. `square` draws a square plot with the same range on both axes and the
/// diagonal y = x dashed, so that a path on the diagonal reads as one at 45°. Curves with an
/// empty name are left out of the legend. Never panics: a drawing error is shown in the SVG.
fn line_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    curves: &[(String, Vec<(f64, f64)>)],
    square: bool,
) -> String {
    let (w, h) = if square { (560, 560) } else { (880, 520) };
    let mut svg = String::new();
    let error = {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        let r = draw_lines(&root, title, x_label, y_label, curves, square);
        r.and_then(|_| root.present().map_err(|e| e.into())).err().map(|e| e.to_string())
    };
    match error {
        None => svg,
        Some(e) => format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"60\"><text x=\"10\" y=\"30\">\
             {}: {}</text></svg>",
            crate::report::escape_html(title),
            crate::report::escape_html(&e)
        ),
    }
}

/// An axis tick value with at most three decimals, no trailing zeros and no "-0".
fn tick(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.replace('-', "−")
    }
}

fn padded(lo: f64, hi: f64) -> std::ops::Range<f64> {
    if !(lo.is_finite() && hi.is_finite()) {
        return -1.0..1.0;
    }
    let pad = ((hi - lo) * 0.05).max(1e-3);
    (lo - pad)..(hi + pad)
}

fn draw_lines(
    root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    curves: &[(String, Vec<(f64, f64)>)],
    square: bool,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let ok = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let all = || curves.iter().flat_map(|c| c.1.iter()).filter(ok);
    let range = |f: fn(&(f64, f64)) -> f64| {
        all().map(f).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
    };
    let (x0, x1) = range(|p| p.0);
    let (y0, y1) = range(|p| p.1);
    let (xr, yr) = if square {
        let r = padded(x0.min(y0), x1.max(y1));
        (r.clone(), r)
    } else {
        (padded(x0, x1), padded(y0, y1))
    };
    let mut chart = ChartBuilder::on(root)
        .caption(title, (FONT, 20))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(60)
        .build_cartesian_2d(xr.clone(), yr.clone())?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .max_light_lines(4)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .bold_line_style(RGBColor(0xdd, 0xe1, 0xe6))
        .light_line_style(RGBColor(0xf0, 0xf2, 0xf4))
        .draw()?;
    if square {
        let (lo, hi) = (xr.start, xr.end);
        chart.draw_series(DashedLineSeries::new(
            vec![(lo, lo), (hi, hi)],
            6,
            4,
            RGBColor(0x8a, 0x91, 0x9a).stroke_width(1),
        ))?;
    }
    let mut labelled = false;
    for (i, (name, pts)) in curves.iter().enumerate() {
        let (r, g, b) = PALETTE[i % PALETTE.len()];
        let color = RGBColor(r, g, b);
        let s = chart
            .draw_series(LineSeries::new(pts.iter().copied().filter(|p| ok(&p)), color.stroke_width(2)))?;
        if !name.is_empty() {
            labelled = true;
            s.label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        }
    }
    if labelled {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font((FONT, 13))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(0xdd, 0xe1, 0xe6))
            .draw()?;
    }
    Ok(())
}
