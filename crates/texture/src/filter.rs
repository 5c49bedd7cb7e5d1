//! Texture filters. A filter turns a texture coordinate and its screen-space Jacobian
//! (Heckbert's footprint: `duv_dx`, `duv_dy`) into a colour, counting each texel it reads.
//!
//! The [`Filter`] trait with nearest, bilinear and trilinear lookups is in `filter/basic.rs`;
//! [`Bicubic`] (Catmull-Rom), [`Anisotropic`] (probes along the major axis) and [`Ewa`]
//! (Heckbert's elliptical Gaussian) each have a file of their own under `filter/`, and the
//! catalogue of names and parameters is `filter/catalogue.rs`. This file only gathers them,
//! so that no filter file imports its parent.

mod aniso;
mod basic;
mod bicubic;
mod catalogue;
pub mod ewa;

pub use aniso::Anisotropic;
pub use basic::{bilinear_level, lod, trilinear_at, Bilinear, Filter, Nearest, Trilinear};
pub use bicubic::{catmull_rom_weights, Bicubic};
pub use catalogue::{FilterInfo, FilterParseError, FilterSpec, FilterVisitor, FILTERS};
pub use ewa::Ewa;
