//! A binary BVH with spatial splits (Stich, Friedrich and Dietrich, "Spatial splits in bounding
//! volume hierarchies", 2009): the binned SAH of [`super::binned`], and also planes that cut
//! triangles, a cut triangle going to both sides with the box of its part on each.
//!
//! Where two sides' boxes overlap, a ray through the overlap walks both subtrees, and a ray
//! that starts on the surface (a bounce or a shadow ray) starts inside every box that holds its
//! origin. Cutting the triangles that straddle a plane makes the two boxes meet at the plane
//! instead. The price is references: a cut triangle is in two leaves (its vertices stored
//! twice), and the build bins the triangles' clipped parts.
//!
//! - **Which splits**: at every node of at least [`SplitParams::min_refs`] references, the best
//!   binned object plane and the best binned spatial plane along the same axis are priced by
//!   the SAH, and the
//!   spatial one is taken where it costs less than the object one times `1 + bias`
//!   ([`SplitParams::bias`]). Without the bias the builder's greedy choice rarely cuts (the
//!   69k-triangle blob's SAH 11.443 → 11.418); with 5 % it cuts where the object split is
//!   nearly as good, which on the blob gives children that later split better (SAH 11.110,
//!   6 % fewer node tests a bounce or a primary ray), and on the 1M-triangle terrain a worse
//!   tree (13.863 → 13.977). [`crate::Blas::build`] therefore builds both trees and keeps the
//!   cheaper ([`Splits::Auto`](crate::Splits)).
//! - **How many references**: at most [`SplitParams::budget`] times the triangles more. A node's
//!   allowance goes to its children in proportion to their references, so the tree does not
//!   depend on the number of threads.
//! - **Unsplitting**: a triangle that straddles the chosen plane goes wholly to one side where
//!   the SAH says that is cheaper than cutting it (Stich et al.'s reference unsplitting).
//! - **Conservative parts**: a part's box is the box of the triangle's vertices on the plane's
//!   side and of its edges' crossings of the plane, each crossing widened by 2⁻²⁰ of its edge's
//!   largest coordinates on the two other axes (the crossing is computed in `f32`), then cut
//!   by the plane and by the triangle's previous box. Every point of the triangle is inside the
//!   box of one of its parts, so the hierarchy stays watertight: the traversal tests whole
//!   triangles, and a box only has to hold the part of its triangle it stands for.

use super::binned::{
    blocks, median_split, partition, sah_split, sweep, Bins, Bounds, Box4, Bvh2, Node2, PrimRef, SahParams,
    BINS, CHUNK, MAX_PRIMS, PAR_BIN, PAR_NODE, SAH_DEPTH,
};
use glam::{Vec3, Vec4};
use rayon::prelude::*;

/// When and how much the build cuts triangles.
#[derive(Clone, Copy, Debug)]
pub struct SplitParams {
    /// A spatial split is tried only where the object split's two boxes overlap by more than
    /// this fraction of the root box's half area (Stich et al. use 10⁻⁵; 0 tries everywhere).
    pub alpha: f32,
    /// The most references the cuts may add, as a fraction of the triangles.
    pub budget: f32,
    /// A spatial split is taken where it costs less than the best object split times
    /// `1 + bias`.
    pub bias: f32,
    /// Nodes with fewer references split by objects only (on the blob, cuts below 64
    /// references changed no test count: SAH 11.443 → 11.435).
    pub min_refs: usize,
}

/// The bottom levels' splits: every node of 64 references or more may cut, with a bias of 5 %
/// and at most half as many references more. On the 69k-triangle blob (AMD Zen 3): 3,537 →
/// 4,547 nodes, 17,942 → 23,008 leaf blocks, SAH 11.443 → 11.110; a bounce ray's node tests
/// 6.92 → 6.51 and block tests 2.13 → 2.03, a primary ray's 4.68 → 4.38 and 1.22 → 1.13
/// (callgrind). With a plane per reference and on every axis: a budget of a quarter, 6.64
/// node tests; biases of 1 %, 10 % and 30 %, 6.64, 6.52, 6.51; no bias, 6.78.
pub const SPLITS: SplitParams = SplitParams { alpha: 0.0, budget: 0.5, bias: 0.05, min_refs: 64 };

/// The builder's tree before it is laid out.
enum Tree {
    Leaf(Box4, Vec<PrimRef>),
    Inner(Box4, Box<[Tree; 2]>),
}

/// What every node of one build reads.
struct Ctx<'a, T> {
    /// A triangle's vertices by its index.
    tri: &'a T,
    p: SahParams,
    /// `alpha` times the root's half area.
    min_overlap: f32,
    bias: f32,
    min_refs: usize,
}

/// Builds the binary BVH over `refs` (triangles by index; `tri` gives a triangle's vertices),
/// cutting triangles where `splits` allows. The result has the layout
/// [`super::binned::build`]'s has (each node before its left subtree, then its right one), with
/// no unused slots; a triangle may be in several leaves.
pub fn build<T: Fn(u32) -> [Vec3; 3] + Sync>(
    refs: Vec<PrimRef>,
    tri: &T,
    params: &SahParams,
    splits: &SplitParams,
) -> Bvh2 {
    assert!(refs.len() <= MAX_PRIMS, "{} primitives exceed the builder's limit", refs.len());
    if refs.is_empty() {
        return Bvh2::default();
    }
    let n = refs.len();
    let p = SahParams { max_leaf: params.max_leaf.max(1), block: params.block.max(1), ..*params };
    let bounds = Bounds::of(&refs);
    let min_overlap = splits.alpha * bounds.geometry.half_area();
    let budget = ((n as f64 * splits.budget.max(0.0) as f64) as usize).min(MAX_PRIMS - n);
    let ctx = Ctx { tri, p, min_overlap, bias: splits.bias, min_refs: splits.min_refs };
    let tree = build_node(refs, bounds, 0, budget, &ctx);
    let mut out = Bvh2 { nodes: Vec::with_capacity(2 * n), refs: Vec::with_capacity(n + n / 4) };
    lay_out(tree, &mut out);
    out
}

/// Appends `tree` to `out` depth first, each node before its left subtree, then its right one.
fn lay_out(tree: Tree, out: &mut Bvh2) {
    match tree {
        Tree::Leaf(b, refs) => {
            let b = b.aabb();
            let (min, max) = (b.min.to_array(), b.max.to_array());
            out.nodes.push(Node2 { min, a: out.refs.len() as u32, max, b: Node2::LEAF | refs.len() as u32 });
            out.refs.extend(refs);
        }
        Tree::Inner(b, kids) => {
            let at = out.nodes.len();
            out.nodes.push(Node2::default());
            let [left, right] = *kids;
            lay_out(left, out);
            let r = out.nodes.len() as u32;
            lay_out(right, out);
            let b = b.aabb();
            out.nodes[at] = Node2 { min: b.min.to_array(), a: at as u32 + 1, max: b.max.to_array(), b: r };
        }
    }
}

/// A node's two sides: references, bounds, and the references each may add.
type Sides = [(Vec<PrimRef>, Bounds, usize); 2];

/// The subtree over `refs` (with `bounds`) at `depth`, which may add `budget` references: a
/// spatial split where it is cheaper than the object split by the bias, else the object split,
/// else a leaf; below [`SAH_DEPTH`], or where the SAH finds no split of a node too large for a
/// leaf, the median split (as [`super::binned`]).
fn build_node<T: Fn(u32) -> [Vec3; 3] + Sync>(
    mut refs: Vec<PrimRef>,
    bounds: Bounds,
    depth: usize,
    budget: usize,
    ctx: &Ctx<'_, T>,
) -> Tree {
    let p = &ctx.p;
    let n = refs.len();
    let fits_leaf = n <= p.max_leaf;
    let surely_leaf = fits_leaf && blocks(n, p) == 1.0 && p.traversal_cost >= 1.0;
    let mut sides: Option<Sides> = None;
    if n > 1 && !surely_leaf {
        if depth < SAH_DEPTH {
            let object = sah_split(&refs, &bounds, p, &mut Bins::new());
            let overlap = object.as_ref().map_or(f32::INFINITY, |s| {
                Box4 { lo: s.left.lo.max(s.right.lo), hi: s.left.hi.min(s.right.hi) }.half_area()
            });
            let spatial = if budget > 0 && n >= ctx.min_refs && overlap > ctx.min_overlap {
                // Along the object split's axis only: the other two cost twice the binning
                // and on the 3.3M-triangle blobs bought SAH 16.649 → 16.641.
                spatial_split(&refs, &bounds.geometry, object.as_ref().map(|s| s.axis), ctx)
            } else {
                None
            };
            let object_cost = object.as_ref().map_or(f32::INFINITY, |s| s.cost);
            let best = spatial.as_ref().map_or(object_cost, |s| s.cost.min(object_cost));
            let area = bounds.geometry.half_area();
            let leaf = fits_leaf && blocks(n, p) * area <= p.traversal_cost * area + best;
            if !leaf && best.is_finite() {
                if let Some(s) = spatial.filter(|s| s.cost < object_cost * (1.0 + ctx.bias)) {
                    sides = apply_spatial(&refs, &s, budget, ctx);
                }
                if let (None, Some(s)) = (&sides, object) {
                    let binner = &s.binner;
                    let (mid, [lc, rc]) = partition(&mut refs, |c| binner.bin(c, s.axis) <= s.bin);
                    if mid > 0 && mid < n {
                        let right = refs.split_off(mid);
                        let bl = budget * mid / n;
                        let left = Bounds { geometry: s.left, centres: lc };
                        let rb = Bounds { geometry: s.right, centres: rc };
                        sides = Some([(std::mem::take(&mut refs), left, bl), (right, rb, budget - bl)]);
                    }
                }
            }
        }
        if sides.is_none() && !fits_leaf {
            let mid = median_split(&mut refs, &bounds.centres);
            let right = refs.split_off(mid);
            let (lb, rb) = (Bounds::of(&refs), Bounds::of(&right));
            let bl = budget * mid / n;
            sides = Some([(std::mem::take(&mut refs), lb, bl), (right, rb, budget - bl)]);
        }
    }
    let Some([(lr, lb, lbud), (rr, rb, rbud)]) = sides else {
        return Tree::Leaf(bounds.geometry, refs);
    };
    let big = lr.len() + rr.len() >= PAR_NODE;
    let (left, right) = if big {
        rayon::join(|| build_node(lr, lb, depth + 1, lbud, ctx), || build_node(rr, rb, depth + 1, rbud, ctx))
    } else {
        (build_node(lr, lb, depth + 1, lbud, ctx), build_node(rr, rb, depth + 1, rbud, ctx))
    };
    Tree::Inner(bounds.geometry, Box::new([left, right]))
}

/// A spatial bin: the box of the triangles' parts in it, how many triangles start in it and
/// how many end in it.
#[derive(Clone, Copy)]
struct SpatialBin {
    geometry: Box4,
    entries: u32,
    exits: u32,
}

const EMPTY_SPATIAL: SpatialBin = SpatialBin { geometry: Box4::EMPTY, entries: 0, exits: 0 };

/// The planes of one node: `bins` equal slices of its box along each axis, or along `only`.
#[derive(Clone, Copy)]
struct Planes {
    lo: Vec4,
    width: Vec4,
    inv: Vec4,
    bins: usize,
}

impl Planes {
    fn new(g: &Box4, n: usize, only: Option<usize>) -> Planes {
        // About one plane per eight references: a small node's triangles then span few bins
        // (on the 3.3M-triangle blobs 24 % less build time than one per reference, SAH 16.637 →
        // 16.641).
        let bins = (n / 8).clamp(4, BINS);
        let extent = g.hi - g.lo;
        let width = extent / bins as f32;
        let mut inv = Vec4::select(extent.cmpgt(Vec4::ZERO), bins as f32 / extent, Vec4::ZERO);
        if let Some(a) = only {
            for k in 0..3 {
                if k != a {
                    inv[k] = 0.0;
                }
            }
        }
        Planes { lo: g.lo, width, inv, bins }
    }

    /// The plane between bins `i − 1` and `i` along `axis`.
    #[inline]
    fn plane(&self, axis: usize, i: usize) -> f32 {
        self.lo[axis] + self.width[axis] * i as f32
    }

    /// The bins of a box's two corners along each axis.
    #[inline]
    fn bins_of(&self, lo: Vec4, hi: Vec4) -> ([usize; 3], [usize; 3]) {
        // Clamped as floats (a NaN goes to 0: `max` returns its second operand), then cut to
        // integers: the bins `(x as usize).min(last)` gives, without a saturating conversion
        // to 64 bits on every lane.
        let last = Vec4::splat((self.bins - 1) as f32);
        let bins = |x: Vec4| {
            let i = x.max(Vec4::ZERO).min(last).as_ivec4();
            [i.x as usize, i.y as usize, i.z as usize]
        };
        (bins((lo - self.lo) * self.inv), bins((hi - self.lo) * self.inv))
    }
}

#[derive(Clone, Copy)]
struct SpatialBins([[SpatialBin; BINS]; 3]);

impl SpatialBins {
    fn new() -> SpatialBins {
        SpatialBins([[EMPTY_SPATIAL; BINS]; 3])
    }

    fn fill<T: Fn(u32) -> [Vec3; 3]>(refs: &[PrimRef], planes: &Planes, tri: &T) -> SpatialBins {
        let mut bins = SpatialBins::new();
        for r in refs {
            let whole = Box4 { lo: r.lo, hi: r.hi };
            let mut vertices = None;
            let (firsts, lasts) = planes.bins_of(r.lo, r.hi);
            for axis in 0..3 {
                if planes.inv[axis] == 0.0 {
                    continue;
                }
                let row = &mut bins.0[axis];
                let (first, last) = (firsts[axis], lasts[axis]);
                row[first].entries += 1;
                row[last].exits += 1;
                if first == last {
                    row[first].geometry = row[first].geometry.union(whole);
                    continue;
                }
                let v = *vertices.get_or_insert_with(|| tri(r.index()));
                let mut rest = whole;
                for (i, bin) in row.iter_mut().enumerate().take(last).skip(first) {
                    let (l, r) = split_box(&v, &rest, axis, planes.plane(axis, i + 1));
                    bin.geometry = bin.geometry.union(l);
                    rest = r;
                }
                row[last].geometry = row[last].geometry.union(rest);
            }
        }
        bins
    }

    fn merge(mut self, other: SpatialBins) -> SpatialBins {
        for axis in 0..3 {
            for (a, b) in self.0[axis].iter_mut().zip(&other.0[axis]) {
                a.geometry = a.geometry.union(b.geometry);
                a.entries += b.entries;
                a.exits += b.exits;
            }
        }
        self
    }
}

/// The cheapest spatial plane: `pos` along `axis`, with the sides the sweep priced.
struct SpatialSplit {
    axis: usize,
    pos: f32,
    cost: f32,
    left: Box4,
    right: Box4,
    counts: [usize; 2],
}

fn spatial_split<T: Fn(u32) -> [Vec3; 3] + Sync>(
    refs: &[PrimRef],
    g: &Box4,
    only: Option<usize>,
    ctx: &Ctx<'_, T>,
) -> Option<SpatialSplit> {
    let planes = Planes::new(g, refs.len(), only);
    let tri = ctx.tri;
    let bins = if refs.len() >= PAR_BIN {
        refs.par_chunks(CHUNK)
            .map(|c| SpatialBins::fill(c, &planes, tri))
            .reduce(SpatialBins::new, SpatialBins::merge)
    } else {
        SpatialBins::fill(refs, &planes, tri)
    };
    let p = &ctx.p;
    let nb = planes.bins;
    let mut best: Option<(usize, usize, f32)> = None;
    for axis in 0..3 {
        if planes.inv[axis] == 0.0 {
            continue;
        }
        let row = &bins.0[axis][..nb];
        let (entries, exits) = (|i: usize| row[i].entries as usize, |i: usize| row[i].exits as usize);
        if let Some((i, cost)) = sweep(nb, |i| row[i].geometry, entries, exits, p) {
            if best.is_none_or(|b| cost < b.2) {
                best = Some((axis, i, cost));
            }
        }
    }
    let (axis, bin, cost) = best?;
    let row = &bins.0[axis][..nb];
    let side = |bins: &[SpatialBin]| bins.iter().fold(Box4::EMPTY, |acc, b| acc.union(b.geometry));
    let counts = [
        row[..=bin].iter().map(|b| b.entries as usize).sum(),
        row[bin + 1..].iter().map(|b| b.exits as usize).sum(),
    ];
    Some(SpatialSplit {
        axis,
        pos: planes.plane(axis, bin + 1),
        cost,
        left: side(&row[..=bin]),
        right: side(&row[bin + 1..]),
        counts,
    })
}

/// Sends each reference to the side of `s`'s plane it lies on, cutting (or, where cheaper,
/// not cutting) those that straddle it. `None` where a side would be empty or hold every
/// reference, or the cuts would exceed the node's allowance.
fn apply_spatial<T: Fn(u32) -> [Vec3; 3] + Sync>(
    refs: &[PrimRef],
    s: &SpatialSplit,
    budget: usize,
    ctx: &Ctx<'_, T>,
) -> Option<Sides> {
    let p = &ctx.p;
    let (axis, pos) = (s.axis, s.pos);
    let [nl, nr] = s.counts;
    let (al, ar) = (s.left.half_area(), s.right.half_area());
    let cost_cut = al * blocks(nl, p) + ar * blocks(nr, p);
    let (mut left, mut right) = (Vec::with_capacity(nl), Vec::with_capacity(nr));
    for r in refs {
        if r.hi[axis] <= pos {
            left.push(*r);
        } else if r.lo[axis] >= pos {
            right.push(*r);
        } else {
            let whole = Box4 { lo: r.lo, hi: r.hi };
            let to_left =
                s.left.union(whole).half_area() * blocks(nl, p) + ar * blocks(nr.saturating_sub(1), p);
            let to_right =
                al * blocks(nl.saturating_sub(1), p) + s.right.union(whole).half_area() * blocks(nr, p);
            if to_left <= cost_cut.min(to_right) {
                left.push(*r);
            } else if to_right <= cost_cut {
                right.push(*r);
            } else {
                let (l, rr) = split_box(&(ctx.tri)(r.index()), &whole, axis, pos);
                match (is_empty(&l), is_empty(&rr)) {
                    (false, false) => {
                        left.push(with_box(r, &l));
                        right.push(with_box(r, &rr));
                    }
                    (false, true) => left.push(*r),
                    _ => right.push(*r),
                }
            }
        }
    }
    let n = refs.len();
    let added = (left.len() + right.len()).checked_sub(n)?;
    if left.is_empty() || right.is_empty() || left.len() == n || right.len() == n || added > budget {
        return None;
    }
    let rest = budget - added;
    let bl = rest * left.len() / (left.len() + right.len());
    let (lb, rb) = (Bounds::of(&left), Bounds::of(&right));
    Some([(left, lb, bl), (right, rb, rest - bl)])
}

/// Whether `b` holds no point.
fn is_empty(b: &Box4) -> bool {
    !(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z)
}

/// The reference `r` (its triangle) with box `b`.
fn with_box(r: &PrimRef, b: &Box4) -> PrimRef {
    PrimRef { lo: b.lo.truncate().extend(r.lo.w), hi: b.hi.truncate().extend(0.0) }
}

/// The boxes of triangle `v`'s parts within `b` on either side of the plane `x[axis] = pos`
/// (either may be empty), conservative as the module doc says.
fn split_box(v: &[Vec3; 3], b: &Box4, axis: usize, pos: f32) -> (Box4, Box4) {
    let (mut l, mut r) = (Box4::EMPTY, Box4::EMPTY);
    for i in 0..3 {
        let (p, q) = (v[i], v[(i + 1) % 3]);
        let (pa, qa) = (p[axis], q[axis]);
        let p4 = p.extend(0.0);
        if pa <= pos {
            l = l.grow(p4);
        }
        if pa >= pos {
            r = r.grow(p4);
        }
        if (pa < pos && qa > pos) || (pa > pos && qa < pos) {
            let t = (pos - pa) / (qa - pa);
            let c = p + (q - p) * t;
            let e = p.abs().max(q.abs()) * (1.0 / (1u32 << 20) as f32);
            let (mut lo, mut hi) = (c - e, c + e);
            lo[axis] = pos;
            hi[axis] = pos;
            let (lo, hi) = (lo.extend(0.0), hi.extend(0.0));
            l = l.grow(lo).grow(hi);
            r = r.grow(lo).grow(hi);
        }
    }
    let clip = |mut s: Box4, below: bool| {
        s.lo = s.lo.max(b.lo);
        s.hi = s.hi.min(b.hi);
        if below {
            s.hi[axis] = s.hi[axis].min(pos);
        } else {
            s.lo[axis] = s.lo[axis].max(pos);
        }
        s
    };
    (clip(l, true), clip(r, false))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aabb::Aabb;
    use proptest::prelude::*;

    fn v3() -> impl Strategy<Value = Vec3> {
        prop::array::uniform3(-10.0f32..10.0).prop_map(Vec3::from)
    }

    fn inside(b: &Box4, x: Vec3) -> bool {
        (0..3).all(|k| b.lo[k] <= x[k] && x[k] <= b.hi[k])
    }

    proptest! {
        /// Cut twice, a triangle's four parts hold every point of it: its vertices, points on
        /// its edges and inside it where `f32` gives them exactly (weights of 1/8), and the
        /// parts lie in the triangle's box on their sides of the planes.
        #[test]
        fn parts_hold_the_triangle(a in v3(), b in v3(), c in v3(), axes in (0usize..3, 0usize..3),
                                   f in (0.0f32..1.0, 0.0f32..1.0)) {
            let v = [a, b, c];
            let whole = Aabb::from_points(&v);
            let b0 = Box4 { lo: whole.min.extend(0.0), hi: whole.max.extend(0.0) };
            let pos1 = whole.min[axes.0] + f.0 * (whole.max[axes.0] - whole.min[axes.0]);
            let pos2 = whole.min[axes.1] + f.1 * (whole.max[axes.1] - whole.min[axes.1]);
            let (l, r) = split_box(&v, &b0, axes.0, pos1);
            prop_assert!(is_empty(&l) || l.hi[axes.0] <= pos1);
            prop_assert!(is_empty(&r) || r.lo[axes.0] >= pos1);
            let parts: Vec<Box4> = [l, r]
                .iter()
                .flat_map(|p| {
                    let (x, y) = split_box(&v, p, axes.1, pos2);
                    [x, y]
                })
                .collect();
            for p in parts.iter().filter(|p| !is_empty(p)) {
                prop_assert!(inside(&b0, p.lo.truncate()) && inside(&b0, p.hi.truncate()));
            }
            // Where the edges cross the planes, computed in f64 (to far below an f32 ulp): the
            // f32 crossing the cut computes may round inward, which the widening covers.
            let held64 = |x: [f64; 3]| {
                parts.iter().any(|p| {
                    (0..3).all(|k| {
                        let slack = 1e-12 * x[k].abs();
                        p.lo[k] as f64 - slack <= x[k] && x[k] <= p.hi[k] as f64 + slack
                    })
                })
            };
            for (axis, pos) in [(axes.0, pos1), (axes.1, pos2)] {
                for i in 0..3 {
                    let (p, q) = (v[i], v[(i + 1) % 3]);
                    let (pa, qa) = (p[axis] as f64, q[axis] as f64);
                    let pos = pos as f64;
                    if (pa < pos && qa > pos) || (pa > pos && qa < pos) {
                        let t = (pos - pa) / (qa - pa);
                        let x = [0, 1, 2].map(|k| p[k] as f64 + (q[k] as f64 - p[k] as f64) * t);
                        prop_assert!(held64(x), "crossing {:?} outside every part", x);
                    }
                }
            }
            // Points of the triangle, each computed in f64 and kept where f32 holds it exactly.
            for i in 0..=8 {
                for j in 0..=8 - i {
                    let (u, w) = (i as f64 / 8.0, j as f64 / 8.0);
                    let x = [0, 1, 2].map(|k| {
                        a[k] as f64 * (1.0 - u - w) + b[k] as f64 * u + c[k] as f64 * w
                    });
                    let x32 = x.map(|t| t as f32);
                    if (0..3).any(|k| x32[k] as f64 != x[k]) {
                        continue;
                    }
                    let x32 = Vec3::from(x32);
                    prop_assert!(parts.iter().any(|p| inside(p, x32)), "{:?} outside every part", x32);
                }
            }
        }
    }

    /// A random triangle soup of thin slivers in every direction.
    fn slivers(n: usize, seed: u64) -> Vec<[Vec3; 3]> {
        let mut s = seed;
        let mut next = move || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((s >> 40) as f32) / (1u64 << 24) as f32
        };
        (0..n)
            .map(|_| {
                let p = Vec3::new(next(), next(), next()) * 10.0;
                let d = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 6.0;
                let e = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 0.2;
                [p, p + d, p + d * 0.5 + e]
            })
            .collect()
    }

    /// The spatial build keeps every triangle, adds at most its allowance, nests its boxes, and
    /// its leaves' boxes together hold every triangle's sample points; with the bias it cuts
    /// slivers (more references than triangles).
    #[test]
    fn the_build_covers_every_triangle() {
        let tris = slivers(3000, 7);
        let refs: Vec<PrimRef> =
            tris.iter().enumerate().map(|(i, t)| PrimRef::new(&Aabb::from_points(t), i as u32)).collect();
        let p = SahParams { max_leaf: 4, block: 4, traversal_cost: 1.0 };
        let bvh = build(refs, &|t| tris[t as usize], &p, &SPLITS);
        assert!(bvh.refs.len() > tris.len(), "no triangle was cut");
        assert!(bvh.refs.len() <= tris.len() + tris.len() / 2);
        let mut leaves_of = vec![Vec::new(); tris.len()];
        let mut todo = vec![0usize];
        while let Some(s) = todo.pop() {
            let n = &bvh.nodes[s];
            if n.is_leaf() {
                assert!(n.prims().len() <= 4);
                for r in &bvh.refs[n.prims()] {
                    let b = r.bounds();
                    assert!(n.bounds().union(b) == n.bounds(), "a part outside its leaf");
                    leaves_of[r.index() as usize].push(b);
                }
            } else {
                for c in [n.a as usize, n.b as usize] {
                    assert!(
                        n.bounds().union(bvh.nodes[c].bounds()) == n.bounds(),
                        "a child outside its node"
                    );
                    todo.push(c);
                }
            }
        }
        for (t, parts) in leaves_of.iter().enumerate() {
            assert!(!parts.is_empty(), "triangle {t} in no leaf");
            let [a, b, c] = tris[t];
            for i in 0..=4 {
                for j in 0..=4 - i {
                    let (u, w) = (i as f32 / 4.0, j as f32 / 4.0);
                    let x = a * (1.0 - u - w) + b * u + c * w;
                    // Sample points computed in f32 stray from the triangle by rounding.
                    let e = Vec3::splat(1e-4);
                    let held = parts.iter().any(|p| (p.min - e).cmple(x).all() && x.cmple(p.max + e).all());
                    assert!(held, "triangle {t}: {x:?} in none of its parts");
                }
            }
        }
    }
}
