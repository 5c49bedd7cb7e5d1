//! Ray tracing's acceleration structure: a two-level BVH like DXR's.

#![warn(missing_docs)]

pub mod aabb;
pub mod blas;
pub mod brute;
pub mod build;
pub mod error;
pub mod hit;
pub mod kernel;
pub mod node;
pub mod query;
pub mod ray;
pub mod tlas;
pub mod traverse;
pub mod triangle;

pub use aabb::Aabb;
pub use blas::Blas;
pub use error::BuildError;
pub use hit::{Hit, HitFilter, Opaque};
pub use kernel::Kernel;
pub use ray::Ray;
pub use tlas::{Instance, Tlas};
