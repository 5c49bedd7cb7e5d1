//! The texture lab's settings: the default filters, the noise margin the reference must keep,
//! the run's configuration with its presets, and how a scene and a file name follow from them.

use crate::error::Result;
use glam::Vec4;
use renderlab_core::Image;
use renderlab_texture::filter::{Ewa, FilterSpec};
use renderlab_texture::mapping::modes::Mode;
use renderlab_texture::reference::{PixelFilter, Sampling};
use renderlab_texture::scene::{SceneKind, TestScene};

/// The lab's default filters, from the filter registry (each filter's entry names the settings
/// measured: nearest, bilinear, bicubic, trilinear, anisotropic with 2/4/8/16 Gaussian-weighted
/// probes and with 16 equal-weight probes (the GPU form), EWA with the model's kernel,
/// Heckbert's original 2σ truncation, and a tighter texel budget).
pub fn default_filters() -> Vec<FilterSpec> {
    renderlab_texture::filter::lab_filters()
}

/// EWA with the model's kernel and a tighter texel budget (a footprint with more than 64
/// texels moves up the pyramid): the cost-bounded variant ([`Ewa::TUNED`]).
pub const TUNED_EWA: Ewa = Ewa::TUNED;

/// dB the reference's noise floor must sit above the best filter's PSNR.
pub const NOISE_MARGIN_DB: f64 = 10.0;

/// Settings of a texture-lab run.
#[derive(Clone, Debug)]
pub struct TextureBenchConfig {
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Scenes.
    pub scenes: Vec<SceneKind>,
    /// Filters.
    pub filters: Vec<FilterSpec>,
    /// Mapping modes timed (on the thesis quad and the checkerboard, when present).
    pub modes: Vec<Mode>,
    /// The pixel-filter model (the primary reference; the box is always the second).
    pub model: PixelFilter,
    /// The reference's first sampling; refined until its noise is [`NOISE_MARGIN_DB`] below
    /// the best filter's error.
    pub sampling: Sampling,
    /// The σ study, or `None` to skip it.
    pub sigma_study: Option<SigmaStudy>,
    /// Untimed runs before timing.
    pub warmup: u32,
    /// Timed runs; the median is reported.
    pub reps: u32,
    /// Whether to write images.
    pub write_images: bool,
    /// Seed of the reference's jitter (the second half uses another seed derived from it).
    pub seed: u64,
    /// The user's texture (a label for reports, linear RGBA) in place of every scene's
    /// built-in one, or `None` for the built-in textures.
    pub texture: Option<(String, Image<Vec4>)>,
}

impl Default for TextureBenchConfig {
    fn default() -> Self {
        Self {
            width: 320,
            height: 240,
            scenes: SceneKind::defaults(),
            filters: default_filters(),
            modes: Mode::ALL.to_vec(),
            model: PixelFilter::GAUSSIAN,
            sampling: Sampling { min_strata: 8, max_strata: 64, tolerance: 0.02 },
            sigma_study: Some(SigmaStudy::default()),
            warmup: 1,
            reps: 5,
            write_images: true,
            seed: 1,
            texture: None,
        }
    }
}

impl TextureBenchConfig {
    /// A small, rough run: 160×120, one repetition, a coarser reference, the σ study on one
    /// scene.
    pub fn quick() -> Self {
        let mut c = TextureBenchConfig {
            width: 160,
            height: 120,
            reps: 1,
            warmup: 0,
            sampling: Sampling { min_strata: 4, max_strata: 32, tolerance: 0.02 },
            ..TextureBenchConfig::default()
        };
        if let Some(s) = &mut c.sigma_study {
            s.scenes.truncate(1);
        }
        c
    }

    /// The two models every filter is scored against: the lab's model and the box.
    pub fn models(&self) -> [PixelFilter; 2] {
        [self.model, PixelFilter::Box]
    }
}

/// Scale of the error heat maps: absolute linear error 0 … this.
pub(super) const HEAT_MAX: f32 = 0.25;

/// The file-name form of a filter or kernel name.
pub(super) fn file_name(s: &str) -> String {
    s.replace([':', '='], "-")
}

/// The scene with the user's texture, if any.
pub(super) fn scene_of(kind: SceneKind, cfg: &TextureBenchConfig) -> Result<TestScene> {
    let mut scene = TestScene::new(kind, cfg.width, cfg.height)?;
    if let Some((label, img)) = &cfg.texture {
        scene = scene.with_texture(img.clone(), label);
    }
    Ok(scene)
}

/// What the σ study covers.
#[derive(Clone, Debug, PartialEq)]
pub struct SigmaStudy {
    /// Scenes.
    pub scenes: Vec<SceneKind>,
    /// σ values, pixels.
    pub sigmas: Vec<f32>,
    /// Truncations, multiples of σ.
    pub cuts: Vec<f32>,
    /// The references' first sampling (refined like the main references').
    pub sampling: Sampling,
    /// Frame width (the study needs many kernels per sample, so it runs smaller than the lab).
    pub width: u32,
    /// Frame height.
    pub height: u32,
}

impl Default for SigmaStudy {
    /// The checkerboard and the thesis's quad at 160×120; σ = 0.35, 0.4, …, 0.6; cut 2σ and 3σ.
    /// (The zone plate at this size is so well filtered by EWA that its references need over
    /// 3000 samples per pixel to keep their noise 10 dB below it: a minute of the report's
    /// three; `--sigma-scenes` adds it.)
    fn default() -> Self {
        SigmaStudy {
            scenes: vec![SceneKind::Checkerboard, SceneKind::ThesisQuad],
            sigmas: vec![0.35, 0.4, 0.45, 0.5, 0.55, 0.6],
            cuts: vec![2.0, 3.0],
            sampling: Sampling { min_strata: 8, max_strata: 64, tolerance: 0.02 },
            width: 160,
            height: 120,
        }
    }
}

impl SigmaStudy {
    /// Every kernel of the grid, σ-major.
    pub fn kernels(&self) -> Vec<PixelFilter> {
        self.cuts
            .iter()
            .flat_map(|&cut| self.sigmas.iter().map(move |&sigma| PixelFilter::Gaussian { sigma, cut }))
            .collect()
    }
}
