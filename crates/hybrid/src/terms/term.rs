//! The terms of the frame's composition and one image per term (see [`crate::terms`]).

use glam::Vec3;
use serde::{Deserialize, Serialize};

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
    #[serde(rename = "ao")]
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
    pub const fn slot(self) -> Option<usize> {
        match self {
            Term::Emitted => Some(0),
            Term::Direct => Some(1),
            Term::Diffuse => Some(2),
            Term::Specular => Some(3),
            Term::Translucent => Some(4),
            Term::Occlusion => None,
        }
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_term_is_written_by_its_name_and_read_back() {
        for t in Term::ALL {
            let text = serde_json::to_string(&t).unwrap();
            assert_eq!(text, format!("\"{}\"", t.name()));
            assert_eq!(serde_json::from_str::<Term>(&text).unwrap(), t);
            assert_eq!(Term::from_name(t.name()), Some(t));
        }
        assert_eq!(Term::RADIANCE.iter().map(|t| t.slot().unwrap()).collect::<Vec<_>>(), [0, 1, 2, 3, 4]);
        assert_eq!(Term::Occlusion.slot(), None);
    }
}
