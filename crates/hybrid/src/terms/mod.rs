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
//! The five sum to the image, in the frame exactly ([`TermImages::of_frame`]) and in the
//! reference from the same paths (`crate::reference`). [`Term::Occlusion`] is not radiance:
//! it is the ambient-occlusion factor of the visible opaque surface, the frame's AO against
//! the converged AO integral.
//!
//! Each stage names the term it writes in its descriptor
//! ([`Descriptor::term`](crate::stages::entry::Descriptor::term)); [`score`] measures a
//! frame's term against the reference's over the pixels where that term matters.

pub mod score;

use crate::renderer::HybridFrame;
use glam::Vec3;
use serde::{Deserialize, Serialize};

pub use score::{area_lit_mask, floor_mse, luminance, score_term, term_mask, PixelKind, TermScore};

/// One term of the frame's composition (see the module's notes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Term {
    /// Emission of the visible opaque surface, or the sky where the camera ray escapes.
    Emitted,
    /// The lights' light reflected once by the visible opaque surface.
    Direct,
    /// Indirect light reflected by the visible opaque surface's diffuse lobe.
    Diffuse,
    /// Indirect light reflected by the visible opaque surface's specular lobe.
    Specular,
    /// All the light of pixels whose nearest visible surface is translucent.
    Translucent,
    /// The ambient-occlusion factor of the visible opaque surface (not radiance).
    Occlusion,
}

impl Term {
    /// The radiance terms, whose sum is the image, in slot order.
    pub const RADIANCE: [Term; 5] =
        [Term::Emitted, Term::Direct, Term::Diffuse, Term::Specular, Term::Translucent];

    /// Every term.
    pub const ALL: [Term; 6] =
        [Term::Emitted, Term::Direct, Term::Diffuse, Term::Specular, Term::Translucent, Term::Occlusion];

    /// The term's name in results and file names.
    pub fn name(self) -> &'static str {
        match self {
            Term::Emitted => "emitted",
            Term::Direct => "direct",
            Term::Diffuse => "diffuse",
            Term::Specular => "specular",
            Term::Translucent => "translucent",
            Term::Occlusion => "ao",
        }
    }

    /// The term named `name`.
    pub fn from_name(name: &str) -> Option<Term> {
        Term::ALL.into_iter().find(|t| t.name() == name)
    }

    /// The slot of a radiance term in [`TermImages::radiance`] (`None` for occlusion).
    pub fn slot(self) -> Option<usize> {
        Term::RADIANCE.iter().position(|&t| t == self)
    }
}

/// One image per term, row-major, in linear radiance (occlusion in [0, 1]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TermImages {
    /// The radiance terms in the order of [`Term::RADIANCE`].
    pub radiance: [Vec<Vec3>; 5],
    /// The ambient-occlusion factor (1 = open; 1 where no opaque surface is visible).
    pub occlusion: Vec<f32>,
}

impl TermImages {
    /// Every term zero (AO open) for `pixels` pixels.
    pub fn zero(pixels: usize) -> Self {
        Self { radiance: std::array::from_fn(|_| vec![Vec3::ZERO; pixels]), occlusion: vec![1.0; pixels] }
    }

    /// The image of radiance term `term`; `None` for [`Term::Occlusion`].
    pub fn get(&self, term: Term) -> Option<&[Vec3]> {
        term.slot().map(|s| self.radiance[s].as_slice())
    }

    /// The sum of the radiance terms: the image they compose.
    pub fn sum(&self) -> Vec<Vec3> {
        let n = self.occlusion.len();
        (0..n).map(|i| self.radiance.iter().fold(Vec3::ZERO, |s, img| s + img[i])).collect()
    }

    /// The frame's terms: where the G-buffer's nearest visible surface is translucent, the
    /// whole pixel is [`Term::Translucent`]; where it is opaque, the lighting terms the stages
    /// wrote (the diffuse term times AO, as the composition multiplies it); where no surface
    /// is, the sky is [`Term::Emitted`]. On pixels without a translucent layer they sum to
    /// the frame's image exactly as the composition adds them.
    pub fn of_frame(frame: &HybridFrame) -> Self {
        let g = &frame.gbuffer;
        let t = &frame.terms;
        let mut out = Self::zero(frame.hdr.len());
        for i in 0..frame.hdr.len() {
            if g.translucent[i].is_some() {
                out.radiance[4][i] = frame.hdr[i];
                continue;
            }
            match &g.opaque[i] {
                None => out.radiance[0][i] = frame.hdr[i],
                Some(sp) => {
                    out.radiance[0][i] = sp.emissive;
                    out.radiance[1][i] = t.direct[i];
                    out.radiance[2][i] = t.diffuse_indirect[i] * t.ambient_occlusion[i];
                    out.radiance[3][i] = t.specular_indirect[i];
                    out.occlusion[i] = t.ambient_occlusion[i];
                }
            }
        }
        out
    }
}
