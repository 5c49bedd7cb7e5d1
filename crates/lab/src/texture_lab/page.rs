//! The texture lab's page: findings, the pixel-filter model and the reference's noise, the
//! rankings per model, the σ study, per-scene tables, the mapping modes and the images.

use super::sigma::rows as sigma_rows;
use super::{
    NoiseRecord, Ranking, SigmaRecord, TextureBenchConfig, TextureRecord, HEAT_MAX, NOISE_MARGIN_DB,
};
use crate::error::Result;
use crate::plot::{scatter_svg, Series};
use crate::report::{format_number, Report};
use std::path::Path;

/// Everything the page shows.
pub struct PageData<'a> {
    /// Every record.
    pub records: &'a [TextureRecord],
    /// Reference noise per scene and kernel.
    pub noise: &'a [NoiseRecord],
    /// Rankings per model.
    pub rankings: &'a [Ranking],
    /// The σ study.
    pub sigma: &'a [SigmaRecord],
    /// Findings.
    pub findings: &'a [String],
    /// Mapping-mode ratios (scene, incremental/direct, rows4/direct).
    pub ratios: &'a [(String, f64, f64)],
    /// Scene names and set-ups.
    pub scenes: &'a [(String, String)],
    /// Per scene: filters with images, whether a horizon crop exists.
    pub images: &'a [(String, Vec<String>, bool)],
    /// Seconds the run took.
    pub seconds: f64,
}

fn find<'a>(
    records: &'a [TextureRecord],
    scene: &str,
    method: &str,
    reference: &str,
) -> Option<&'a TextureRecord> {
    records
        .iter()
        .find(|r| r.kind == "filter" && r.scene == scene && r.method == method && r.reference == reference)
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// Writes the page.
pub fn write(path: &Path, cfg: &TextureBenchConfig, d: &PageData) -> Result<()> {
    let mut r = Report::new("Texture mapping and filtering lab");
    r.paragraph(&format!(
        "{} scenes × {} filters at {}×{} pixels (images and references on {} threads), plus the perspective-mapping evaluation modes. \
         Each filter reads the exact texture coordinate and Jacobian of the pixel centre (computed in f64 \
         from the scene's projective map), so its time and error are the filter's alone. Times are medians of \
         {} runs after {} warm-up, per surface pixel, on one thread (the filters take turns run by run); \
         fetches are counted in a separate pass. The run took {:.1} s.",
        cfg.scenes.len(),
        cfg.filters.len(),
        cfg.width,
        cfg.height,
        rayon::current_num_threads(),
        cfg.reps,
        cfg.warmup,
        d.seconds
    ));
    r.section("Findings");
    for f in d.findings {
        r.paragraph(f);
    }

    r.section("The pixel-filter model");
    let [model, second] = cfg.models();
    r.paragraph(&format!(
        "What a pixel sees is stated once: the lab's model is a {}; the second model is a {}. The \
         reference integrates the model, and every filter that has a kernel takes it from the same \
         description: EWA's weights are the model's Gaussian carried to texture space (its ellipse is the \
         kernel's truncation disc; the reconstruction term keeps a fixed ¼ texel² variance), and the \
         anisotropic filter's probes are Gaussian-weighted along the major axis so that probes and weights \
         together have the model's variance (anisoN:box is the GPU's equal-weight form, a one-pixel box). \
         Parameters in a filter's name (sigma=, cut=) override the model's. Every filter is scored against \
         both models.",
        model.describe(),
        second.describe()
    ));
    r.paragraph(
        "Why the Gaussian: a texture filter's job is to remove the frequencies the pixel grid cannot show. \
         The box's spectrum is a sinc whose first side lobe passes 22% of the amplitude above Nyquist, so a \
         box-filtered ground truth still contains aliasing (moiré on the checkerboard near the horizon); a \
         filter that antialiases better is charged for not reproducing it. The Gaussian of σ = ½ pixel \
         attenuates Nyquist to about 29% and twice Nyquist to under 1%, has no ringing, and is the kernel EWA \
         is derived from. Under magnification the box model favours sharp filters, under minification the \
         Gaussian favours smooth ones; both verdicts are shown.",
    );
    r.section("The reference and its noise");
    r.paragraph(&format!(
        "Ground truth: each pixel's value is the integral of the level-0 bilinear reconstruction of the \
         texture under the pixel filter, mapped exactly (f64 projective map). Samples belong to the screen: \
         every unit cell gets n×n jittered strata and each sample feeds every pixel whose kernel covers it \
         (the kernel's weight, normalised per pixel), so one set of samples serves every kernel. The density \
         adapts: a pilot pass of {p}² samples per cell measures the texture's variance under it, and the \
         cell gets enough strata (up to {m}²) that its mean's standard error is at most τ even without the \
         gain from stratification (first τ = {t}). Two references from independent seeds are computed; \
         their mean is the reference, and their difference measures its noise: the floor is the PSNR of one \
         half against the other plus 6.02 dB. While any floor is less than {margin} dB above the best \
         filter's PSNR against that reference, the least strata and 1/τ grow by the square root of the \
         shortfall in squared error (1 dB spare) and both halves are recomputed.",
        p = cfg.sampling.min_strata,
        m = cfg.sampling.max_strata,
        t = cfg.sampling.tolerance,
        margin = NOISE_MARGIN_DB
    ));
    let rows = d
        .noise
        .iter()
        .map(|n| {
            vec![
                n.scene.clone(),
                n.reference.clone(),
                format_number(n.samples_per_pixel, 0),
                n.max_samples_per_pixel.to_string(),
                format!("{} ({} rounds)", n.tolerance, n.rounds),
                format_number(n.halves_psnr_db, 2),
                format_number(n.floor_db, 2),
                format!("{} {}", n.best_filter, format_number(n.best_psnr_db, 2)),
                format_number(n.margin_db, 1),
                if n.met { "yes".into() } else { "no".into() },
            ]
        })
        .collect();
    r.table(
        &strings(&[
            "scene",
            "kernel",
            "samples/px",
            "max samples/px",
            "τ",
            "halves PSNR dB",
            "noise floor dB",
            "best filter dB",
            "margin dB",
            "≥ 10 dB",
        ]),
        rows,
    );
    r.paragraph(
        "The horizon: on the ground-plane scenes (checkerboard, zone plate) the plane is clipped at the depth \
         where one pixel's footprint spans one texture tile along its major axis (at the centre column); \
         beyond, up to and above the horizon, is sky. Every metric counts only pixels whose whole filter \
         support lies on the surface under both pixel filters (so quad edges and the clip line, which no \
         texture filter antialiases, are excluded).",
    );
    let rows: Vec<Vec<String>> = d.scenes.iter().map(|(n, desc)| vec![n.clone(), desc.clone()]).collect();
    r.table(&strings(&["scene", "set-up"]), rows);

    r.section("The best filter for each model");
    r.paragraph(
        "PSNR pooled over scenes (from the mean squared error), FLIP averaged, cost as total time over \
         trilinear's total time and as ns per lookup on one thread, fetches per lookup.",
    );
    for reference in ["gaussian", "box"] {
        let rows = d
            .rankings
            .iter()
            .filter(|x| x.reference == reference)
            .map(|x| {
                vec![
                    x.rank.to_string(),
                    x.filter.clone(),
                    format_number(x.pooled_psnr_db, 2),
                    format_number(x.mean_flip, 4),
                    x.scenes_best.to_string(),
                    format_number(x.ns_per_pixel, 1),
                    format!("{}×", format_number(x.cost_vs_trilinear, 2)),
                    format_number(x.fetches_per_pixel, 1),
                ]
            })
            .collect();
        r.section(&format!("Ranking under the {reference} model"));
        r.table(
            &strings(&[
                "rank",
                "filter",
                "pooled PSNR dB",
                "mean FLIP",
                "best on scenes",
                "ns/lookup",
                "time / trilinear",
                "fetches",
            ]),
            rows,
        );
    }

    if !d.sigma.is_empty() {
        r.section("σ study: how the verdict moves with the kernel");
        if let Some(study) = &cfg.sigma_study {
            r.paragraph(&format!(
            "References for each Gaussian kernel of the grid (σ and truncation), from one set of samples per \
             scene, refined like the main references, at {}×{} pixels (see the noise table for \
             their floors). Each row scores EWA with the reference's own kernel, the \
             best EWA with any other kernel of the grid, 16 Gaussian-weighted probes with the reference's \
             kernel, 16 equal-weight probes and trilinear against that reference (PSNR dB, fully covered \
             pixels); the last column names the best of the four kinds.",
            study.width,
            study.height
        ));
        }
        let rows = sigma_rows(d.sigma)
            .iter()
            .map(|x| {
                vec![
                    x.scene.to_string(),
                    format!("σ={} cut={}", x.sigma, x.cut),
                    format_number(x.ewa, 2),
                    format!("{} ({})", format_number(x.other_ewa.1, 2), x.other_ewa.0),
                    format_number(x.aniso, 2),
                    format_number(x.aniso_box, 2),
                    format_number(x.trilinear, 2),
                    x.winner().to_string(),
                ]
            })
            .collect();
        r.table(
            &strings(&[
                "scene",
                "reference kernel",
                "EWA matched",
                "best other EWA",
                "aniso16 matched",
                "aniso16:box",
                "trilinear",
                "best",
            ]),
            rows,
        );
    }

    r.section("Cost against error");
    for reference in ["gaussian", "box"] {
        let mut series: Vec<Series> = Vec::new();
        for rec in d.records.iter().filter(|x| x.kind == "filter" && x.reference == reference) {
            let i = match series.iter().position(|s| s.name == rec.method) {
                Some(i) => i,
                None => {
                    series.push(Series::new(rec.method.clone(), vec![]));
                    series.len() - 1
                }
            };
            series[i].points.push((rec.ns_per_pixel, rec.flip.max(1e-4)));
            series[i].labels.push(rec.scene.clone());
        }
        r.svg(&scatter_svg(
            &format!("ns per pixel vs FLIP ({reference} reference), every filter and scene"),
            "ns per surface pixel",
            "mean FLIP",
            &series,
            true,
            true,
        ));
    }

    r.section("Filters, per scene");
    let scenes: Vec<String> = d.scenes.iter().map(|s| s.0.clone()).collect();
    for s in &scenes {
        r.section(&format!("Scene {s}"));
        let rows = d
            .records
            .iter()
            .filter(|x| x.kind == "filter" && &x.scene == s && x.reference == "gaussian")
            .map(|g| {
                let b = find(d.records, s, &g.method, "box");
                let bf =
                    |f: fn(&TextureRecord) -> f64, k| b.map(|b| format_number(f(b), k)).unwrap_or("–".into());
                vec![
                    g.method.clone(),
                    format_number(g.ns_per_pixel, 1),
                    format_number(g.fetches_per_pixel, 2),
                    format_number(g.psnr_db, 2),
                    format_number(g.ssim, 4),
                    format_number(g.flip, 4),
                    bf(|r| r.psnr_db, 2),
                    bf(|r| r.ssim, 4),
                    bf(|r| r.flip, 4),
                ]
            })
            .collect();
        r.table(
            &strings(&[
                "filter",
                "ns/px",
                "fetches/px",
                "PSNR dB (gauss)",
                "SSIM (gauss)",
                "FLIP (gauss)",
                "PSNR dB (box)",
                "SSIM (box)",
                "FLIP (box)",
            ]),
            rows,
        );
    }

    r.section("Perspective-mapping modes");
    r.paragraph(
        "Each mode fills the texture coordinates of every surface pixel of the frame, row span by row span, \
         on one thread; the modes take turns repetition by repetition in one run, and the median is \
         reported. Coordinate errors are in level-0 texels against the direct mode (f32, as the thesis's \
         base Heckbert) and against the exact f64 mapping; image errors are those of trilinear filtering with \
         the mode's coordinates and the exact Jacobian. incremental_rows4 is the thesis's (2.6) recurrence, \
         unchanged, on four rows at once (one row per lane of a 4-wide SIMD register, over the union of the \
         four rows' spans).",
    );
    r.paragraph(
        "Why one-row incremental is slower than direct: its three running sums (w_u, w_v, q) are a \
         loop-carried dependency, each pixel waiting for the previous pixel's additions, so the compiler \
         cannot vectorise it and it runs one pixel at a time; the direct form has independent pixels and is \
         vectorised four pixels per instruction, which more than pays for its second division and extra \
         multiplications. Counting operations (the thesis's argument) does not predict time on a pipelined, \
         vector CPU. Running the same recurrence on four rows at once keeps every operation and its rounding \
         and gives the vector unit four independent chains.",
    );
    for (scene, inc, rows4) in d.ratios {
        r.paragraph(&format!(
            "{scene}, side by side in one run: incremental / direct = {}, incremental_rows4 / direct = {}.",
            format_number(*inc, 3),
            format_number(*rows4, 3)
        ));
    }
    let rows = d
        .records
        .iter()
        .filter(|x| x.kind == "mapping" && x.reference == "gaussian")
        .map(|g| {
            let b = d.records.iter().find(|b| {
                b.kind == "mapping" && b.scene == g.scene && b.method == g.method && b.reference == "box"
            });
            let direct =
                d.records.iter().find(|b| b.kind == "mapping" && b.scene == g.scene && b.method == "direct");
            vec![
                g.scene.clone(),
                g.method.clone(),
                format_number(g.ns_per_pixel, 3),
                direct
                    .map(|x| format!("{}×", format_number(g.ns_per_pixel / x.ns_per_pixel, 2)))
                    .unwrap_or("–".into()),
                format_number(g.uv_err_vs_direct_max_texels, 4),
                format_number(g.uv_err_vs_direct_mean_texels, 5),
                format_number(g.uv_err_vs_exact_max_texels, 4),
                format_number(g.psnr_db, 2),
                b.map(|b| format_number(b.psnr_db, 2)).unwrap_or("–".into()),
            ]
        })
        .collect();
    r.table(
        &strings(&[
            "scene",
            "mode",
            "ns/px",
            "time / direct",
            "max |Δuv| vs direct (texels)",
            "mean |Δuv| vs direct",
            "max |Δuv| vs exact",
            "PSNR dB (gauss)",
            "PSNR dB (box)",
        ]),
        rows,
    );

    r.section("All measurements");
    let rows = d
        .records
        .iter()
        .map(|g| {
            vec![
                g.scene.clone(),
                g.kind.to_string(),
                g.method.clone(),
                g.reference.to_string(),
                format_number(g.ns_per_pixel, 2),
                format_number(g.fetches_per_pixel, 2),
                format_number(g.psnr_db, 2),
                format_number(g.ssim, 4),
                format_number(g.flip, 4),
            ]
        })
        .collect();
    r.table(
        &strings(&["scene", "kind", "method", "reference", "ns/px", "fetches/px", "PSNR dB", "SSIM", "FLIP"]),
        rows,
    );

    if d.images.iter().any(|i| !i.1.is_empty()) {
        r.section("Images");
        r.paragraph(&format!(
            "Per scene: the two references, then each filter's result and its absolute error against the \
             Gaussian reference (0–{HEAT_MAX} linear; grey = not measured). For the ground-plane scenes the \
             region just below the clip line is also shown enlarged 4× (nearest-neighbour)."
        ));
        for (scene, filters, crop) in d.images {
            if filters.is_empty() {
                continue;
            }
            r.section(&format!("Images: {scene}"));
            let mut items: Vec<(String, String)> = vec![
                (format!("img/{scene}_reference_gaussian.png"), "reference (Gaussian)".into()),
                (format!("img/{scene}_reference_box.png"), "reference (box)".into()),
            ];
            for f in filters {
                let file = super::file_name(f);
                items.push((format!("img/{scene}_{file}.png"), f.clone()));
                items.push((format!("img/{scene}_{file}_err.png"), format!("{f}: error")));
            }
            r.image_grid(&items, 4);
            if *crop {
                let mut items: Vec<(String, String)> = vec![
                    (
                        format!("img/{scene}_reference_gaussian_crop.png"),
                        "reference (Gaussian), horizon ×4".into(),
                    ),
                    (format!("img/{scene}_reference_box_crop.png"), "reference (box), horizon ×4".into()),
                ];
                for f in filters {
                    let file = super::file_name(f);
                    items.push((format!("img/{scene}_{file}_crop.png"), format!("{f}, horizon ×4")));
                }
                r.image_grid(&items, 4);
            }
        }
    }
    r.write(path)?;
    Ok(())
}
