//! A view's reference by term as the rows are scored against it, and as it is kept on disk.
//!
//! When a view's reference is rendered, each term's mask and the reference's noise floor on
//! it are fixed ([`renderlab_hybrid::terms`]): the floors go into `refs/VIEW.json`, the mean
//! term images into `refs/VIEW.term-NAME.exr` (exact floats) and the pixel kinds, the
//! ambient-occlusion reference and the area lights' share of the unshadowed direct light into
//! `refs/VIEW.aux.exr`. A resumed run reads them back and rebuilds the same masks, so a row
//! is scored alike whether its reference was just rendered or read.

use super::record::{TermFloor, TermFloors};
use super::store::{RunDir, View};
use crate::error::{LabError, Result};
use glam::Vec3;
use renderlab_core::io::{load_color, save_exr};
use renderlab_core::Image;
use renderlab_hybrid::terms::{area_lit_mask, floor, luminance, score_term, term_mask, PixelKind};
use renderlab_hybrid::{HybridFrame, Reference, Term, TermImages, TermScore};
use std::path::PathBuf;

/// A frame pixel counts as black below this luminance.
pub const BLACK: f32 = 1e-4;
/// A reference pixel counts as lit above this luminance (so that a pixel dark in the
/// reference too is not counted).
pub const LIT: f32 = 1e-2;

/// A view's reference by term, with its masks.
#[derive(Clone, Debug)]
pub struct ViewTerms {
    mean: TermImages,
    kinds: Vec<PixelKind>,
    area_share: Vec<f32>,
    masks: Vec<(Vec<bool>, String)>,
    area_lit: (Vec<bool>, String),
    floors: TermFloors,
}

impl ViewTerms {
    /// The terms of a reference just rendered, their masks and floors.
    pub fn of_reference(r: &Reference) -> Self {
        let mean = r.mean_terms();
        let area_share = r.area_share.clone();
        let [a, b] = &r.terms;
        let floors = |masks: &[(Vec<bool>, String)], area_lit: &(Vec<bool>, String)| TermFloors {
            terms: Term::ALL
                .iter()
                .zip(masks)
                .map(|(&term, (m, _))| TermFloor {
                    term,
                    mask_pixels: count(m),
                    floor: floor(term, a, b, &mean, m),
                })
                .collect(),
            area_lit: TermFloor {
                term: Term::Direct,
                mask_pixels: count(&area_lit.0),
                floor: floor(Term::Direct, a, b, &mean, &area_lit.0),
            },
        };
        let (masks, area_lit) = masks(&area_share, &r.kinds);
        let floors = floors(&masks, &area_lit);
        Self { mean, kinds: r.kinds.clone(), area_share, masks, area_lit, floors }
    }

    /// The floors (for `refs/VIEW.json`).
    pub fn floors(&self) -> &TermFloors {
        &self.floors
    }

    /// Every file [`Self::save`] writes for `view` (what a merge copies).
    pub fn files(dir: &RunDir, view: &View) -> Vec<PathBuf> {
        let (mut terms, aux) = Self::paths(dir, view);
        terms.push(aux);
        terms
    }

    /// The term images' files of `view`.
    fn paths(dir: &RunDir, view: &View) -> (Vec<PathBuf>, PathBuf) {
        let term = |t: Term| dir.refs_dir().join(format!("{}.term-{}.exr", view.id, t.name()));
        (
            Term::RADIANCE.iter().map(|&t| term(t)).collect(),
            dir.refs_dir().join(format!("{}.aux.exr", view.id)),
        )
    }

    /// Writes the term images of `view` (each atomically).
    pub fn save(&self, dir: &RunDir, view: &View, width: u32, height: u32) -> Result<()> {
        let (terms, aux) = Self::paths(dir, view);
        for (path, img) in terms.iter().zip(&self.mean.radiance) {
            save_exr(path, &Image::from_vec(width, height, img.clone())?)?;
        }
        let packed = (0..self.kinds.len())
            .map(|i| Vec3::new(self.mean.occlusion[i], self.kinds[i].code(), self.area_share[i]))
            .collect();
        save_exr(&aux, &Image::from_vec(width, height, packed)?)?;
        Ok(())
    }

    /// Reads back the term images of `view` written by [`Self::save`], at `width × height`,
    /// with the floors from its `refs/VIEW.json`.
    pub fn load(dir: &RunDir, view: &View, width: u32, height: u32, floors: &TermFloors) -> Result<Self> {
        let (terms, aux) = Self::paths(dir, view);
        let read = |p: &PathBuf| -> Result<Vec<Vec3>> {
            let img = load_color(p)?;
            if img.size() != (width, height) {
                return Err(LabError::Hybrid(format!("{} is {}x{}", p.display(), img.width(), img.height())));
            }
            Ok(img.pixels().to_vec())
        };
        let mut radiance: [Vec<Vec3>; 5] = Default::default();
        for (slot, p) in radiance.iter_mut().zip(&terms) {
            *slot = read(p)?;
        }
        let packed = read(&aux)?;
        let kinds =
            packed.iter().map(|p| PixelKind::from_code(p.y)).collect::<Option<Vec<_>>>().ok_or_else(
                || LabError::Hybrid(format!("{}: a pixel kind is not 0, 1 or 2", aux.display())),
            )?;
        let mean = TermImages { radiance, occlusion: packed.iter().map(|p| p.x).collect() };
        let area_share: Vec<f32> = packed.iter().map(|p| p.z).collect();
        if floors.terms.len() != Term::ALL.len() {
            return Err(LabError::Hybrid(format!("the reference of {} has no floor per term", view.id)));
        }
        let (masks, area_lit) = masks(&area_share, &kinds);
        Ok(Self { mean, kinds, area_share, masks, area_lit, floors: floors.clone() })
    }

    /// Every term of `frame` scored (in the order of [`Term::ALL`]), the direct term over
    /// the area-lit pixels, and the translucent pixels the frame shows black where the
    /// reference does not.
    pub fn score(&self, frame: &HybridFrame) -> (Vec<TermScore>, TermScore, u64) {
        let x = frame.term_images();
        let scores = Term::ALL
            .iter()
            .zip(&self.masks)
            .zip(&self.floors.terms)
            .map(|((&t, (m, label)), f)| score_term(t, &x, &self.mean, m, label, f.floor))
            .collect();
        let (m, label) = &self.area_lit;
        let area = score_term(Term::Direct, &x, &self.mean, m, label, self.floors.area_lit.floor);
        let reference = self.mean.get(Term::Translucent).expect("a radiance term");
        let black = (0..self.kinds.len())
            .filter(|&i| {
                self.kinds[i] == PixelKind::Translucent
                    && luminance(frame.hdr[i]) < BLACK
                    && luminance(reference[i]) > LIT
            })
            .count() as u64;
        (scores, area, black)
    }
}

/// Each term's mask (in the order of [`Term::ALL`]) and the area-lit mask.
#[allow(clippy::type_complexity)]
fn masks(area_share: &[f32], kinds: &[PixelKind]) -> (Vec<(Vec<bool>, String)>, (Vec<bool>, String)) {
    (Term::ALL.iter().map(|&t| term_mask(t, kinds)).collect(), area_lit_mask(area_share, kinds))
}

fn count(mask: &[bool]) -> u64 {
    mask.iter().filter(|&&m| m).count() as u64
}
