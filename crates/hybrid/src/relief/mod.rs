//! Relief in the G-buffer: the relief pass that runs after the geometry pass on materials
//! with a depth map ([`pass`]), its settings ([`settings`]), the materials' relief inputs
//! made once ([`maps`]), and the measurement of its pixel-depth offset against the exact
//! tracer ([`measure`]).
//!
//! The relief techniques are `renderlab_relief`'s, unchanged: the pass builds each pixel's
//! tangent-space ray from its triangle's exact texture mapping and hands it to the tracer.

pub mod maps;
pub mod measure;
pub mod pass;
pub mod settings;

pub use maps::ReliefMaps;
pub use measure::{measure_pixel_depth_offset, PdoRow};
pub use pass::{relief_pass, ReliefSample, TangentRay};
pub use settings::{ReliefSettings, ReliefTracer};
