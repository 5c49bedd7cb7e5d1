//! The scanline evaluation modes of the perspective mapping, each as the thesis (§2.1 and
//! §2.3 of the thesis; §2.2/§2.4 of the seed summary) describes it, plus affine interpolation
//! for contrast. Every kernel fills `out[n]` with the texture coordinate of pixel
//! `(x0 + n, y)` and reports its floating-point operations to an [`OpCounter`].
//!
//! The catalogue: one file per mode under `modes/`, each with its kernel, its module doc
//! stating the formula and the operations it counts per pixel, and one [`RowMode`]
//! implementation (its name, whether it is exact, its row and frame evaluation), and one line
//! per mode in the `registry!` below, from which [`Mode`], [`Mode::ALL`], [`Mode::name`],
//! [`Mode::is_exact`], [`eval_row`] and [`eval_spans`] come. The enum is matched once per row
//! or frame; the kernels' loops see only the concrete mode. What the modes share is below
//! them: [`RowMode`] in `modes/row_mode.rs`, [`Span`] in `modes/span.rs`, the linear forms of
//! (2.4) in `modes/forms.rs`; no mode file imports this one.
//!
//! Pixel indices are converted through `i32` (a vectorisable conversion; rows beyond 2³¹
//! pixels are meaningless in `f32` anyway).
//!
//! Where a row crosses the horizon (`G·x + H·y + I = 0`) the results are the IEEE values of
//! the division (infinite or NaN); no kernel loops on data or panics.

mod forms;
pub mod row_mode;
mod span;

pub use k_stride::MAX_STRIDE;
pub use row_mode::RowMode;
pub use span::Span;

use super::error::MappingError;
use super::ops::OpCounter;
use super::projective::Coeffs;
use glam::Vec2;

/// Declares the catalogue: each mode's module and its kernel (a function of the module's
/// name), the [`Mode`] enum (one variant per mode; a parameterised mode names its parameter,
/// its type and the value [`Mode::ALL`] uses), [`Mode::ALL`], and the dispatch from a variant
/// to its [`RowMode`].
macro_rules! registry {
    ($($variant:ident $(($p:ident: $param:ty = $default:expr))? => $module:ident::$ty:ident,)*) => {
        $(pub mod $module;)*
        $(pub use $module::$module;)*

        /// How a scanline's texture coordinates are evaluated.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Mode {
            $(
                #[doc = concat!("[`", stringify!($module), "::", stringify!($ty), "`].")]
                $variant $(($param))?,
            )*
        }

        impl Mode {
            /// Every mode, with `k = 8` for the stride, in report order.
            pub const ALL: [Mode; [$(stringify!($variant),)*].len()] = [$(Mode::$variant $(($default))?,)*];

            /// Short name for reports.
            pub fn name(&self) -> String {
                match *self {
                    $(Mode::$variant $(($p))? => <$module::$ty as RowMode>::name(($($p)?)),)*
                }
            }

            /// Whether the mode computes the perspective mapping exactly (up to rounding).
            pub fn is_exact(&self) -> bool {
                match self {
                    $(Mode::$variant { .. } => <$module::$ty as RowMode>::EXACT,)*
                }
            }
        }

        /// Evaluates one scanline: `out[n]` gets `(u, v)` at pixel `(x0 + n, y)`.
        ///
        /// Errors only on a bad stride; any coefficients (even NaN) give a defined, possibly
        /// non-finite, result.
        pub fn eval_row<O: OpCounter>(
            c: &Coeffs,
            mode: Mode,
            x0: i32,
            y: i32,
            out: &mut [Vec2],
            ops: &mut O,
        ) -> Result<(), MappingError> {
            match mode {
                $(Mode::$variant $(($p))? => <$module::$ty as RowMode>::eval_row(($($p)?), c, x0, y, out, ops),)*
            }
        }

        /// Evaluates a whole frame: row `y0 + k` gets `(u, v)` for `spans[k]`, written into
        /// `out[k·width + x]` (`out` holds `spans.len()` rows of `width`). Spans reaching past
        /// `width` are cut. [`Mode::IncrementalRows`] takes four rows at a time over the union
        /// of their spans (so it may also write pixels of those rows outside their own spans,
        /// inside the union); every other mode evaluates each span with [`eval_row`].
        pub fn eval_spans<O: OpCounter>(
            c: &Coeffs,
            mode: Mode,
            y0: i32,
            spans: &[Span],
            width: usize,
            out: &mut [Vec2],
            ops: &mut O,
        ) -> Result<(), MappingError> {
            match mode {
                $(Mode::$variant $(($p))? => {
                    <$module::$ty as RowMode>::eval_spans(($($p)?), c, y0, spans, width, out, ops)
                })*
            }
        }
    };
}

registry! {
    Direct => direct::Direct,
    PerRow => per_row::PerRow,
    Incremental => incremental::Incremental,
    IncrementalRows => incremental_rows4::IncrementalRows,
    KStride(k: usize = 8) => k_stride::KStride,
    TwoWay => two_way::TwoWay,
    Affine => affine::Affine,
    DepthCoordinate => depth_coordinate::DepthCoordinate,
}
