//! A row as it is persisted when it finishes ([`RowResult`]) and as the results files show
//! it ([`HybridRecord`], with the deltas against its view's baseline and the reference's
//! noise floor beside its error).

use super::backend::{GpuRow, HybridBackend};
use super::sweep::{Stage, SweepRow};
use renderlab_core::any_f64;
use renderlab_hybrid::terms::Floor;
use renderlab_hybrid::{StageId, Term, TermScore};
use serde::{Deserialize, Serialize};

/// One finished row: what was rendered and what was measured, nothing derived from other
/// rows. Written to `DIR/rows/ID.json` the moment the row is done.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RowResult {
    /// The row's identifier (its file name without `.json`).
    pub id: String,
    /// The identifier of the row's view (`SCENE__INDEX_CAMERA`).
    pub view: String,
    /// The scene spec (built-in name or file).
    pub scene: String,
    /// The camera's name.
    pub camera: String,
    /// The row of the sweep.
    pub row: SweepRow,
    /// Timed frames.
    pub reps: u32,
    /// Median wall-clock time of the whole frame, ms.
    pub frame_ms: f64,
    /// Fastest frame, ms.
    pub frame_min_ms: f64,
    /// Slowest frame, ms.
    pub frame_max_ms: f64,
    /// Median time of the swept stage's own pass, ms (the baseline: the whole frame).
    pub stage_ms: f64,
    /// Rays traced in the whole frame (every pass).
    pub rays: u64,
    /// Rays traced by the swept stage's pass.
    pub stage_rays: u64,
    /// PSNR against the reference, dB (display images).
    #[serde(with = "any_f64")]
    pub psnr_db: f64,
    /// Mean SSIM against the reference.
    #[serde(with = "any_f64")]
    pub ssim: f64,
    /// Mean FLIP error against the reference.
    #[serde(with = "any_f64")]
    pub flip: f64,
    /// The frame's image, relative to the run's directory (empty when images are off).
    pub image: String,
    /// Its FLIP heat map, relative to the run's directory (empty when images are off).
    pub error_image: String,
    /// Every term of the frame scored against the reference's same term
    /// ([`renderlab_hybrid::terms`]), in the order of [`Term::ALL`].
    #[serde(default)]
    pub terms: Vec<TermScore>,
    /// The direct term scored over the pixels the area lights light most (where they give at
    /// least half of the reference's direct light): what soft shadows change.
    #[serde(default)]
    pub direct_area_lit: Option<TermScore>,
    /// Pixels whose visible surface is translucent that the frame shows black (luminance
    /// below 10⁻⁴) where the reference does not (above 10⁻²).
    #[serde(default)]
    pub black_pixels: u64,
    /// Which renderer drew the frame the fields above measure (`cpu` or `gpu`; a run on both
    /// keeps the CPU's here and the GPU's in `gpu`).
    #[serde(default)]
    pub backend: HybridBackend,
    /// What the GPU measured, where it ran.
    #[serde(default)]
    pub gpu: Option<GpuRow>,
}

impl RowResult {
    /// The score of `term`, if measured.
    pub fn term(&self, term: Term) -> Option<&TermScore> {
        self.terms.iter().find(|t| t.term == term)
    }
}

/// What the results files hold per row: the [`RowResult`] flattened, with the deltas against
/// its view's baseline and the reference's noise floor.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HybridRecord {
    /// Scene spec.
    pub scene: String,
    /// Camera name.
    pub camera: String,
    /// The camera's position in its scene (names may repeat; this does not).
    pub camera_index: usize,
    /// Swept stage (`baseline`, `shadows`, `translucency`, `reflections`, `gi`, `ao`).
    pub stage: &'static str,
    /// Configuration label, e.g. `rt-reflections b4 r0.5`.
    pub label: String,
    /// The swept count (shadow samples, refraction rays, bounces, spp); empty for the baseline.
    pub count: Option<u32>,
    /// The swept max roughness (reflections, translucency).
    pub max_roughness: Option<f32>,
    /// Frame width, pixels.
    pub width: u32,
    /// Frame height, pixels.
    pub height: u32,
    /// Timed frames (the median is reported).
    pub reps: u32,
    /// Median frame time, ms.
    pub frame_ms: f64,
    /// Fastest frame, ms.
    pub frame_min_ms: f64,
    /// Slowest frame, ms.
    pub frame_max_ms: f64,
    /// Median time of the swept stage's pass, ms.
    pub stage_ms: f64,
    /// The view's baseline frame time, ms.
    pub baseline_ms: f64,
    /// `frame_ms − baseline_ms`: what ray tracing the stage costs (the thesis's delta).
    pub delta_ms: f64,
    /// `frame_ms / baseline_ms`.
    pub delta_ratio: f64,
    /// Rays traced per frame.
    pub rays: u64,
    /// Rays traced per frame by the swept stage.
    pub stage_rays: u64,
    /// Rays per pixel of the swept stage.
    pub stage_rays_per_pixel: f64,
    /// PSNR against the reference, dB.
    pub psnr_db: f64,
    /// Mean SSIM against the reference.
    pub ssim: f64,
    /// Mean FLIP against the reference.
    pub flip: f64,
    /// Paths per pixel of the reference.
    pub reference_spp: u32,
    /// The highest PSNR against this reference that means anything: the PSNR between its
    /// two halves plus 10·log10 4 (the full reference's expected error, see
    /// `renderlab_hybrid::Reference`), dB.
    pub noise_floor_psnr_db: f64,
    /// Mean FLIP between the reference's two halves (FLIP of reference noise at half the
    /// samples: an upper bound of the full reference's).
    pub noise_floor_flip: f64,
    /// True when the row's PSNR reaches the noise floor: its error is not distinguishable
    /// from the reference's own, and no lower error is claimed.
    pub at_noise_floor: bool,
    /// The term the swept stage writes (`direct`, `specular`, `translucent`, `diffuse`,
    /// `ao`); empty for the baseline, which writes every term.
    pub term: &'static str,
    /// Pixels over which the term is scored.
    pub term_mask_pixels: Option<u64>,
    /// The term's mean squared error per channel against the reference's term (linear).
    pub term_mse: Option<f64>,
    /// The term's trimmed relative MSE (what rows are ranked by;
    /// `renderlab_hybrid::terms::score`).
    pub term_rel_mse: Option<f64>,
    /// `10·log10(1 / term_rel_mse)`, dB.
    pub term_rel_db: Option<f64>,
    /// The reference's own floor on the term in the same measure, dB.
    pub term_rel_floor_db: Option<f64>,
    /// The term's PSNR (peak 1, linear), dB.
    pub term_psnr_db: Option<f64>,
    /// The reference's own noise floor on the term, dB.
    pub term_floor_psnr_db: Option<f64>,
    /// Whether the term's error cannot be told from the reference's noise on it.
    pub term_at_floor: Option<bool>,
    /// Translucent pixels shown black where the reference is not.
    pub black_pixels: u64,
    /// Which renderer drew the frame the row's times and errors measure (`cpu`, `gpu`;
    /// with both, `cpu`, and the GPU's columns beside).
    pub backend: &'static str,
    /// The GPU adapter, where the GPU ran the row.
    pub gpu_adapter: Option<String>,
    /// Whether that adapter is a CPU emulating a GPU (lavapipe).
    pub gpu_software: Option<bool>,
    /// The GPU's ray-tracing path (`compute`, `query`).
    pub gpu_rt_path: Option<String>,
    /// Median GPU frame time, ms (timestamps).
    pub gpu_frame_ms: Option<f64>,
    /// Median GPU time of the swept stage, ms.
    pub gpu_stage_ms: Option<f64>,
    /// Median GPU frame wall time, ms.
    pub gpu_wall_ms: Option<f64>,
    /// PSNR of the GPU frame against the reference, dB.
    pub gpu_psnr_db: Option<f64>,
    /// The swept stage's term of the GPU frame, ranked error in dB.
    pub gpu_term_rel_db: Option<f64>,
    /// With both renderers: CPU frame time over GPU frame time (interleaved frames).
    pub cpu_over_gpu: Option<f64>,
    /// Every term's score (in `results.json`'s rows, not the CSV).
    #[serde(skip)]
    pub terms: Vec<TermScore>,
    /// The direct term over the area-lit pixels (see [`RowResult::direct_area_lit`]).
    #[serde(skip)]
    pub direct_area_lit: Option<TermScore>,
}

impl HybridRecord {
    /// `row` (of camera number `camera_index` in its scene) measured against its view's `baseline` (its deltas are NaN without one: a
    /// shard whose baseline row another shard renders) and its reference's noise floor.
    pub fn new(
        row: &RowResult,
        camera_index: usize,
        baseline: Option<&RowResult>,
        width: u32,
        height: u32,
        floor: &RefInfo,
    ) -> Self {
        let r: &SweepRow = &row.row;
        let baseline_ms = baseline.map_or(f64::NAN, |b| b.frame_ms);
        let pixels = (width as u64 * height as u64).max(1) as f64;
        let own = match r.stage {
            Stage::Baseline => None,
            Stage::Swept(id) => row.term(id.descriptor().term),
        };
        HybridRecord {
            scene: row.scene.clone(),
            camera: row.camera.clone(),
            camera_index,
            stage: r.stage.name(),
            label: r.label(),
            count: r.count(),
            max_roughness: r.max_roughness(),
            width,
            height,
            reps: row.reps,
            frame_ms: row.frame_ms,
            frame_min_ms: row.frame_min_ms,
            frame_max_ms: row.frame_max_ms,
            stage_ms: row.stage_ms,
            baseline_ms,
            delta_ms: row.frame_ms - baseline_ms,
            delta_ratio: row.frame_ms / baseline_ms,
            rays: row.rays,
            stage_rays: row.stage_rays,
            stage_rays_per_pixel: row.stage_rays as f64 / pixels,
            psnr_db: row.psnr_db,
            ssim: row.ssim,
            flip: row.flip,
            reference_spp: floor.spp,
            noise_floor_psnr_db: floor.noise_floor_psnr_db,
            noise_floor_flip: floor.halves_flip,
            at_noise_floor: row.psnr_db >= floor.noise_floor_psnr_db,
            term: own.map_or("", |t| t.term.name()),
            term_mask_pixels: own.map(|t| t.mask_pixels),
            term_mse: own.map(|t| t.mse),
            term_rel_mse: own.map(|t| t.rel_mse),
            term_rel_db: own.map(|t| t.rel_db),
            term_rel_floor_db: own.map(|t| t.rel_floor_db),
            term_psnr_db: own.map(|t| t.psnr_db),
            term_floor_psnr_db: own.map(|t| t.floor_psnr_db),
            term_at_floor: own.map(|t| t.at_floor),
            black_pixels: row.black_pixels,
            backend: match row.backend {
                HybridBackend::Gpu => "gpu",
                _ => "cpu",
            },
            gpu_adapter: row.gpu.as_ref().map(|g| g.device.adapter.clone()),
            gpu_software: row.gpu.as_ref().map(|g| g.device.software),
            gpu_rt_path: row.gpu.as_ref().map(|g| g.device.rt_path.clone()),
            gpu_frame_ms: row.gpu.as_ref().map(|g| g.frame_ms),
            gpu_stage_ms: row.gpu.as_ref().map(|g| g.stage_ms),
            gpu_wall_ms: row.gpu.as_ref().map(|g| g.wall_ms),
            gpu_psnr_db: row.gpu.as_ref().map(|g| g.psnr_db),
            gpu_term_rel_db: row.gpu.as_ref().and_then(|g| {
                let term = own?.term;
                g.terms.iter().find(|t| t.term == term).map(|t| t.rel_db)
            }),
            cpu_over_gpu: row.gpu.as_ref().and_then(|g| g.cpu_over_gpu),
            terms: row.terms.clone(),
            direct_area_lit: row.direct_area_lit.clone(),
        }
    }

    /// The score of `term`, if measured.
    pub fn term_score(&self, term: Term) -> Option<&TermScore> {
        self.terms.iter().find(|t| t.term == term)
    }

    /// Whether the row is the view's baseline.
    pub fn is_baseline(&self) -> bool {
        self.stage == Stage::Baseline.name()
    }

    /// The swept stage (`None` for the baseline).
    pub fn stage_id(&self) -> Option<StageId> {
        StageId::from_name(self.stage)
    }

    /// The row's setting without the stage's prefix (`b1 r0.01` of `rt-reflections b1
    /// r0.01`); the whole label when it has no such prefix.
    pub fn setting(&self) -> &str {
        self.label.split_once(' ').map_or(&self.label, |(_, rest)| rest)
    }

    /// The row's view as the page names it: scene, camera and the camera's number.
    pub fn view_title(&self) -> String {
        format!("{} {} (camera {})", self.scene, self.camera, self.camera_index)
    }

    /// Whether `other` is a row of the same view.
    pub fn same_view(&self, other: &HybridRecord) -> bool {
        self.scene == other.scene && self.camera_index == other.camera_index
    }
}

/// `records` grouped by view (scene and camera number), views in order of first appearance,
/// rows in their order.
pub fn by_view(records: &[HybridRecord]) -> Vec<Vec<&HybridRecord>> {
    let mut out: Vec<Vec<&HybridRecord>> = Vec::new();
    for r in records {
        match out.iter_mut().find(|v| v[0].same_view(r)) {
            Some(v) => v.push(r),
            None => out.push(vec![r]),
        }
    }
    out
}

/// A view's reference as the rows are measured against it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RefInfo {
    /// Paths per pixel.
    pub spp: u32,
    /// Rays the path tracer traced.
    pub rays: u64,
    /// Wall-clock seconds the reference took (not compared between runs).
    pub seconds: f64,
    /// PSNR between the two halves' display images, dB.
    #[serde(with = "any_f64")]
    pub halves_psnr_db: f64,
    /// `halves_psnr_db + 10·log10 4`: the full reference's own expected PSNR, dB.
    #[serde(with = "any_f64")]
    pub noise_floor_psnr_db: f64,
    /// Mean FLIP between the halves.
    #[serde(with = "any_f64")]
    pub halves_flip: f64,
    /// Mean SSIM between the halves.
    #[serde(with = "any_f64")]
    pub halves_ssim: f64,
    /// The reference image, relative to the run's directory.
    pub image: String,
    /// The reference's noise floor on each term over the term's mask.
    pub terms: TermFloors,
}

/// The reference's noise on one term over that term's mask.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TermFloor {
    /// The term.
    pub term: Term,
    /// Pixels in the mask.
    pub mask_pixels: u64,
    /// The reference's expected error on the term, both measures.
    pub floor: Floor,
}

/// Every term's floor, and the direct term's over the area-lit pixels.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TermFloors {
    /// In the order of [`Term::ALL`].
    pub terms: Vec<TermFloor>,
    /// The direct term over the pixels the area lights light most.
    pub area_lit: TermFloor,
}

/// How the errors are measured, as `results.json` and the page say it.
pub const ERROR_SPACE: &str =
    "display images: linear radiance clamped to [0, 1] and sRGB-encoded, the reference likewise";

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize, Deserialize, Debug)]
    struct Wrap(#[serde(with = "any_f64")] f64);

    #[test]
    fn non_finite_values_round_trip() {
        for v in [1.5, -0.0, 1e-300, f64::INFINITY, f64::NEG_INFINITY] {
            let text = serde_json::to_string(&Wrap(v)).unwrap();
            let back: Wrap = serde_json::from_str(&text).unwrap();
            assert_eq!(back.0.to_bits(), v.to_bits(), "{text}");
        }
        let back: Wrap = serde_json::from_str(&serde_json::to_string(&Wrap(f64::NAN)).unwrap()).unwrap();
        assert!(back.0.is_nan());
        assert!(serde_json::from_str::<Wrap>("\"lots\"").is_err());
    }
}
