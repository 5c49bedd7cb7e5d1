//! The precomputed maps the techniques read: the depth field itself, the thesis's complexity
//! map, the relaxed cone map, the packed 16-bit copy of depth and cone ratios, and the
//! min-depth pyramid of space leaping.

pub mod complexity;
pub mod cone;
pub mod height;
pub mod packed;
pub mod pyramid;
