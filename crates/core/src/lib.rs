//! Core types shared by every renderlab crate: images in linear light, colour conversion,
//! image I/O with validation, the camera, meshes with tangent frames, materials, scenes and
//! the per-pixel [`SurfacePoint`] that the rasterizer hands to the shading techniques.
//!
//! Everything here is deterministic and allocation-aware: images are flat arrays, sizes are
//! validated before memory is reserved, and files are written atomically.

#![warn(missing_docs)]

pub mod any_f64;
pub mod apng;
pub mod camera;
pub mod color;
pub mod counter;
pub mod error;
pub mod fastmath;
pub mod fs;
pub mod image;
pub mod io;
pub mod kernel;
pub mod material;
pub mod memory;
pub mod mesh;
pub mod scene;
pub mod srgb8;
pub mod stats;
pub mod surface;
pub mod tempfiles;

pub use camera::Camera;
pub use error::{CoreError, Result};
pub use glam;
pub use image::Image;
pub use material::Material;
pub use mesh::{Mesh, Vertex};
pub use scene::{DirectionalLight, Scene, SceneObject};
pub use surface::{ShadePoint, SurfacePoint};
