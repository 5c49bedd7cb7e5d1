//! The texture mapping and filtering lab: every filter on every test scene, timed, its texel
//! fetches counted, and its error measured against a supersampled ground truth under two
//! pixel-filter models (the lab's Gaussian and the box); a σ study that moves the Gaussian
//! model's σ and truncation; every perspective-mapping evaluation mode timed side by side with
//! its texture-coordinate error and the image error it causes.
//!
//! The filters read the exact per-pixel texture coordinate and Jacobian
//! ([`TestScene::surface`]), so their cost and error are the filter's alone; the mapping modes
//! are measured apart. The filters with a kernel (anisotropic, EWA) take it from the same
//! [`PixelFilter`] description the reference integrates. Writes `results.json`,
//! `results.csv`, `noise.csv`, `sigma.csv`, images (results, references, error heat maps,
//! zoomed horizon crops) and `index.html`.
//!
//! [`TestScene::surface`]: renderlab_texture::scene::TestScene::surface
//! [`PixelFilter`]: renderlab_texture::reference::PixelFilter

mod config;
mod modes;
mod page;
mod record;
mod run;
mod sigma;
mod truth;
mod verdicts;

pub use config::{default_filters, SigmaStudy, TextureBenchConfig, NOISE_MARGIN_DB, TUNED_EWA};
pub use record::{Ranking, TextureRecord, TextureSummary};
pub use run::run_texture_bench;
pub use sigma::SigmaRecord;
pub use truth::{NoiseRecord, HALVES_TO_FLOOR_DB};
pub use verdicts::rank;
