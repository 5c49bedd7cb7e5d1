//! The EWA footprint ellipse: the screen→texture Jacobian of Heckbert's projective mapping,
//! computed several ways, and the implicit ellipse `A·U² + B·U·V + C·V² = F` it defines.
//!
//! The Jacobian methods all walk a block of pixels row by row (the thesis's set-up is per
//! polygon and per row), filling one [`Jacobian`] per pixel:
//!
//! - [`JacobianMethod::ForwardDifference`] — (2.11), the thesis's baseline: differences of the
//!   mapping at `(x+1, y)` and `(x, y+1)` against `(x, y)`, with `u(x, y)` carried along the
//!   row from the previous pixel's `(x+1, y)` so that four divisions remain per pixel.
//! - [`JacobianMethod::ThesisIncremental`] — (2.16)–(2.21) exactly as printed, errors
//!   included: the wrong sign of (2.13)'s `y` term in the start value of the `∂v/∂x`
//!   numerator, and the `x`-difference denominator `(K+Gx)(L+Gx)` reused for the
//!   `y`-derivatives (2.14)/(2.15).
//! - [`JacobianMethod::CorrectedIncremental`] — the same scheme with the sign fixed and the
//!   `y`-derivatives over `(K+Gx)(K+H+Gx)`: exactly the forward differences of (2.11).
//! - [`JacobianMethod::Analytic`] — the true derivatives: the same numerators over `D²`,
//!   `D = Gx + Hy + I`, one reciprocal per pixel.
//! - [`JacobianMethod::AnalyticParallel`] — the same with every pixel independent.
//!
//! Forward differences (and so both incremental schemes) approximate the derivative at
//! `x + ½` rather than at `x`; their error against [`JacobianMethod::Analytic`] is measured
//! in the tests.
//!
//! Files: the [`Jacobian`] and its [`Axes`] in `ellipse/jacobian.rs`, the methods and
//! [`jacobian_block`] in `ellipse/methods.rs` (one file per method under `ellipse/methods/`),
//! the [`Ellipse`] in `ellipse/implicit.rs`, [`EllipseError`] in `ellipse/error.rs`.

mod error;
mod implicit;
mod jacobian;
mod methods;

pub use error::EllipseError;
pub use implicit::Ellipse;
pub use jacobian::{Axes, Jacobian};
pub use methods::{jacobian_block, JacobianMethod};
