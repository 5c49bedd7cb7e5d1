//! Cone maps for cone-step mapping: for every texel, how wide a cone standing on the surface
//! may open upward before it meets (conservative) or ambiguously crosses (relaxed) the relief.
//!
//! # Units and the stepping rule
//!
//! Positions are `(uv, d)`: `uv` in texture coordinates (one tile = 1, repeat wrap) and `d`
//! the depth of [`HeightField`] (0 = top of the relief box, 1 = bottom). A **ratio** `r` is
//! a horizontal UV distance per unit of depth: the cone with apex `(uv, D(uv))` on the surface
//! and ratio `r` is `{(uv′, d) : |uv′ − uv| ≤ r · (D(uv) − d)}`, where `|·|` is the Euclidean
//! length in UV (so on a non-square texture a texel is not a square in these units), and
//! `D` is the bilinear depth of [`HeightField::depth`]. Ratios do not depend on the height
//! scale: a technique whose ray moves `Δuv = s · V.xy / V.z · height_scale` (i.e. `|Δuv| = s`
//! UV per unit of depth, the `uv_per_depth` vector of the techniques) and that stands at
//! depth `t` above the surface (`t < D(uv)`) on the cone's axis may advance its depth by
//!
//! ```text
//! Δt = r · (D(uv) − t) / (s + r)
//! ```
//!
//! which is exactly where it leaves the cone. In tangent-space units (where the box is
//! `height_scale` deep) the cone's half-angle tangent is `r / height_scale`.
//!
//! # The two kinds
//!
//! * [`ConeKind::Conservative`] (Dummer's cone step mapping, 2006): the cone is empty. This
//!   module makes that hold for the *bilinear* surface the techniques actually sample, for
//!   every `uv` that the nearest-texel fetch of [`ConeMap::ratio`] maps to the texel, not
//!   only at texel centres, and across tile borders (see [`ConeMap::build`]). A ray that
//!   steps by the rule above can therefore never jump over surface.
//! * [`ConeKind::Relaxed`] (Policarpo and Oliveira, *Relaxed Cone Stepping for Relief
//!   Mapping*, GPU Gems 3, ch. 18, 2007): the cone may contain surface, but is limited so that
//!   a viewing ray coming down from the top of the box toward the texel cannot pass through a
//!   piece of relief *and come out again* inside the cone. Following their construction: for
//!   a texel `p` and each other texel `q`, take the ray from the top-plane point above `p`
//!   through the surface point of `q`; from `q` it runs inside the relief until it emerges at
//!   an exit point `e`; the cone at `p` must leave `e` outside, i.e.
//!   `r ≤ |e − p| / (d_p − d_e)` whenever `e` lies above `p`'s depth. The ratio is the
//!   smallest such bound. A step may then end below the surface, but with one crossing
//!   behind it, which a binary search finds. This is a heuristic (it reasons about rays from
//!   the top plane only), so the stored ratio is never allowed to fall below the rigorous
//!   conservative one.
//!
//! Every ratio is finite, in `[0, MAX_RATIO]`.

mod pool;
mod relaxed;
mod search;

pub use pool::MAX_RATIO;

use crate::maps::height::HeightField;
use glam::Vec2;
use pool::Pooled;
use renderlab_core::counter::Counter;

/// Which cone map to build (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum ConeKind {
    /// Empty cones: stepping never enters the surface.
    Conservative,
    /// Policarpo and Oliveira's relaxed cones: a step crosses the surface at most once
    /// (for rays from the top plane), to be finished by a binary search.
    Relaxed,
}

/// Cone ratios on a grid of texels covering one tile, fetched nearest-texel with repeat wrap.
#[derive(Clone, Debug)]
pub struct ConeMap {
    width: u32,
    height: u32,
    kind: ConeKind,
    ratios: Vec<f32>,
}

/// The cone-map size for a `width × height` height field and a `max_size` limit: the field's
/// own size when both sides fit, otherwise scaled down (keeping the aspect ratio, each side
/// at least 1) so that the longer side equals `max_size`. A `max_size` of 0 counts as 1.
pub fn cone_map_size(width: u32, height: u32, max_size: u32) -> (u32, u32) {
    let m = max_size.max(1) as u64;
    let longer = width.max(height) as u64;
    if longer <= m {
        return (width, height);
    }
    let scale = |n: u32| ((n as u64 * m + longer / 2) / longer).clamp(1, n as u64) as u32;
    (scale(width), scale(height))
}

impl ConeMap {
    /// Builds the cone map of `field` at [`cone_map_size`]`(…, max_size)`.
    ///
    /// Texel `(x, y)` of the map answers for the UV cell `[x/W, (x+1)/W) × [y/H, (y+1)/H)`
    /// (the region its nearest-texel fetch covers). The conservative ratio is the largest
    /// `r ≤ MAX_RATIO` for which, for every `uv` in that cell and every `uv′` anywhere (tiling),
    /// `D(uv′) ≥ D(uv) − |uv′ − uv| / r` on the bilinear surface `D`. It is found from bounds
    /// that are exact for bilinear patches: near the cell (its 3×3 neighbourhood of map texels)
    /// the steepest bilinear slope there limits `r`; further away, each map cell `Q` limits
    /// `r` to `gap(P, Q) / (max D over P − min D over Q)`, where `gap` is the shortest UV
    /// distance between the two cells (this is the "min-depth pooling" at reduced size). The
    /// search runs outward ring by ring, skipping 8×8 blocks whose lowest depth cannot
    /// beat the current bound, and stops once no farther cell can.
    ///
    /// The relaxed map follows the published construction on the map's own grid: each map
    /// texel gets the depth of the highest field texel whose centre lies in its cell (the
    /// field itself at full size), the surface between map texels is bilinear, every other
    /// texel `q` is tested once (at its nearest copy under tiling), and exit points are found
    /// exactly on that surface (the ray's height above a bilinear patch is quadratic) rather
    /// than by the paper's fixed steps. Where a ray is deep inside the relief it leaps ahead
    /// by the conservative cones of the upside-down surface, which bound how far it surely
    /// stays inside. Texels are tested nearest first and skipped when even an exit at `q`
    /// itself could not lower the ratio. A per-texel work budget bounds pathological fields;
    /// when it runs out the texel keeps the smaller of its best ratio so far and the least
    /// any untested texel could impose (narrower, so still safe). The result is
    /// `max(relaxed, conservative)`, at most `MAX_RATIO`.
    ///
    /// Runs in parallel; deterministic for any thread count.
    pub fn build(field: &HeightField, kind: ConeKind, max_size: u32) -> ConeMap {
        let (wc, hc) = cone_map_size(field.width(), field.height(), max_size);
        let grid = Pooled::new(field, wc, hc);
        let conservative = grid.conservative_ratios();
        let ratios = match kind {
            ConeKind::Conservative => conservative,
            ConeKind::Relaxed => grid.relaxed_ratios(&conservative),
        };
        ConeMap { width: wc, height: hc, kind, ratios }
    }

    /// Width of the map in texels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height of the map in texels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Which construction built the map.
    #[inline]
    pub fn kind(&self) -> ConeKind {
        self.kind
    }

    /// All ratios, row-major (for upload to a GPU texture or for inspection).
    #[inline]
    pub fn ratios(&self) -> &[f32] {
        &self.ratios
    }

    /// The ratio stored at texel `(x, y)`, wrapped.
    #[inline]
    pub fn texel(&self, x: i64, y: i64) -> f32 {
        let xx = renderlab_core::image::wrap_index(x, self.width);
        let yy = renderlab_core::image::wrap_index(y, self.height);
        self.ratios[yy * self.width as usize + xx]
    }

    /// The map texel whose cell contains `uv` (nearest-texel fetch, repeat wrap):
    /// `(floor(u·W) mod W, floor(v·H) mod H)`. Non-finite coordinates map to texel 0.
    #[inline]
    pub fn texel_of(&self, uv: Vec2) -> (u32, u32) {
        let cell = |t: f32, n: u32| -> u32 {
            let t = if t.is_finite() { (t * n as f32).clamp(-1.0e9, 1.0e9) } else { 0.0 };
            renderlab_core::image::wrap_index(renderlab_core::fastmath::floor(t) as i64, n) as u32
        };
        (cell(uv.x, self.width), cell(uv.y, self.height))
    }

    /// The cone ratio for a ray standing above `uv`, fetched from the nearest texel (no
    /// interpolation: the guarantee is per texel cell), counting one fetch. Units and the
    /// stepping rule are in the module documentation.
    #[inline]
    pub fn ratio<C: Counter>(&self, uv: Vec2, counter: &mut C) -> f32 {
        counter.count(1);
        self.ratio_uncounted(uv)
    }

    /// [`ConeMap::ratio`] without counting.
    #[inline]
    pub fn ratio_uncounted(&self, uv: Vec2) -> f32 {
        let (x, y) = self.texel_of(uv);
        self.ratios[y as usize * self.width as usize + x as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_keep_the_aspect_ratio() {
        assert_eq!(cone_map_size(1024, 1024, 256), (256, 256));
        assert_eq!(cone_map_size(1024, 512, 256), (256, 128));
        assert_eq!(cone_map_size(100, 60, 256), (100, 60));
        assert_eq!(cone_map_size(1000, 3, 10), (10, 1));
        assert_eq!(cone_map_size(7, 7, 0), (1, 1));
    }
}
