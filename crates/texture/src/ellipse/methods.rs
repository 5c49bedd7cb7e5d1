//! The ways of computing the footprint Jacobian over a block of pixels: one file per method
//! under `methods/`, each a kernel of the module's name that walks the block row by row (the
//! thesis's set-up is per polygon and per row) and counts its operations, and one line per
//! method in the `registry!` below, from which [`JacobianMethod`], its [`ALL`] list, its
//! names and the dispatch of [`jacobian_block`] come. What the methods share is below them:
//! the per-polygon constants in `methods/increments.rs`, the pixel coordinates in
//! `methods/coords.rs`; no method file imports this one.
//!
//! [`ALL`]: JacobianMethod::ALL

mod coords;
mod increments;

use super::error::EllipseError;
use super::jacobian::Jacobian;
use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;

/// Declares the catalogue: each method's module (its kernel has the module's name, which is
/// also the method's name in reports), the [`JacobianMethod`] enum with each line's doc,
/// [`JacobianMethod::ALL`], [`JacobianMethod::name`] and the dispatch of [`jacobian_block`].
macro_rules! registry {
    ($($(#[$doc:meta])* $variant:ident => $module:ident,)*) => {
        $(mod $module;)*

        /// How the per-pixel Jacobian is computed.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum JacobianMethod {
            $($(#[$doc])* $variant,)*
        }

        impl JacobianMethod {
            /// Every method, in report order.
            pub const ALL: [JacobianMethod; [$(stringify!($variant),)*].len()] = [$(JacobianMethod::$variant,)*];

            /// Short name for reports.
            pub fn name(&self) -> &'static str {
                match self {
                    $(JacobianMethod::$variant => stringify!($module),)*
                }
            }
        }

        /// Fills `out` (row-major, `width` pixels per row) with the Jacobian at pixels
        /// `(x0 + i, y0 + j)`, by `method`, counting operations into `ops`.
        ///
        /// Errors only when `out.len()` is not a multiple of `width`; rows crossing the horizon
        /// give non-finite entries, which [`Ellipse::from_jacobian`](super::Ellipse::from_jacobian)
        /// rejects.
        pub fn jacobian_block<O: OpCounter>(
            c: &Coeffs,
            method: JacobianMethod,
            x0: i32,
            y0: i32,
            width: usize,
            out: &mut [Jacobian],
            ops: &mut O,
        ) -> Result<(), EllipseError> {
            if width == 0 {
                return if out.is_empty() { Ok(()) } else { Err(EllipseError::BadBlock { len: out.len(), width }) };
            }
            if !out.len().is_multiple_of(width) {
                return Err(EllipseError::BadBlock { len: out.len(), width });
            }
            match method {
                $(JacobianMethod::$variant => $module::$module(c, x0, y0, width, out, ops),)*
            }
            Ok(())
        }
    };
}

registry! {
    /// (2.11) forward differences, the thesis's baseline.
    ForwardDifference => forward_difference,
    /// (2.16)–(2.21) as printed in the thesis, with its errors ([THESIS ERROR]).
    ThesisIncremental => thesis_incremental,
    /// (2.16)–(2.21) corrected: equal to forward differences up to rounding.
    CorrectedIncremental => corrected_incremental,
    /// Exact derivatives, one reciprocal per pixel, numerators and `D` stepped incrementally.
    Analytic => analytic,
    /// Exact derivatives with every pixel independent: `D = G·x + (H·y + I)` and the
    /// y-numerators `O·x + …` evaluated afresh (more multiplications, no loop-carried
    /// additions, so the compiler can vectorise it).
    AnalyticParallel => analytic_parallel,
}
