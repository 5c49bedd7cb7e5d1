//! The σ study: how the verdict moves with the pixel filter. On a few scenes (at a smaller
//! frame than the lab's, since every sample feeds a dozen kernels), references for
//! a grid of Gaussian kernels (σ 0.35–0.6 px, truncated at 2σ and 3σ) from one set of samples,
//! and EWA and Gaussian-weighted anisotropic filtering with each kernel; every EWA is scored
//! against every reference, so the table shows both whether the matched kernel wins and which
//! filter is best for each kernel.

use super::config::{scene_of, SigmaStudy, TextureBenchConfig, NOISE_MARGIN_DB};
use super::truth::{truth, NoiseRecord};
use crate::error::Result;
use crate::metrics::psnr;
use crate::report::format_number;
use glam::Vec3;
use renderlab_core::Image;
use renderlab_texture::filter::{Anisotropic, Ewa, FilterSpec, Trilinear};
use renderlab_texture::reference::PixelFilter;
use serde::Serialize;

/// One filter scored against one reference kernel of the study.
#[derive(Clone, Debug, Serialize)]
pub struct SigmaRecord {
    /// Scene name.
    pub scene: String,
    /// Reference σ, pixels.
    pub ref_sigma: f32,
    /// Reference truncation, multiples of σ.
    pub ref_cut: f32,
    /// The filter's name.
    pub filter: String,
    /// Whether the filter's kernel is the reference's.
    pub matched: bool,
    /// PSNR against the reference, dB (fully covered pixels).
    pub psnr_db: f64,
}

/// The study's filters: EWA and 16 Gaussian-weighted probes for every kernel, then the
/// kernel-free comparisons (16 equal-weight probes, trilinear).
fn filters(kernels: &[PixelFilter]) -> Vec<FilterSpec> {
    let mut v: Vec<FilterSpec> =
        kernels.iter().filter_map(|&k| Ewa::with_kernel(k).map(FilterSpec::Ewa)).collect();
    v.extend(kernels.iter().map(|&k| FilterSpec::Anisotropic(Anisotropic { max_probes: 16, kernel: k })));
    v.push(FilterSpec::Anisotropic(Anisotropic::box_probes(16)));
    v.push(FilterSpec::Trilinear(Trilinear));
    v
}

/// Runs the study; appends the references' noise to `noise`.
pub fn run(
    study: &SigmaStudy,
    cfg: &TextureBenchConfig,
    progress: &dyn Fn(&str),
    noise: &mut Vec<NoiseRecord>,
) -> Result<Vec<SigmaRecord>> {
    let kernels = study.kernels();
    let specs = filters(&kernels);
    let mut out = Vec::new();
    for &kind in &study.scenes {
        let scene =
            scene_of(kind, &TextureBenchConfig { width: study.width, height: study.height, ..cfg.clone() })?;
        let name = kind.name();
        progress(&format!("σ study, {name}: filters"));
        let surface = scene.surface();
        let images: Vec<Image<Vec3>> = specs.iter().map(|f| scene.render_spec(&surface, f)).collect();
        let named: Vec<(String, &Image<Vec3>)> =
            specs.iter().zip(&images).map(|(f, i)| (f.name(), i)).collect();
        let t = truth(&scene, &kernels, &study.sampling, cfg.seed, &named, NOISE_MARGIN_DB, &|m| {
            progress(&format!("σ study, {name}: {m}"))
        })?;
        for mut n in t.noise {
            n.scene = format!("{name} (σ study)");
            noise.push(n);
        }
        for r in &t.refs {
            let PixelFilter::Gaussian { sigma, cut } = r.filter else { continue };
            for (f, img) in specs.iter().zip(&images) {
                out.push(SigmaRecord {
                    scene: name.clone(),
                    ref_sigma: sigma,
                    ref_cut: cut,
                    filter: f.name(),
                    matched: f.kernel() == Some(r.filter),
                    psnr_db: psnr(img, &r.image, Some(&r.mask)),
                });
            }
        }
    }
    Ok(out)
}

/// Per scene and reference kernel: the matched EWA's PSNR, the best other EWA (name, PSNR),
/// the matched 16-probe anisotropic's, the box-probe anisotropic's, trilinear's, and the
/// winner among the four filter kinds.
pub struct Row<'a> {
    /// Scene.
    pub scene: &'a str,
    /// Reference kernel.
    pub sigma: f32,
    /// Reference truncation.
    pub cut: f32,
    /// EWA with the reference's kernel.
    pub ewa: f64,
    /// The best EWA with another kernel.
    pub other_ewa: (&'a str, f64),
    /// Gaussian-weighted anisotropic with the reference's kernel.
    pub aniso: f64,
    /// Equal-weight anisotropic.
    pub aniso_box: f64,
    /// Trilinear.
    pub trilinear: f64,
}

impl Row<'_> {
    /// The best of the four kinds.
    pub fn winner(&self) -> &'static str {
        let c = [
            ("ewa", self.ewa),
            ("aniso16", self.aniso),
            ("aniso16:box", self.aniso_box),
            ("trilinear", self.trilinear),
        ];
        c.iter().max_by(|a, b| a.1.total_cmp(&b.1)).map_or("–", |w| w.0)
    }
}

/// The study's table, one row per scene and reference kernel.
pub fn rows(records: &[SigmaRecord]) -> Vec<Row<'_>> {
    let mut out: Vec<Row> = Vec::new();
    for r in records {
        if out.iter().any(|o| o.scene == r.scene && o.sigma == r.ref_sigma && o.cut == r.ref_cut) {
            continue;
        }
        let same: Vec<&SigmaRecord> = records
            .iter()
            .filter(|x| x.scene == r.scene && x.ref_sigma == r.ref_sigma && x.ref_cut == r.ref_cut)
            .collect();
        let get =
            |p: &dyn Fn(&SigmaRecord) -> bool| same.iter().find(|x| p(x)).map_or(f64::NAN, |x| x.psnr_db);
        let other = same
            .iter()
            .filter(|x| x.filter.starts_with("ewa") && !x.matched)
            .max_by(|a, b| a.psnr_db.total_cmp(&b.psnr_db))
            .map_or(("–", f64::NAN), |x| (x.filter.as_str(), x.psnr_db));
        out.push(Row {
            scene: &r.scene,
            sigma: r.ref_sigma,
            cut: r.ref_cut,
            ewa: get(&|x| x.matched && x.filter.starts_with("ewa")),
            other_ewa: other,
            aniso: get(&|x| x.matched && x.filter.starts_with("aniso")),
            aniso_box: get(&|x| x.filter == "aniso16:box"),
            trilinear: get(&|x| x.filter == "trilinear"),
        });
    }
    out
}

/// Sentences: per scene, how often the matched EWA beats every mismatched one, and which kind
/// wins for how many kernels.
pub fn findings(records: &[SigmaRecord]) -> Vec<String> {
    let rows = rows(records);
    let mut scenes: Vec<&str> = rows.iter().map(|r| r.scene).collect();
    scenes.dedup();
    scenes
        .iter()
        .map(|s| {
            let mine: Vec<&Row> = rows.iter().filter(|r| r.scene == *s).collect();
            let matched_best = mine.iter().filter(|r| r.ewa >= r.other_ewa.1).count();
            let mut wins: Vec<(&str, usize)> = Vec::new();
            for r in &mine {
                match wins.iter_mut().find(|w| w.0 == r.winner()) {
                    Some(w) => w.1 += 1,
                    None => wins.push((r.winner(), 1)),
                }
            }
            let spread = mine.iter().map(|r| r.ewa).fold(f64::INFINITY, f64::min);
            let top = mine.iter().map(|r| r.ewa).fold(f64::NEG_INFINITY, f64::max);
            format!(
                "σ study, {s}: EWA with the reference's own kernel beats every EWA with another kernel for {matched_best} \
                 of {} kernels; best kind per kernel: {}; matched EWA ranges {}–{} dB over the kernels.",
                mine.len(),
                wins.iter().map(|(k, n)| format!("{k} {n}")).collect::<Vec<_>>().join(", "),
                format_number(spread, 2),
                format_number(top, 2)
            )
        })
        .collect()
}
