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
//! The labs' fixtures (the thesis's benchmark cameras and scenes, the furnished room) are in
//! [`fixtures`].
//!
//! Every lab has one shape, the [`Lab`] trait (settings with a full and a quick preset, a run
//! that hands back a [`LabSummary`]); [`suite`] runs them all and writes the report's index.

#![warn(missing_docs)]

pub mod error;
pub mod fixtures;
pub mod frames;
mod glyphs;
pub mod heatmap;
pub mod hybrid_lab;
pub mod lab;
pub mod metrics;
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
pub use timing::{measure, Timing};
