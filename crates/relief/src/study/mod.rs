//! Studies: experiments on the relief techniques that need nothing above this crate (their
//! scenes built from `renderlab_core` meshes, rasterized by `renderlab_raster`), kept as
//! library functions so that examples, the lab and tests run the same code.

pub mod lod;
