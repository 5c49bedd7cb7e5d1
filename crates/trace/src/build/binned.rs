//! A binary BVH by the binned surface-area heuristic (Wald, "On fast construction of SAH-based
//! bounding volume hierarchies", 2007), built top-down in parallel.
//!
//! Each node bins its primitives' centroids into [`BINS`] equal slices along each of the three
//! axes, sweeps the bins to price every one of the `3·(BINS − 1)` planes by SAH, and splits at
//! the cheapest unless a leaf is cheaper. The cost of a set of `n` primitives is counted in
//! intersection *blocks* (`⌈n / block⌉`), since a leaf's triangles are tested four at a time:
//! a leaf of four costs what a leaf of one does, and the build makes full leaves.
//!
//! A node's bins also give its children's boxes, and the partition, which moves each primitive
//! once, gives the boxes of their centroids, so each level reads the primitives twice (binning,
//! partitioning) and a bin keeps one box, not two (the 1M-triangle terrain's build 5–10 %
//! faster than with two, criterion, alternated; the same trees). Small nodes use fewer bins
//! (about one per primitive), which keeps the plane sweep from costing more than the binning.
//!
//! Parallelism: the two subtrees of a node with at least [`PAR_NODE`] primitives are built as
//! rayon tasks, and a node with at least [`PAR_BIN`] primitives bins in parallel chunks. The
//! result does not depend on the number of threads: bins merge by integer sums and exact
//! min/max, and every node's slots are fixed before its children are built (a subtree over `n`
//! primitives owns `2n − 1` consecutive node slots, left subtree first; some stay unused).
//!
//! Depth is bounded: below depth [`SAH_DEPTH`] nodes split at the object median of their
//! widest centroid axis, which halves them, so no path is longer than [`MAX_DEPTH`] and the
//! traversal's fixed stack cannot overflow. The same median split serves nodes that SAH cannot
//! split (all centroids in one bin) but that are too large for a leaf.

use crate::aabb::Aabb;
use glam::{Vec3, Vec4};
use rayon::prelude::*;

/// Bins per axis (for nodes of at least that many primitives).
pub const BINS: usize = 32;

/// Depth below which SAH is no longer tried.
pub const SAH_DEPTH: usize = 40;

/// The most primitives one hierarchy holds (`2^28`).
pub const MAX_PRIMS: usize = 1 << 28;

/// The longest root-to-leaf path: SAH levels, then median levels that halve at most `2^28`.
pub const MAX_DEPTH: usize = SAH_DEPTH + 28;

/// Subtrees with at least this many primitives are built as parallel tasks.
pub const PAR_NODE: usize = 4096;

/// Nodes with at least this many primitives bin (and bound) in parallel.
pub const PAR_BIN: usize = 1 << 15;

/// Primitives per parallel chunk of a large node's binning.
pub(super) const CHUNK: usize = 1 << 13;

/// A primitive as the builder sees it: its box in two 4-lane vectors (so that unions are one
/// SIMD min and max), with its index in the caller's list stored in the bits of `lo.w`.
#[derive(Clone, Copy, Debug)]
pub struct PrimRef {
    pub(super) lo: Vec4,
    pub(super) hi: Vec4,
}

impl PrimRef {
    /// The primitive `index` with box `b`.
    pub fn new(b: &Aabb, index: u32) -> PrimRef {
        PrimRef { lo: b.min.extend(f32::from_bits(index)), hi: b.max.extend(0.0) }
    }

    /// The primitive's index.
    #[inline]
    pub fn index(&self) -> u32 {
        self.lo.w.to_bits()
    }

    /// The primitive's box.
    pub fn bounds(&self) -> Aabb {
        Aabb { min: self.lo.truncate(), max: self.hi.truncate() }
    }

    /// Twice the box's centre (lane w meaningless).
    #[inline(always)]
    fn centre2(&self) -> Vec4 {
        self.lo + self.hi
    }
}

/// A box in 4-lane vectors, lane w ignored.
#[derive(Clone, Copy, Debug)]
pub(super) struct Box4 {
    pub(super) lo: Vec4,
    pub(super) hi: Vec4,
}

impl Box4 {
    pub(super) const EMPTY: Box4 =
        Box4 { lo: Vec4::splat(f32::INFINITY), hi: Vec4::splat(f32::NEG_INFINITY) };

    #[inline(always)]
    pub(super) fn union(self, o: Box4) -> Box4 {
        Box4 { lo: self.lo.min(o.lo), hi: self.hi.max(o.hi) }
    }

    #[inline(always)]
    pub(super) fn grow(self, p: Vec4) -> Box4 {
        Box4 { lo: self.lo.min(p), hi: self.hi.max(p) }
    }

    #[inline(always)]
    pub(super) fn half_area(&self) -> f32 {
        let d = self.hi - self.lo;
        if !(d.x >= 0.0 && d.y >= 0.0 && d.z >= 0.0) {
            return 0.0;
        }
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    pub(super) fn aabb(&self) -> Aabb {
        Aabb { min: self.lo.truncate(), max: self.hi.truncate() }
    }
}

/// A set's box and the box of its doubled centroids.
#[derive(Clone, Copy, Debug)]
pub(super) struct Bounds {
    pub(super) geometry: Box4,
    pub(super) centres: Box4,
}

impl Bounds {
    const EMPTY: Bounds = Bounds { geometry: Box4::EMPTY, centres: Box4::EMPTY };

    pub(super) fn of(refs: &[PrimRef]) -> Bounds {
        let seq = |refs: &[PrimRef]| {
            refs.iter().fold(Bounds::EMPTY, |b, r| Bounds {
                geometry: b.geometry.union(Box4 { lo: r.lo, hi: r.hi }),
                centres: b.centres.grow(r.centre2()),
            })
        };
        if refs.len() >= PAR_BIN {
            refs.par_chunks(CHUNK).map(seq).reduce(|| Bounds::EMPTY, Bounds::union)
        } else {
            seq(refs)
        }
    }

    fn union(self, o: Bounds) -> Bounds {
        Bounds { geometry: self.geometry.union(o.geometry), centres: self.centres.union(o.centres) }
    }
}

/// A binary node of 32 bytes: its box and two words. An inner node's words are its children's
/// slots; a leaf's are the first of its primitives in [`Bvh2::refs`] and its count with
/// [`Node2::LEAF`] set.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct Node2 {
    /// The box's minimum.
    pub min: [f32; 3],
    /// Left child slot, or a leaf's first primitive.
    pub a: u32,
    /// The box's maximum.
    pub max: [f32; 3],
    /// Right child slot, or a leaf's count with [`Node2::LEAF`] set.
    pub b: u32,
}

impl Node2 {
    /// Marks a leaf's count.
    pub const LEAF: u32 = 1 << 31;

    /// Whether the node is a leaf.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.b & Node2::LEAF != 0
    }

    /// A leaf's primitives: the range of [`Bvh2::refs`] it covers.
    #[inline]
    pub fn prims(&self) -> std::ops::Range<usize> {
        let first = self.a as usize;
        first..first + (self.b & !Node2::LEAF) as usize
    }

    /// The node's box.
    #[inline]
    pub fn bounds(&self) -> Aabb {
        Aabb { min: Vec3::from(self.min), max: Vec3::from(self.max) }
    }
}

/// What the heuristic counts.
#[derive(Clone, Copy, Debug)]
pub struct SahParams {
    /// The most primitives in one leaf.
    pub max_leaf: usize,
    /// Primitives tested together: a set of `n` costs `⌈n / block⌉` intersections.
    pub block: usize,
    /// Cost of visiting a node, relative to one block intersection.
    pub traversal_cost: f32,
}

/// A binary BVH: root at slot 0 (when there are primitives), primitives reordered so that each
/// leaf's are consecutive.
#[derive(Clone, Debug, Default)]
pub struct Bvh2 {
    /// Node slots (`2n − 1` for `n` primitives, some unused).
    pub nodes: Vec<Node2>,
    /// The primitives in leaf order.
    pub refs: Vec<PrimRef>,
}

impl Bvh2 {
    /// The tree's SAH cost under `p`, over its root's half area: each inner node's half area
    /// times the traversal cost, and each leaf's times its blocks. 0 for an empty tree.
    pub fn sah(&self, p: &SahParams) -> f64 {
        let Some(root) = self.nodes.first() else { return 0.0 };
        let (mut cost, mut todo) = (0.0f64, vec![0usize]);
        while let Some(s) = todo.pop() {
            let n = &self.nodes[s];
            let area = n.bounds().half_area() as f64;
            if n.is_leaf() {
                cost += area * blocks(n.prims().len(), p) as f64;
            } else {
                cost += area * p.traversal_cost as f64;
                todo.extend([n.a as usize, n.b as usize]);
            }
        }
        cost / (root.bounds().half_area() as f64).max(f64::MIN_POSITIVE)
    }
}

/// Builds the binary BVH over `refs` (at most [`MAX_PRIMS`]; the callers check).
pub fn build(mut refs: Vec<PrimRef>, params: &SahParams) -> Bvh2 {
    assert!(refs.len() <= MAX_PRIMS, "{} primitives exceed the builder's limit", refs.len());
    if refs.is_empty() {
        return Bvh2::default();
    }
    let mut nodes = vec![Node2::default(); 2 * refs.len() - 1];
    let params = SahParams { max_leaf: params.max_leaf.max(1), block: params.block.max(1), ..*params };
    let bounds = Bounds::of(&refs);
    let at = At { first: 0, slot: 0, depth: 0 };
    build_node(&mut refs, &mut nodes, at, bounds, &params, &mut Bins::new());
    Bvh2 { nodes, refs }
}

/// Where a subtree goes: its first primitive's position in the final order, its root's slot,
/// its root's depth.
#[derive(Clone, Copy, Debug)]
struct At {
    first: usize,
    slot: u32,
    depth: usize,
}

fn build_node(
    refs: &mut [PrimRef],
    nodes: &mut [Node2],
    at: At,
    bounds: Bounds,
    p: &SahParams,
    scratch: &mut Bins,
) {
    let At { first, slot, depth } = at;
    let n = refs.len();
    let fits_leaf = n <= p.max_leaf;
    // A leaf of one block costs the parent's area; any split costs at least that much more.
    let surely_leaf = fits_leaf && blocks(n, p) == 1.0 && p.traversal_cost >= 1.0;
    let mut split = None;
    if n > 1 && !surely_leaf {
        if depth < SAH_DEPTH {
            if let Some(s) = sah_split(refs, &bounds, p, scratch) {
                let area = bounds.geometry.half_area();
                let leaf_cost = blocks(n, p) * area;
                let split_cost = p.traversal_cost * area + s.cost;
                if !(fits_leaf && leaf_cost <= split_cost) {
                    let binner = &s.binner;
                    let (mid, [lc, rc]) = partition(refs, |c| binner.bin(c, s.axis) <= s.bin);
                    if mid > 0 && mid < n {
                        let left = Bounds { geometry: s.left, centres: lc };
                        split = Some((mid, left, Bounds { geometry: s.right, centres: rc }));
                    }
                }
            }
        }
        if split.is_none() && !fits_leaf {
            let mid = median_split(refs, &bounds.centres);
            split = Some((mid, Bounds::of(&refs[..mid]), Bounds::of(&refs[mid..])));
        }
    }
    let b = bounds.geometry.aabb();
    let (min, max) = (b.min.to_array(), b.max.to_array());
    let Some((mid, left_bounds, right_bounds)) = split else {
        nodes[0] = Node2 { min, a: first as u32, max, b: Node2::LEAF | n as u32 };
        return;
    };
    let right = slot + 2 * mid as u32;
    nodes[0] = Node2 { min, a: slot + 1, max, b: right };
    let (left_nodes, right_nodes) = nodes[1..].split_at_mut(2 * mid - 1);
    let (left_refs, right_refs) = refs.split_at_mut(mid);
    let left_at = At { first, slot: slot + 1, depth: depth + 1 };
    let right_at = At { first: first + mid, slot: right, depth: depth + 1 };
    if n >= PAR_NODE {
        rayon::join(
            || build_node(left_refs, left_nodes, left_at, left_bounds, p, scratch),
            || build_node(right_refs, right_nodes, right_at, right_bounds, p, &mut Bins::new()),
        );
    } else {
        build_node(left_refs, left_nodes, left_at, left_bounds, p, scratch);
        build_node(right_refs, right_nodes, right_at, right_bounds, p, scratch);
    }
}

/// `⌈n / block⌉` as the cost of intersecting `n` primitives.
#[inline]
pub(super) fn blocks(n: usize, p: &SahParams) -> f32 {
    n.div_ceil(p.block) as f32
}

/// Maps doubled centroids to bins along each axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct Binner {
    origin: Vec4,
    /// Bins per unit length (0 along an axis where all centroids coincide).
    scale: Vec4,
    bins: usize,
}

impl Binner {
    fn new(centres: &Box4, n: usize) -> Binner {
        let bins = n.clamp(4, BINS);
        let extent = centres.hi - centres.lo;
        let k = bins as f32 * (1.0 - 1e-5);
        let mut scale = Vec4::select(extent.cmpgt(Vec4::ZERO), k / extent, Vec4::ZERO);
        scale.w = 0.0;
        Binner { origin: centres.lo, scale, bins }
    }

    #[inline(always)]
    fn bins_of(&self, c: Vec4) -> [usize; 3] {
        // Clamped as floats (a NaN goes to 0: `max` returns its second operand), then cut to
        // integers: the bins `(x as usize).min(bins − 1)` gives, without a saturating
        // conversion to 64 bits on every lane.
        let f = ((c - self.origin) * self.scale).max(Vec4::ZERO).min(Vec4::splat((self.bins - 1) as f32));
        let i = f.as_ivec4();
        [i.x as usize, i.y as usize, i.z as usize]
    }

    #[inline(always)]
    pub(super) fn bin(&self, c: Vec4, axis: usize) -> usize {
        self.bins_of(c)[axis]
    }
}

/// A bin's primitives: the box around them and how many. (The boxes of their centroids, which
/// the children's binning needs, come from the partition, which reads every primitive once
/// instead of three times.)
#[derive(Clone, Copy)]
struct Bin {
    geometry: Box4,
    count: u32,
}

const EMPTY_BIN: Bin = Bin { geometry: Box4::EMPTY, count: 0 };

/// Bins along the three axes; a node uses the first [`Binner::bins`] of each row. One set is
/// reused by every node of a sequentially built subtree, so that a small node does not pay
/// for clearing all of them.
#[derive(Clone, Copy)]
pub(super) struct Bins([[Bin; BINS]; 3]);

impl Bins {
    pub(super) fn new() -> Bins {
        Bins([[EMPTY_BIN; BINS]; 3])
    }

    fn fill(refs: &[PrimRef], binner: &Binner) -> Bins {
        let mut bins = Bins::new();
        bins.add(refs, binner);
        bins
    }

    fn clear(&mut self, bins: usize) {
        for row in &mut self.0 {
            row[..bins].fill(EMPTY_BIN);
        }
    }

    fn add(&mut self, refs: &[PrimRef], binner: &Binner) {
        let bins = self;
        for r in refs {
            let c = r.centre2();
            let g = Box4 { lo: r.lo, hi: r.hi };
            for (axis, i) in binner.bins_of(c).into_iter().enumerate() {
                let b = &mut bins.0[axis][i];
                b.geometry = b.geometry.union(g);
                b.count += 1;
            }
        }
    }

    fn merge(mut self, other: Bins) -> Bins {
        for axis in 0..3 {
            for (a, b) in self.0[axis].iter_mut().zip(&other.0[axis]) {
                a.geometry = a.geometry.union(b.geometry);
                a.count += b.count;
            }
        }
        self
    }
}

/// The cheapest binned plane: primitives in bins `0..=bin` along `axis` go left.
pub(super) struct Split {
    pub(super) binner: Binner,
    pub(super) axis: usize,
    pub(super) bin: usize,
    /// `Σ half_area(side) · blocks(side)` over the two sides.
    pub(super) cost: f32,
    /// The boxes of the two sides' primitives.
    pub(super) left: Box4,
    pub(super) right: Box4,
}

pub(super) fn sah_split(
    refs: &[PrimRef],
    bounds: &Bounds,
    p: &SahParams,
    scratch: &mut Bins,
) -> Option<Split> {
    let binner = Binner::new(&bounds.centres, refs.len());
    if binner.scale == Vec4::ZERO {
        return None;
    }
    if refs.len() >= PAR_BIN {
        *scratch = refs.par_chunks(CHUNK).map(|c| Bins::fill(c, &binner)).reduce(Bins::new, Bins::merge);
    } else {
        scratch.clear(binner.bins);
        scratch.add(refs, &binner);
    }
    let bins = &*scratch;
    let nb = binner.bins;
    let mut best: Option<(usize, usize, f32)> = None;
    for axis in 0..3 {
        if binner.scale[axis] == 0.0 {
            continue;
        }
        let row = &bins.0[axis][..nb];
        let count = |i: usize| row[i].count as usize;
        if let Some((i, cost)) = sweep(nb, |i| row[i].geometry, count, count, p) {
            if best.is_none_or(|b| cost < b.2) {
                best = Some((axis, i, cost));
            }
        }
    }
    let (axis, bin, cost) = best?;
    let row = &bins.0[axis][..nb];
    let side = |bins: &[Bin]| bins.iter().fold(Box4::EMPTY, |acc, b| acc.union(b.geometry));
    Some(Split { binner, axis, bin, cost, left: side(&row[..=bin]), right: side(&row[bin + 1..]) })
}

/// The cheapest of the planes between `nb` bins along one axis by the SAH, given bin `i`'s box
/// and how many primitives a side gains with it: `to_left(i)` for a side that ends at bin `i`,
/// `to_right(i)` for one that starts there (the same count for object bins; a spatial bin's
/// triangles that start and end in it). Planes with an empty side are skipped. Returns the left
/// side's last bin and `Σ half_area(side) · blocks(side)`; the first of equal costs wins.
pub(super) fn sweep(
    nb: usize,
    geometry: impl Fn(usize) -> Box4,
    to_left: impl Fn(usize) -> usize,
    to_right: impl Fn(usize) -> usize,
    p: &SahParams,
) -> Option<(usize, f32)> {
    // right[i]: the cost of bins i.. as one side, and their count.
    let mut right = [(0.0f32, 0usize); BINS];
    let (mut acc, mut count) = (Box4::EMPTY, 0usize);
    for i in (1..nb).rev() {
        acc = acc.union(geometry(i));
        count += to_right(i);
        right[i] = (acc.half_area() * blocks(count, p), count);
    }
    let (mut acc, mut count) = (Box4::EMPTY, 0usize);
    let mut best: Option<(usize, f32)> = None;
    for i in 0..nb - 1 {
        acc = acc.union(geometry(i));
        count += to_left(i);
        let (right_cost, right_count) = right[i + 1];
        if count == 0 || right_count == 0 {
            continue;
        }
        let cost = acc.half_area() * blocks(count, p) + right_cost;
        if best.is_none_or(|b| cost < b.1) {
            best = Some((i, cost));
        }
    }
    best
}

/// Moves the primitives whose (doubled) centroid `left` accepts to the front; returns how many
/// there are and the boxes of the two sides' centroids.
pub(super) fn partition(refs: &mut [PrimRef], left: impl Fn(Vec4) -> bool) -> (usize, [Box4; 2]) {
    let (mut i, mut j) = (0, refs.len());
    let (mut lc, mut rc) = (Box4::EMPTY, Box4::EMPTY);
    while i < j {
        let c = refs[i].centre2();
        if left(c) {
            lc = lc.grow(c);
            i += 1;
        } else {
            rc = rc.grow(c);
            j -= 1;
            refs.swap(i, j);
        }
    }
    (i, [lc, rc])
}

/// Splits at the median centroid along the widest centroid axis; returns `n / 2`.
pub(super) fn median_split(refs: &mut [PrimRef], centres: &Box4) -> usize {
    let e = centres.hi - centres.lo;
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = refs.len() / 2;
    refs.select_nth_unstable_by(mid, |a, b| a.centre2()[axis].total_cmp(&b.centre2()[axis]));
    mid
}
