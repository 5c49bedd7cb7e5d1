//! Studies: measurements of one feature of the relief renderer against its exact reference,
//! that need nothing above this crate (their scenes built from `renderlab_core` meshes,
//! rasterized by `renderlab_raster`), kept as library functions that return their rows so
//! that examples, the lab and tests run the same code.
//!
//! - [`grazing`]: self-shadowing at grazing light against the exact hard shadow.
//! - [`lod`]: level of detail per distance band and on a camera path.
//! - [`silhouettes`]: coverage of the relief's outline on curved and finite shapes
//!   ([`crate::curved`]).

pub mod grazing;
pub mod lod;
pub mod silhouettes;
