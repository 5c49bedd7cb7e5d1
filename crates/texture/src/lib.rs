//! Textures and their filtering: mip pyramids for any size (non-square and
//! non-power-of-two included), and the [`Filter`] trait with nearest, bilinear and trilinear
//! implementations. Every filter reports its texel fetches through a
//! [`Counter`](renderlab_core::counter::Counter), so counting costs nothing when it is off.

#![warn(missing_docs)]

pub mod filter;
pub mod mip;

pub use filter::{Bilinear, Filter, Nearest, Trilinear};
pub use mip::{Texture, Wrap};
