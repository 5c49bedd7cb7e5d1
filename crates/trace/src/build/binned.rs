//! A binary BVH by the binned surface-area heuristic (Wald, "On fast construction of SAH-based
//! bounding volume hierarchies", 2007), built top-down in parallel.
//!
//! Each node bins its primitives' centroids into [`BINS`] equal slices along each of the three
//! axes, sweeps the bins to price every one of the `3·(BINS − 1)` planes by SAH, and splits at
//! the cheapest unless a leaf is cheaper. The cost of a set of `n` primitives is counted in
//! intersection *blocks* (`⌈n / block⌉`), since a leaf's triangles are tested four at a time:
//! a leaf of four costs what a leaf of one does, and the build makes full leaves.
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
use glam::Vec3;
use rayon::prelude::*;

/// Bins per axis.
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

const CHUNK: usize = 1 << 13;

/// A primitive as the builder sees it: its box and its index in the caller's list.
#[derive(Clone, Copy, Debug)]
pub struct PrimRef {
    /// The primitive's bounds.
    pub bounds: Aabb,
    /// The primitive's index.
    pub index: u32,
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

/// Builds the binary BVH over `refs` (at most [`MAX_PRIMS`]; the callers check).
pub fn build(mut refs: Vec<PrimRef>, params: &SahParams) -> Bvh2 {
    assert!(refs.len() <= MAX_PRIMS, "{} primitives exceed the builder's limit", refs.len());
    if refs.is_empty() {
        return Bvh2::default();
    }
    let mut nodes = vec![Node2::default(); 2 * refs.len() - 1];
    let params = SahParams { max_leaf: params.max_leaf.max(1), block: params.block.max(1), ..*params };
    build_node(&mut refs, 0, &mut nodes, 0, 0, &params);
    Bvh2 { nodes, refs }
}

/// The depth of the deepest leaf below slot `i` (0 for a leaf).
pub fn depth(bvh: &Bvh2, i: usize) -> usize {
    let n = &bvh.nodes[i];
    if n.is_leaf() {
        0
    } else {
        1 + depth(bvh, n.a as usize).max(depth(bvh, n.b as usize))
    }
}

fn build_node(
    refs: &mut [PrimRef],
    first: usize,
    nodes: &mut [Node2],
    slot: u32,
    depth: usize,
    p: &SahParams,
) {
    let n = refs.len();
    let (bounds, centroids) = bounds_of(refs);
    let mut mid = 0;
    if n > 1 {
        let fits_leaf = n <= p.max_leaf;
        if depth < SAH_DEPTH {
            if let Some(split) = sah_split(refs, &centroids, p) {
                let area = bounds.half_area();
                let leaf_cost = blocks(n, p) * area;
                let split_cost = p.traversal_cost * area + split.cost;
                if !(fits_leaf && leaf_cost <= split_cost) {
                    let binner = Binner::new(&centroids);
                    mid = partition(refs, |r| binner.bin(r.bounds.centre(), split.axis) <= split.bin);
                }
            }
        }
        if (mid == 0 || mid == n) && !fits_leaf {
            mid = median_split(refs, &centroids);
        } else if mid == n {
            mid = 0;
        }
    }
    let (min, max) = (bounds.min.to_array(), bounds.max.to_array());
    if mid == 0 {
        nodes[0] = Node2 { min, a: first as u32, max, b: Node2::LEAF | n as u32 };
        return;
    }
    let right = slot + 2 * mid as u32;
    nodes[0] = Node2 { min, a: slot + 1, max, b: right };
    let (left_nodes, right_nodes) = nodes[1..].split_at_mut(2 * mid - 1);
    let (left_refs, right_refs) = refs.split_at_mut(mid);
    let mut left = move || build_node(left_refs, first, left_nodes, slot + 1, depth + 1, p);
    let mut right = move || build_node(right_refs, first + mid, right_nodes, right, depth + 1, p);
    if n >= PAR_NODE {
        rayon::join(left, right);
    } else {
        left();
        right();
    }
}

/// `⌈n / block⌉` as the cost of intersecting `n` primitives.
#[inline]
fn blocks(n: usize, p: &SahParams) -> f32 {
    n.div_ceil(p.block) as f32
}

/// The primitives' bounds and their centroids' bounds.
fn bounds_of(refs: &[PrimRef]) -> (Aabb, Aabb) {
    let seq = |refs: &[PrimRef]| {
        refs.iter()
            .fold((Aabb::EMPTY, Aabb::EMPTY), |(b, c), r| (b.union(r.bounds), c.grow(r.bounds.centre())))
    };
    if refs.len() >= PAR_BIN {
        refs.par_chunks(CHUNK)
            .map(seq)
            .reduce(|| (Aabb::EMPTY, Aabb::EMPTY), |a, b| (a.0.union(b.0), a.1.union(b.1)))
    } else {
        seq(refs)
    }
}

/// Maps centroids to bins along each axis.
struct Binner {
    origin: Vec3,
    /// Bins per unit length (0 along an axis where all centroids coincide).
    scale: Vec3,
}

impl Binner {
    fn new(centroids: &Aabb) -> Binner {
        let extent = centroids.max - centroids.min;
        let k = BINS as f32 * (1.0 - 1e-5);
        let scale = Vec3::select(extent.cmpgt(Vec3::ZERO), k / extent, Vec3::ZERO);
        Binner { origin: centroids.min, scale }
    }

    #[inline(always)]
    fn bin(&self, c: Vec3, axis: usize) -> usize {
        // `as usize` saturates (and maps NaN to 0), so the index is always in range.
        (((c[axis] - self.origin[axis]) * self.scale[axis]) as usize).min(BINS - 1)
    }
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: u32,
}

const EMPTY_BIN: Bin = Bin { bounds: Aabb::EMPTY, count: 0 };

#[derive(Clone, Copy)]
struct Bins([[Bin; BINS]; 3]);

impl Bins {
    fn fill(refs: &[PrimRef], binner: &Binner) -> Bins {
        let mut bins = Bins([[EMPTY_BIN; BINS]; 3]);
        for r in refs {
            let c = r.bounds.centre();
            for axis in 0..3 {
                let b = &mut bins.0[axis][binner.bin(c, axis)];
                b.bounds = b.bounds.union(r.bounds);
                b.count += 1;
            }
        }
        bins
    }

    fn merge(mut self, other: Bins) -> Bins {
        for axis in 0..3 {
            for (a, b) in self.0[axis].iter_mut().zip(&other.0[axis]) {
                a.bounds = a.bounds.union(b.bounds);
                a.count += b.count;
            }
        }
        self
    }
}

/// The cheapest binned plane: primitives in bins `0..=bin` along `axis` go left.
struct Split {
    axis: usize,
    bin: usize,
    /// `Σ half_area(side) · blocks(side)` over the two sides.
    cost: f32,
}

fn sah_split(refs: &[PrimRef], centroids: &Aabb, p: &SahParams) -> Option<Split> {
    let binner = Binner::new(centroids);
    if binner.scale == Vec3::ZERO {
        return None;
    }
    let bins = if refs.len() >= PAR_BIN {
        refs.par_chunks(CHUNK)
            .map(|c| Bins::fill(c, &binner))
            .reduce(|| Bins([[EMPTY_BIN; BINS]; 3]), Bins::merge)
    } else {
        Bins::fill(refs, &binner)
    };
    let mut best: Option<Split> = None;
    for axis in 0..3 {
        if binner.scale[axis] == 0.0 {
            continue;
        }
        let row = &bins.0[axis];
        // right[i]: the cost of bins i.. as one side.
        let mut right = [(0.0f32, 0usize); BINS];
        let (mut acc, mut count) = (Aabb::EMPTY, 0usize);
        for i in (1..BINS).rev() {
            acc = acc.union(row[i].bounds);
            count += row[i].count as usize;
            right[i] = (acc.half_area() * blocks(count, p), count);
        }
        let (mut acc, mut count) = (Aabb::EMPTY, 0usize);
        for i in 0..BINS - 1 {
            acc = acc.union(row[i].bounds);
            count += row[i].count as usize;
            let (right_cost, right_count) = right[i + 1];
            if count == 0 || right_count == 0 {
                continue;
            }
            let cost = acc.half_area() * blocks(count, p) + right_cost;
            if best.as_ref().is_none_or(|b| cost < b.cost) {
                best = Some(Split { axis, bin: i, cost });
            }
        }
    }
    best
}

/// Moves the primitives for which `left` holds to the front; returns how many there are.
fn partition(refs: &mut [PrimRef], left: impl Fn(&PrimRef) -> bool) -> usize {
    let (mut i, mut j) = (0, refs.len());
    while i < j {
        if left(&refs[i]) {
            i += 1;
        } else {
            j -= 1;
            refs.swap(i, j);
        }
    }
    i
}

/// Splits at the median centroid along the widest centroid axis; returns `n / 2`.
fn median_split(refs: &mut [PrimRef], centroids: &Aabb) -> usize {
    let e = centroids.max - centroids.min;
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = refs.len() / 2;
    refs.select_nth_unstable_by(mid, |a, b| a.bounds.centre()[axis].total_cmp(&b.bounds.centre()[axis]));
    mid
}
