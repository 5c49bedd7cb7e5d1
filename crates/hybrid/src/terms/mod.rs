//! The deferred frame's image split by light path, and the same split of the path-traced
//! reference, so that each stage is scored on the term it writes rather than on the whole
//! frame.
//!
//! The frame composes, where the nearest visible surface is opaque,
//! `emitted + direct + diffuse_indirect·AO + specular_indirect`, shows the sky where no
//! surface is, and draws its translucent layer over the pixels a translucent surface covers.
//! The radiance [`Term`]s partition every pixel's light the same way:
//!
//! * [`Term::Emitted`]: what the camera sees without any scattering: the surface's own
//!   emission, or the sky where the camera ray escapes;
//! * [`Term::Direct`]: light from the scene's lights (point, spot, directional, area)
//!   reflected once by the visible opaque surface, with visibility;
//! * [`Term::Diffuse`] and [`Term::Specular`]: everything else the visible opaque surface
//!   reflects (emissive surfaces, the sky, other surfaces' light, any number of bounces),
//!   split by the BRDF's diffuse and specular lobes at that surface;
//! * [`Term::Translucent`]: all the light of a pixel whose nearest visible surface is
//!   translucent.
//!
//! The five sum to the image, in the frame exactly ([`HybridFrame::term_images`](crate::HybridFrame::term_images)) and in the
//! reference from the same paths (`crate::reference`). [`Term::Occlusion`] is not radiance:
//! it is the ambient-occlusion factor of the visible opaque surface, the frame's AO against
//! the converged AO integral.
//!
//! Each stage names the term it writes in its descriptor
//! ([`Descriptor::term`](crate::stages::entry::Descriptor::term)); [`score`] measures a
//! frame's term against the reference's over the pixels where that term matters.

pub mod score;
pub mod term;

pub use score::{area_lit_mask, floor, luminance, score_term, term_mask, Floor, PixelKind, TermScore};
pub use term::{Term, TermImages};
