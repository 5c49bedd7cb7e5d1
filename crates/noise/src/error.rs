//! Typed errors for every parameter this crate validates.
//!
//! Noise functions themselves never fail (a non-finite coordinate simply gives 0); what can
//! fail is a *parameter* that would make a computation overflow, lose all precision or never
//! finish: an octave count, a frequency, a period or a grid size. Each variant names the
//! parameter so that a command-line front end can print one clear line.

use thiserror::Error;

/// Why a noise parameter or batch request was rejected.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NoiseError {
    /// The octave count is zero or above [`crate::MAX_OCTAVES`].
    #[error("octaves = {value}: must be between 1 and {max}")]
    Octaves {
        /// The rejected octave count.
        value: u32,
        /// The largest accepted count.
        max: u32,
    },
    /// A real-valued parameter (frequency, lacunarity, gain, grid origin or step) is NaN,
    /// infinite or outside its accepted range.
    #[error("{name} = {value}: {reason}")]
    Parameter {
        /// The parameter's name as the API spells it.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What the accepted range is.
        reason: &'static str,
    },
    /// The highest octave's frequency would exceed [`crate::MAX_FREQUENCY`], where f32
    /// coordinates no longer resolve a lattice cell.
    #[error("frequency of the last octave = {value}: exceeds {max} (too many octaves or too high a frequency/lacunarity)")]
    FrequencyOverflow {
        /// The last octave's frequency.
        value: f64,
        /// The largest accepted frequency.
        max: f64,
    },
    /// A tiling period is zero, too large, or not a whole number of lattice cells at some
    /// octave.
    #[error("period on axis {axis} = {value}: {reason}")]
    Period {
        /// Axis index (0 = x).
        axis: usize,
        /// The offending period (in lattice cells of the octave that failed).
        value: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A grid size is zero, its sample count overflows, or it exceeds [`crate::MAX_SAMPLES`].
    #[error("grid size {dims:?}: {reason}")]
    Size {
        /// The requested extent per axis.
        dims: Vec<usize>,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The output slice does not have exactly one element per grid sample.
    #[error("output length {got}: the grid has {expected} samples")]
    OutputLength {
        /// Samples in the grid.
        expected: usize,
        /// Length of the slice passed in.
        got: usize,
    },
}

/// Result alias for this crate.
pub type Result<T> = std::result::Result<T, NoiseError>;
