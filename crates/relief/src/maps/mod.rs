//! The precomputed maps the techniques read: the depth field itself, the thesis's complexity
//! map, the relaxed cone map and the packed 16-bit copy of depth and cone ratios.

pub mod complexity;
pub mod cone;
pub mod height;
pub mod packed;
