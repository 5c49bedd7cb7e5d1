//! The memory layout the traversal reads: 8-wide nodes and 4-triangle leaf blocks.
//!
//! A [`WideNode`] holds its eight children's boxes as six rows of eight floats (min x, max x,
//! min y, max y, min z, max z), so one AVX2 load fetches one plane of all eight children, and
//! eight 32-bit child references. A reference with [`LEAF_BIT`] set is a leaf: in a bottom
//! level the index of a [`TriBlock`], in the top level an instance index; otherwise it is the
//! index of another node. Unused slots have empty boxes (`min = +∞`, `max = −∞`), which no slab
//! test accepts, so the traversal needs no child count.

use crate::aabb::Aabb;
use glam::Vec3;

/// Children per node.
pub const WIDTH: usize = 8;

/// Triangles per leaf block.
pub const BLOCK: usize = 4;

/// Set in a child reference that is a leaf.
pub const LEAF_BIT: u32 = 1 << 31;

/// The reference of an empty hierarchy's root (and of unused child slots).
pub const EMPTY: u32 = u32::MAX;

/// One node of an 8-wide BVH: 256 bytes, aligned to 64, so that a node is exactly four cache
/// lines and its address is its index shifted by 8 (a multiply by 224, the size without the
/// padding, is three cycles more on every step of a walk's chain of dependent loads).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct WideNode {
    /// `bounds[2·axis]` are the children's minima along `axis`, `bounds[2·axis + 1]` their maxima.
    pub bounds: [[f32; WIDTH]; 6],
    /// The children's references.
    pub children: [u32; WIDTH],
    /// Unused (zero): pads the node to 256 bytes.
    pub pad: [u32; WIDTH],
}

const _: () = assert!(std::mem::size_of::<WideNode>() == 256);

impl WideNode {
    /// A node with every slot unused.
    pub const EMPTY: WideNode = WideNode {
        bounds: [
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        children: [EMPTY; WIDTH],
        pad: [0; WIDTH],
    };

    /// Puts a child with box `b` and reference `child` in slot `slot`.
    pub fn set(&mut self, slot: usize, b: &Aabb, child: u32) {
        for axis in 0..3 {
            self.bounds[2 * axis][slot] = b.min[axis];
            self.bounds[2 * axis + 1][slot] = b.max[axis];
        }
        self.children[slot] = child;
    }

    /// The box in slot `slot`.
    pub fn child_bounds(&self, slot: usize) -> Aabb {
        let row = |r: usize| self.bounds[r][slot];
        Aabb { min: Vec3::new(row(0), row(2), row(4)), max: Vec3::new(row(1), row(3), row(5)) }
    }
}

/// Up to four triangles of one leaf, structure-of-arrays: `v[3·j + axis][lane]` is coordinate
/// `axis` of vertex `j` of the triangle in `lane`. 160 bytes. Unused lanes have NaN vertices and
/// primitive `u32::MAX`; the watertight test never hits a NaN triangle.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct TriBlock {
    /// Vertex coordinates, one row per (vertex, axis).
    pub v: [[f32; BLOCK]; 9],
    /// Each lane's triangle index in its mesh.
    pub prim: [u32; BLOCK],
}

impl TriBlock {
    /// A block of the given triangles (at most [`BLOCK`]), the rest padded.
    pub fn new(tris: impl IntoIterator<Item = (u32, [Vec3; 3])>) -> TriBlock {
        let mut b = TriBlock { v: [[f32::NAN; BLOCK]; 9], prim: [u32::MAX; BLOCK] };
        for (lane, (prim, vs)) in tris.into_iter().take(BLOCK).enumerate() {
            for (j, p) in vs.iter().enumerate() {
                for axis in 0..3 {
                    b.v[3 * j + axis][lane] = p[axis];
                }
            }
            b.prim[lane] = prim;
        }
        b
    }

    /// The vertices of the triangle in `lane`.
    #[inline(always)]
    pub fn vertices(&self, lane: usize) -> [[f32; 3]; 3] {
        let p = |j: usize| [self.v[3 * j][lane], self.v[3 * j + 1][lane], self.v[3 * j + 2][lane]];
        [p(0), p(1), p(2)]
    }
}

/// Wide levels on the longest path from `root` down to a leaf (0 for a leaf or [`EMPTY`]).
pub fn depth(nodes: &[WideNode], root: u32) -> usize {
    if root & LEAF_BIT != 0 {
        return 0;
    }
    let n = &nodes[root as usize];
    1 + n.children.iter().filter(|&&c| c != EMPTY).map(|&c| depth(nodes, c)).max().unwrap_or(0)
}
