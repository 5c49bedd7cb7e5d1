//! Heckbert's projective (perspective-correct) texture mapping of a planar quadrilateral seen
//! from an eye point, and every way the thesis evaluates it along a scanline.
//!
//! In Heckbert's row-vector convention a screen point `(x, y)` maps to the texture point
//! `(u, v)` through one 3×3 matrix:
//!
//! ```text
//! [u·q  v·q  q] = [x  y  1] · | A  D  G |      u = (A·x + B·y + C) / (G·x + H·y + I)
//!                             | B  E  H |      v = (D·x + E·y + F) / (G·x + H·y + I)
//!                             | C  F  I |
//! ```
//!
//! The matrix is built in double precision ([`Projective`]); the scanline kernels in
//! [`modes`] work in `f32` on its nine coefficients ([`Coeffs`]) so that their drift is
//! the drift a renderer would see. [`QuadScene`] holds the thesis's default scene and turns
//! any planar quad plus eye into the screen→texture matrix, rejecting degenerate input with
//! a [`MappingError`].

mod error;
pub mod modes;
pub mod ops;
mod projective;
mod quad;

pub use error::MappingError;
pub use modes::{eval_row, eval_spans, Mode, Span};
pub use ops::{NoOps, OpCounter, OpRate, OpTally, RowCost};
pub use projective::{Coeffs, Projective};
pub use quad::QuadScene;
