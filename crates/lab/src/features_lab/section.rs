//! What a section of the features page is made of: its table, figures and findings, and the
//! tables' number format.

use serde::Serialize;

/// A figure of a section: an image file under the run's directory and its caption.
#[derive(Clone, Debug, Serialize)]
pub struct Figure {
    /// Path relative to the page.
    pub file: String,
    /// What it shows.
    pub caption: String,
}

/// One section of the page: a study's table, its figures and what it found.
#[derive(Clone, Debug, Serialize)]
pub struct Section {
    /// Heading.
    pub title: String,
    /// File-name stem of its table (`STEM.json`).
    pub stem: &'static str,
    /// What was measured and how, in a paragraph.
    pub intro: String,
    /// Conclusions drawn from the rows.
    pub findings: Vec<String>,
    /// Column headings.
    pub headers: Vec<String>,
    /// One row per measurement.
    pub rows: Vec<Vec<String>>,
    /// Figures per row of the grid.
    pub columns: usize,
    /// The figures.
    pub figures: Vec<Figure>,
}

/// `v` with `d` decimals (the tables' number format).
pub(super) fn num(v: f64, d: usize) -> String {
    crate::report::format_number(v, d)
}
