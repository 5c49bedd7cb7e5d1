//! The EWA footprint ellipse: the screen→texture Jacobian of Heckbert's projective mapping,
//! computed several ways, and the implicit ellipse `A·U² + B·U·V + C·V² = F` it defines.
//!
//! The Jacobian methods ([`JacobianMethod`], one file per method under `ellipse/methods/`,
//! each stating its formula) all walk a block of pixels row by row (the thesis's set-up is
//! per polygon and per row), filling one [`Jacobian`] per pixel: (2.11) forward differences,
//! the thesis's incremental form (2.16)–(2.21) as printed and corrected, and the analytic
//! derivatives, stepped or with every pixel independent.
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
