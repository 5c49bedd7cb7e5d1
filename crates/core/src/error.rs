//! Typed errors of the core crate. Each message names the file or parameter at fault so that
//! the command-line tool can print it as a single line.

use std::path::PathBuf;

/// Result alias for the core crate.
pub type Result<T> = std::result::Result<T, CoreError>;

/// Everything that can go wrong when loading, validating or writing core data.
#[derive(Debug, thiserror::Error)]
pub enum CoreError {
    /// The file could not be opened or read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// File concerned.
        path: PathBuf,
        /// Underlying I/O error.
        source: std::io::Error,
    },
    /// The file could not be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        /// File concerned.
        path: PathBuf,
        /// Underlying I/O error.
        source: std::io::Error,
    },
    /// The file exists but its contents are not a valid image of a supported format.
    #[error("{path}: not a valid image: {reason}")]
    Decode {
        /// File concerned.
        path: PathBuf,
        /// What the decoder reported.
        reason: String,
    },
    /// The image or request has dimensions we refuse (zero, or too large to allocate safely).
    #[error("{what}: bad dimensions {width}x{height}: {reason}")]
    Dimensions {
        /// File or parameter concerned.
        what: String,
        /// Width requested.
        width: u64,
        /// Height requested.
        height: u64,
        /// Why they were refused.
        reason: &'static str,
    },
    /// A file extension we cannot read or write.
    #[error("{path}: unsupported image format (use .png, .jpg, .tga or .exr)")]
    UnsupportedFormat {
        /// File concerned.
        path: PathBuf,
    },
    /// Two maps that must agree in size do not.
    #[error("{what}: sizes differ ({a_w}x{a_h} vs {b_w}x{b_h})")]
    SizeMismatch {
        /// What was being paired.
        what: String,
        /// First width.
        a_w: u32,
        /// First height.
        a_h: u32,
        /// Second width.
        b_w: u32,
        /// Second height.
        b_h: u32,
    },
    /// A parameter is NaN, infinite or out of its allowed range.
    #[error("{name}: invalid value {value}: {reason}")]
    Parameter {
        /// Parameter name (as the user would type it).
        name: String,
        /// The value given, printed.
        value: String,
        /// The allowed range or rule.
        reason: String,
    },
    /// A name (material, technique, …) that is not known.
    #[error("unknown {kind} '{name}' (known: {known})")]
    UnknownName {
        /// What kind of thing was named.
        kind: &'static str,
        /// The name given.
        name: String,
        /// Comma-separated list of valid names.
        known: String,
    },
}

impl CoreError {
    /// Convenience constructor for [`CoreError::Parameter`].
    pub fn param(name: impl Into<String>, value: impl ToString, reason: impl Into<String>) -> Self {
        CoreError::Parameter { name: name.into(), value: value.to_string(), reason: reason.into() }
    }
}

/// Checks that a float parameter is finite and inside `[lo, hi]`.
pub fn check_range(name: &str, value: f32, lo: f32, hi: f32) -> Result<f32> {
    if !value.is_finite() {
        return Err(CoreError::param(name, value, "must be a finite number"));
    }
    if value < lo || value > hi {
        return Err(CoreError::param(name, value, format!("must lie in [{lo}, {hi}]")));
    }
    Ok(value)
}
