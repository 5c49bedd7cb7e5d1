//! Statistics of the quantities the noise lab draws, and the rows of its results table.

use serde::Serialize;

/// Mean, standard deviation, minimum and maximum of the finite values of a sample.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Stats {
    /// Arithmetic mean.
    pub mean: f64,
    /// Population standard deviation.
    pub std: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Stats {
    /// Statistics of the finite entries of `values` (all NaN when there is none).
    pub fn of(values: &[f32]) -> Stats {
        let finite = || values.iter().filter(|v| v.is_finite()).map(|&v| f64::from(v));
        let n = finite().count();
        if n == 0 {
            return Stats { mean: f64::NAN, std: f64::NAN, min: f64::NAN, max: f64::NAN };
        }
        let mean = finite().sum::<f64>() / n as f64;
        let var = finite().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
        Stats {
            mean,
            std: var.sqrt(),
            min: finite().fold(f64::INFINITY, f64::min),
            max: finite().fold(f64::NEG_INFINITY, f64::max),
        }
    }
}

/// One row of the lab's statistics table (and of `results.csv`): a quantity of an experiment
/// and its statistics, flat so that it is one CSV record.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StatRow {
    /// Which experiment (e.g. `Fig. 3.3`).
    pub experiment: String,
    /// Which quantity (an axis, a layer or the sum).
    pub quantity: String,
    /// Arithmetic mean.
    pub mean: f64,
    /// Population standard deviation.
    pub std: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl StatRow {
    /// The row of `quantity` of `experiment` with statistics `stats`.
    pub fn new(experiment: impl Into<String>, quantity: impl Into<String>, stats: Stats) -> Self {
        let Stats { mean, std, min, max } = stats;
        StatRow { experiment: experiment.into(), quantity: quantity.into(), mean, std, min, max }
    }

    /// Its statistics.
    pub fn stats(&self) -> Stats {
        Stats { mean: self.mean, std: self.std, min: self.min, max: self.max }
    }
}
