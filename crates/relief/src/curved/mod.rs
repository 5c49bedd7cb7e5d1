//! Relief on curved and finite surfaces, where it shows at the silhouette.
//!
//! Analytic base shapes ([`sphere`], [`cylinder`], a finite flat [`patch`]) behind one
//! interface ([`shape`]) carry the relief displaced inward along their normals; [`frame`]
//! turns a shape and a camera into a frame's per-pixel surface points and patch information;
//! [`reference`](mod@reference) is the exact world-space reference, which knows coverage; [`crate::study::silhouettes`] measures
//! the silhouette methods against it.

pub mod any_shape;
pub mod cylinder;
pub mod frame;
pub mod patch;
pub mod reference;
pub mod shape;
pub mod sphere;
