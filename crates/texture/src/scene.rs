//! Test scenes for the texture lab: planar surfaces seen through a pinhole camera, each an
//! exact screen→texture mapping with an analytic UV Jacobian per pixel.
//!
//! The parts, a file each: `scene/view.rs` the plane seen through a pinhole camera
//! ([`PlanarView`]: one projective map, its [`Region`] and the [`Footprint`] Jacobian at a
//! pixel); `scene/catalogue.rs` the scenes, one file per scene under `scene/catalogue/` with
//! one `registry!` line each ([`SceneKind`], [`SCENES`]); `scene/test_scene.rs` a scene built
//! for a frame and rendered through a filter ([`TestScene`]); `scene/surface.rs` the per-pixel
//! texture coordinates and Jacobians a rasteriser would hand to the filter ([`Surface`]).
//!
//! **The horizon.** Towards the horizon a pixel's footprint grows without bound. The ground
//! plane is therefore clipped at the depth where one pixel's footprint (the major axis of its
//! Jacobian, at the image's centre column) spans [`FAR_CLIP_TILES`] texture tiles; beyond that
//! depth, up to the horizon and above it, pixels show the background (sky) and are excluded
//! from every metric. Pixels whose footprint is only partly on the surface (quad edges, the
//! clip line) are excluded too ([`crate::reference::Reference::mask`]), so that errors measure
//! filtering, not edge antialiasing, which no texture filter does.

pub mod catalogue;
mod surface;
mod test_scene;
mod view;

pub use crate::error::SceneError;
pub use catalogue::{
    Checkerboard, Descriptor, Entry, Param, SceneKind, ThesisCircuit, ThesisEarth, ThesisQuad, TiltedQuad,
    ZonePlate, FAR_CLIP_TILES, SCENES,
};
pub use surface::{Surface, SurfacePixel};
pub use test_scene::TestScene;
pub use view::{Crop, Footprint, PlanarView, Region};
