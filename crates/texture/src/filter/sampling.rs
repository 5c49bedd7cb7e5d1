//! The interface every texture filter implements ([`Filter`]) and the generic code a caller
//! runs with whichever filter a `FilterSpec` names ([`FilterVisitor`], monomorphised per
//! filter so that the inner loops pay no dispatch).

use crate::mip::Texture;
use glam::{Vec2, Vec4};
use renderlab_core::counter::Counter;

/// A texture reconstruction/antialiasing filter.
pub trait Filter: Sync {
    /// Short name used in reports and on the command line.
    fn name(&self) -> &'static str;

    /// Filtered texture value at `uv` for a pixel whose footprint is spanned by
    /// `duv_dx` and `duv_dy` (UV change per pixel step in x and y).
    fn sample<C: Counter>(
        &self,
        tex: &Texture,
        uv: Vec2,
        duv_dx: Vec2,
        duv_dy: Vec2,
        counter: &mut C,
    ) -> Vec4;
}

/// Generic code run with the concrete filter a `FilterSpec` names (monomorphised per filter,
/// so the inner loops pay no dispatch).
pub trait FilterVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the filter.
    fn visit<F: Filter>(self, filter: &F) -> Self::Output;
}
