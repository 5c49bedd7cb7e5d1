//! Textures and their filtering: mip pyramids for any size (non-square and
//! non-power-of-two included), and the [`Filter`] trait with nearest, bilinear, bicubic,
//! trilinear, anisotropic and EWA implementations and their catalogue ([`FilterSpec`]); [`kernel`]
//! the pixel-filter model that the filters with a kernel and the reference share. Every filter reports its texel fetches through a
//! [`Counter`](renderlab_core::counter::Counter), so counting costs nothing when it is off.
//!
//! [`mapping`] holds Heckbert's perspective-correct (projective) mapping with the thesis's
//! scanline evaluation modes (a catalogue, one file per mode) and their operation counts;
//! [`ellipse`] the EWA footprint Jacobian (a catalogue of methods, one file each) and ellipse
//! coefficients. [`scene`] holds the texture lab's test scenes (a catalogue, one file per
//! scene: exact mappings with analytic Jacobians) and [`reference`](mod@reference) their
//! supersampled ground truth.
//!
//! [`materials`] builds the built-in relief materials (albedo, height and normal maps:
//! `bricks`, `sand_rocks`, `bark_willow`, `brick_pavement`) and [`procedural`] the texture
//! lab's own textures; both take their gradient noise from `renderlab-noise`.

#![warn(missing_docs)]

pub mod ellipse;
mod error;
pub mod filter;
pub mod kernel;
pub mod mapping;
pub mod materials;
pub mod mip;
pub mod procedural;
pub mod reference;
pub mod scene;

pub use ellipse::{Axes, Ellipse, EllipseError, Jacobian, JacobianMethod};
pub use filter::{Anisotropic, Bicubic, Bilinear, Ewa, Filter, FilterSpec, Nearest, Trilinear};
pub use kernel::PixelFilter;
pub use mapping::{MappingError, Mode, Projective, QuadScene};
pub use mip::{Texture, Wrap};
