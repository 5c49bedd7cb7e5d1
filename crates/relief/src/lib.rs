//! Relief-surface techniques: the parallax family, parallax occlusion mapping (fixed and the
//! thesis's adaptive layer count), relief mapping, cone-step mapping, self-shadowing, the
//! Sobel complexity map, and the exact height-field intersection used as ground truth.
//!
//! Conventions: techniques work on the *depth* map `1 − height` (0 at the top surface), in
//! tangent space where `view_ts` points from the surface toward the eye. A ray entering the
//! top surface at `uv` reaches depth `d` at `uv − V.xy / V.z · height_scale · d`.

#![warn(missing_docs)]

pub mod adaptive;
pub mod complexity;
pub mod cone;
pub mod cone_fast;
pub mod cone_step;
pub mod height;
pub mod material;
pub mod packed;
pub mod parallax;
pub mod pom_simd;
pub mod reference;
pub mod relief_mapping;
pub mod render;
pub mod shade;
pub mod shadow;
pub mod technique;

pub use height::HeightField;
pub use material::ReliefMaterial;
pub use shade::{Frame, FrameInput};
pub use technique::{ReliefHit, ReliefInputs, ReliefTechnique, Shading, Technique};
