//! Relief-surface techniques: the parallax family, parallax occlusion mapping (fixed and the
//! thesis's adaptive layer count), relief mapping, cone-step mapping, self-shadowing, the
//! Sobel complexity map, and the exact height-field intersection used as ground truth.

pub mod height;

pub use height::HeightField;
