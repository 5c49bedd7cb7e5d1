//! The noise lab's HTML page: what `templates/noise.html` shows, gathered by the run (numbers
//! formatted there, prose in the template).

use super::stats::StatRow;
use crate::error::Result;
use crate::report::{format_number, write_page, Template};
use serde::Serialize;
use std::path::Path;

const TEMPLATE: Template =
    Template { name: "noise.html", source: include_str!("../../templates/noise.html") };

/// An image or SVG file beside the page, with its caption.
#[derive(Clone, Debug, Serialize)]
pub struct Figure {
    /// File name, relative to the page.
    pub file: String,
    /// Caption (text).
    pub caption: String,
}

/// One path experiment: its title, its largest distance from the diagonal, its projections.
#[derive(Clone, Debug, Serialize)]
pub struct PathFigures {
    /// The experiment's title.
    pub title: &'static str,
    /// Largest distance of a point from the diagonal, formatted.
    pub distance: String,
    /// The x–y and x–z projections.
    pub figures: Vec<Figure>,
}

/// The clouds experiment as the page states it.
#[derive(Clone, Debug, Serialize)]
pub struct Clouds {
    /// Number of layers.
    pub layers: u32,
    /// Image side, pixels.
    pub size: u32,
    /// The layers' frequencies, comma-separated.
    pub frequencies: String,
    /// The layers' weights, comma-separated.
    pub weights: String,
    /// The layers' seeds, comma-separated.
    pub seeds: String,
    /// Smallest value of the weighted sum before normalisation, formatted.
    pub raw_min: String,
    /// Largest value of the weighted sum before normalisation, formatted.
    pub raw_max: String,
    /// The clouds image.
    pub image: &'static str,
    /// Each layer's image.
    pub layer_figures: Vec<Figure>,
}

/// One still of the water animation.
#[derive(Clone, Debug, Serialize)]
pub struct WaterStill {
    /// File name.
    pub file: String,
    /// Frame index.
    pub frame: u32,
    /// Time of the frame, seconds, formatted.
    pub t: String,
}

/// The water animation as the page states it (numbers formatted for the page).
#[derive(Clone, Debug, Serialize)]
pub struct Water {
    /// fBm octaves.
    pub octaves: u32,
    /// Largest wavelength, units.
    pub wavelength: String,
    /// Height scale.
    pub amplitude: String,
    /// Wind velocity, x.
    pub wind_x: String,
    /// Wind velocity, y.
    pub wind_y: String,
    /// Frames in the animation.
    pub frames: u32,
    /// Seconds between frames.
    pub time_step: String,
    /// Frame width, pixels.
    pub width: u32,
    /// Frame height, pixels.
    pub height: u32,
    /// The animation (APNG).
    pub animation: &'static str,
    /// Playback rate.
    pub fps: u32,
    /// Milliseconds per frame on this machine.
    pub ms_per_frame: String,
    /// A few stills.
    pub stills: Vec<WaterStill>,
}

/// One smoke animation.
#[derive(Clone, Debug, Serialize)]
pub struct SmokeAnimation {
    /// `advect` or `thesis`.
    pub key: &'static str,
    /// The animation (APNG).
    pub file: String,
    /// Milliseconds per frame on this machine.
    pub ms_per_frame: String,
}

/// The smoke animations as the page states them (numbers formatted for the page).
#[derive(Clone, Debug, Serialize)]
pub struct Smoke {
    /// Density grid per side.
    pub grid: u32,
    /// fBm octaves.
    pub octaves: u32,
    /// Henyey–Greenstein anisotropy.
    pub anisotropy: String,
    /// Frames per animation.
    pub frames: u32,
    /// Seconds between frames.
    pub time_step: String,
    /// Rise speed, units per second.
    pub rise_speed: String,
    /// The thesis's animation factor used.
    pub thesis_factor: String,
    /// The two animations.
    pub animations: Vec<SmokeAnimation>,
    /// Every few frames: animation, frame, time, mean density, correlation with frame 0.
    pub frames_table: Vec<Vec<String>>,
    /// The first frame under each filter.
    pub filters: Vec<Figure>,
}

/// Everything the page shows.
#[derive(Clone, Debug, Serialize)]
pub struct Page {
    /// The three path experiments.
    pub paths: Vec<PathFigures>,
    /// The Fig. 3.4 coordinate functions (SVG).
    pub octave_axes: &'static str,
    /// The thesis's octave sum (SVG).
    pub octave_sum: &'static str,
    /// The clouds.
    pub clouds: Clouds,
    /// The water animation.
    pub water: Water,
    /// The smoke animations.
    pub smoke: Smoke,
    /// The statistics table.
    pub stats: Vec<Vec<String>>,
}

/// The statistics table's rows.
pub fn stat_rows(stats: &[StatRow]) -> Vec<Vec<String>> {
    stats
        .iter()
        .map(|r| {
            vec![
                r.experiment.clone(),
                r.quantity.clone(),
                format_number(r.mean, 4),
                format_number(r.std, 4),
                format_number(r.min, 4),
                format_number(r.max, 4),
            ]
        })
        .collect()
}

/// Writes the page to `path`.
pub fn write(path: &Path, page: &Page) -> Result<()> {
    write_page(path, TEMPLATE, "Perlin noise: the thesis's experiments", page)
}
