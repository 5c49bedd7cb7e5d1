//! SVG charts for reports, drawn with plotters' SVG backend into a `String` that
//! a report page embeds inline (no image files, crisp at any zoom).
//!
//! Two kinds cover the experiments: [`scatter_svg`], cost against error with one series per
//! technique (optionally connected, optionally labelled point by point, linear or logarithmic
//! axes), and [`bar_svg`], grouped bars such as frames per second per view angle per
//! technique. Both skip non-finite values (and non-positive ones on a log axis), pad their
//! ranges, give each series a distinct colour from a colour-blind-aware palette ([`PALETTE`]) and
//! draw the legend beside the plot so that it never hides data. Neither panics: if plotters
//! reports an error, the SVG shows the message instead of the chart.
//!
//! [`line_svg`] draws dense curves (no markers), for noise functions and paths.

mod axis;
mod bar;
mod legend;
mod line;
mod scatter;
mod series;
mod style;

pub use bar::bar_svg;
pub use line::line_svg;
pub use scatter::scatter_svg;
pub use series::{BarSeries, Series};
pub use style::{PALETTE, PLOT_HEIGHT, PLOT_WIDTH};
