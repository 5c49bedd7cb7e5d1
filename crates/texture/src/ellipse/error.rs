//! What can make a footprint unusable.

/// What can make a footprint unusable.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EllipseError {
    /// A Jacobian entry, or a coefficient computed from it, is NaN or infinite (a pixel on or
    /// beyond the horizon, or an overflow).
    #[error("footprint Jacobian is NaN or infinite")]
    NonFinite,
    /// The Jacobian's columns are parallel or zero: the footprint has no area, so the ellipse
    /// degenerates to a segment or a point.
    #[error("footprint ellipse is degenerate (zero area)")]
    Degenerate,
    /// The output block's length is not a multiple of its width.
    #[error("block of {len} Jacobians is not a whole number of rows of width {width}")]
    BadBlock {
        /// Output length.
        len: usize,
        /// Row width asked for.
        width: usize,
    },
}
