//! Experiments and their measurement: image metrics, timing, results files and HTML reports.
//!
//! This crate is the toolkit every lab (relief, texture filtering, noise, ray tracing) is built
//! from. An experiment renders each technique and a ground-truth reference with the same
//! shading, then:
//!
//! - times each technique the same way with [`timing::measure`] (warm-up, repetitions, median);
//! - compares its image with the reference with [`metrics`] (PSNR, SSIM and FLIP, optionally
//!   restricted to a mask such as "pixels where the surface is visible");
//! - turns error maps into pictures with [`heatmap`];
//! - writes rows of numbers with [`results`] (CSV and JSON, atomically);
//! - draws cost-against-error charts with [`plot`] and renders each lab's self-contained HTML
//!   page from its template with [`report`], linked from an index page.
//!
//! The metrics, the heat maps and the labs' fixtures (the thesis's benchmark cameras and
//! scenes, the furnished room) come from `renderlab-measure`, below the GPU renderer and the
//! viewer, which use them too; they are re-exported here under their old paths.
//!
//! Every lab has one shape, the [`Lab`] trait (settings with a full and a quick preset, a run
//! that hands back a [`LabSummary`]); [`suite`] runs them all and writes the report's index.

#![warn(missing_docs)]

pub mod error;
pub mod features_lab;
pub mod frames;
pub mod hybrid_lab;
pub mod lab;
pub mod noise_lab;
pub mod plot;
pub mod relief_lab;
pub mod report;
pub mod results;
pub mod suite;
pub mod texture_lab;
pub mod timing;

pub use error::{LabError, Result};
pub use lab::{Lab, LabSummary, Progress};
pub use metrics::{Comparison, FlipResult, Metrics};
/// The image metrics, heat maps and benchmark fixtures every lab uses, from the crate below
/// the GPU renderer and the viewer that they share.
pub use renderlab_measure::{fixtures, heatmap, metrics};
pub use timing::{measure, Timing};
