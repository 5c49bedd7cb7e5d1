//! The memory layout the traversal reads: 8-wide nodes and 4-triangle leaf blocks.
//!
//! A [`WideNode`] holds its eight children's boxes as six rows of eight floats (min x, max x,
//! min y, max y, min z, max z), so one AVX2 load fetches one plane of all eight children, and
//! eight 32-bit child references. A reference with [`LEAF_BIT`] set is a leaf: in a bottom
//! level a [`TriBlock`], in the top level an instance index; otherwise it is another node. A
//! bottom level keeps its nodes and blocks together in an [`Arena`], where a reference is an
//! offset in [`UNIT`]s; a top level keeps its nodes in an array, where it is an index (both
//! are [`Nodes`] to the walk). Unused slots have empty boxes (`min = +∞`, `max = −∞`), which
//! no slab test accepts, so the traversal needs no child count.

use crate::aabb::Aabb;
use crate::error::BuildError;
use crate::pages::Lines;
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
    /// Per child that is a node in an [`Arena`]: the cache lines of that node's own leaf
    /// blocks, which follow it there (a packet walk entering the child requests them with the
    /// child's lines; a single ray's walk requests a fixed count,
    /// [`crate::traverse::walk::AHEAD`]). Zero elsewhere; pads the node to 256 bytes.
    pub after: [u32; WIDTH],
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
        after: [0; WIDTH],
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
pub fn depth<N: Nodes + ?Sized>(nodes: &N, root: u32) -> usize {
    if root & LEAF_BIT != 0 {
        return 0;
    }
    let n = nodes.get(root);
    1 + n.children.iter().filter(|&&c| c != EMPTY).map(|&c| depth(nodes, c)).max().unwrap_or(0)
}

/// Where a walk finds the nodes of a hierarchy by their references: an array indexed by
/// node number (a top level's [`WideNode`]s) or an [`Arena`] (a bottom level's).
pub trait Nodes {
    /// The node with reference `r` (without [`LEAF_BIT`]).
    ///
    /// # Safety
    /// `r` is a node reference of this store's hierarchy.
    unsafe fn node(&self, r: u32) -> &WideNode;

    /// [`Nodes::node`], checked: panics on a reference outside the store.
    fn get(&self, r: u32) -> &WideNode;

    /// Whether leaf references address this store too, in the same units as node references
    /// (an [`Arena`]'s leaf blocks): a walk may then request a child's lines without
    /// asking which kind it is ([`Nodes::address`]).
    const SHARED: bool = false;

    /// The address that reference `r` (without [`LEAF_BIT`]) stands for where the store is
    /// [`Nodes::SHARED`], a node's or a leaf block's; elsewhere only a node's. For requests
    /// ahead of a walk, which never fault: `r` need not be in the store.
    fn address(&self, r: u32) -> *const u8;
}

impl Nodes for [WideNode] {
    #[inline(always)]
    unsafe fn node(&self, r: u32) -> &WideNode {
        debug_assert!((r as usize) < self.len());
        self.get_unchecked(r as usize)
    }

    fn get(&self, r: u32) -> &WideNode {
        &self[r as usize]
    }

    #[inline(always)]
    fn address(&self, r: u32) -> *const u8 {
        self.as_ptr().wrapping_add(r as usize) as *const u8
    }
}

/// The bytes of one reference unit of an [`Arena`]: eight, the largest scale of an x86
/// address, so that a walk turns a reference into an address in one step (`base + 8·r`, where
/// units of 32 bytes took a shift and an add). Against 32-byte units (`scripts/paired_passes.py`,
/// two builds, 4 rounds of 8 pairs, AMD Zen 3): primary rays +0 to +5 %, shadow rays +1 to +5 %
/// (bunny, terrain, the 1,728-triangle blob), bounce rays 0.94 to 1.01 (within the rounds'
/// spread). References have 31 bits, so an arena holds up to [`MAX_ARENA_BYTES`].
pub const UNIT: usize = 8;

/// The most bytes an [`Arena`] holds (16 GiB: about 270 million triangles in full leaves).
pub const MAX_ARENA_BYTES: usize = UNIT << 31;

/// A bottom level's nodes and leaf blocks in one allocation, depth first, each node followed
/// by its leaf children's blocks and then its node children's subtrees, each kind in order of
/// the child's box area, largest first: a node and the leaves a ray tests after it share
/// memory pages and lie where the hardware's stream prefetch looks next, and the lines
/// requested ahead of a walk ([`crate::traverse::walk::AHEAD`], [`WideNode::after`]) hold the
/// leaves most likely hit (by area, against slot order: bounce and shadow rays +3 to +7 % on
/// the 48 instanced blobs, +0 to +3 % on the terrain and the blob). References are offsets in
/// units of [`UNIT`] bytes (a leaf's with [`LEAF_BIT`]), so a reference of either kind is an
/// address ([`Nodes::address`]); nodes start on a cache line. Measured against separate node
/// and block arrays (the same walk, `profile_set`, 5 alternating rounds): single rays on the
/// meshes larger than the caches +1 to +6 %, instanced shadow rays +10 %; and with a node's
/// leaf lines requested when the node is ([`WideNode::after`]), a further +4 to +20 %. A large
/// arena lies on 2 MiB pages where the operating system offers them (Linux's transparent huge
/// pages), so that its scattered reads seldom miss the address translation cache as well.
#[derive(Clone, Default)]
pub struct Arena {
    lines: Lines,
    nodes: usize,
    blocks: usize,
}

/// A bottom level with nodes and leaf blocks in separate arrays: the form a build makes and
/// a GPU tracer uploads ([`Arena::new`], [`Arena::indexed`]).
#[derive(Clone, Debug)]
pub struct Indexed {
    /// The wide nodes, root first; node references are indices here.
    pub nodes: Vec<WideNode>,
    /// The leaf blocks; leaf references are [`LEAF_BIT`] and an index here.
    pub blocks: Vec<TriBlock>,
    /// The root's reference: node 0, a leaf (a mesh of at most four triangles) or [`EMPTY`].
    pub root: u32,
}

impl Arena {
    /// The arena of the hierarchy `tree`, and its root's reference in it, or
    /// [`BuildError::TooMany`] when it would need more than [`MAX_ARENA_BYTES`].
    pub fn new(tree: &Indexed) -> Result<(Arena, u32), BuildError> {
        let Indexed { nodes, blocks, root } = tree;
        let (nodes, blocks, root) = (nodes.as_slice(), blocks.as_slice(), *root);
        // First the size, then the bytes, written in place: no second copy of a large mesh.
        fn size(nodes: &[WideNode], r: u32, at: &mut usize) {
            if r & LEAF_BIT != 0 {
                *at += (r != EMPTY) as usize * BLOCK_BYTES;
                return;
            }
            *at = at.next_multiple_of(64) + NODE_BYTES;
            let n = &nodes[r as usize];
            *at += n.children.iter().filter(|&&c| c & LEAF_BIT != 0 && c != EMPTY).count() * BLOCK_BYTES;
            // In `put`'s order: each subtree starts on a cache line, so the padding between
            // them depends on the order.
            for i in by_area(n, false) {
                size(nodes, n.children[i], at);
            }
        }
        fn put(nodes: &[WideNode], blocks: &[TriBlock], r: u32, out: &mut Arena, at: &mut usize) -> u32 {
            if r == EMPTY {
                return EMPTY;
            }
            if r & LEAF_BIT != 0 {
                let here = *at;
                out.write(here, &blocks[(r & !LEAF_BIT) as usize]);
                out.blocks += 1;
                *at += BLOCK_BYTES;
                return LEAF_BIT | (here / UNIT) as u32;
            }
            let here = at.next_multiple_of(64);
            *at = here + NODE_BYTES;
            out.nodes += 1;
            let mut node = nodes[r as usize];
            // Leaf blocks first, then node children, each largest first: the leaf lines a walk
            // requests ahead hold the leaves a ray most likely hits, and the subtree a ray
            // most likely enters follows its parent's leaves.
            for i in by_area(&node, true) {
                node.children[i] = put(nodes, blocks, node.children[i], out, at);
            }
            for i in by_area(&node, false) {
                let c = node.children[i];
                let leaves = nodes[c as usize].children.iter().filter(|&&l| l & LEAF_BIT != 0 && l != EMPTY);
                node.after[i] = (leaves.count() * BLOCK_BYTES).div_ceil(64) as u32;
                node.children[i] = put(nodes, blocks, c, out, at);
            }
            out.write(here, &node);
            (here / UNIT) as u32
        }
        /// The slots of `node`'s leaf children (or node children), by their boxes' surface
        /// area, largest first (a ray in a random direction hits a convex box with a chance in
        /// proportion to its area); the slot order among equals.
        fn by_area(node: &WideNode, leaves: bool) -> impl Iterator<Item = usize> {
            let mut slots = [0usize; WIDTH];
            let mut n = 0;
            for (i, &c) in node.children.iter().enumerate() {
                if (c & LEAF_BIT != 0) == leaves && c != EMPTY {
                    slots[n] = i;
                    n += 1;
                }
            }
            let area = |i: usize| node.child_bounds(i).half_area();
            slots[..n].sort_by(|&a, &b| area(b).total_cmp(&area(a)));
            slots.into_iter().take(n)
        }
        let mut bytes = 0;
        if root != EMPTY {
            size(nodes, root, &mut bytes);
        }
        fits(bytes)?;
        let mut arena = Arena { lines: Lines::zeroed(bytes.div_ceil(64)), nodes: 0, blocks: 0 };
        let mut at = 0;
        let root = put(nodes, blocks, root, &mut arena, &mut at);
        debug_assert_eq!(at, bytes);
        Ok((arena, root))
    }

    /// Copies `x` to byte `at` (within the storage; a multiple of `x`'s alignment).
    fn write<T: Copy>(&mut self, at: usize, x: &T) {
        let size = std::mem::size_of::<T>();
        assert!(at.is_multiple_of(std::mem::align_of::<T>()) && at + size <= self.lines.len() * 64);
        // SAFETY: in bounds and aligned (checked above); `T` is plain data (`Copy`, no padding
        // read back as anything but bytes of the same type).
        unsafe { std::ptr::write((self.lines.as_mut_ptr() as *mut u8).add(at) as *mut T, *x) }
    }

    /// The leaf block with reference `r` (with or without [`LEAF_BIT`]).
    ///
    /// # Safety
    /// `r` is a leaf reference of this arena's hierarchy.
    #[inline(always)]
    pub unsafe fn block(&self, r: u32) -> &TriBlock {
        let at = ((r & !LEAF_BIT) as usize) * UNIT;
        debug_assert!(at + BLOCK_BYTES <= self.lines.len() * 64);
        &*((self.lines.as_ptr() as *const u8).add(at) as *const TriBlock)
    }

    /// Wide nodes.
    pub fn node_count(&self) -> usize {
        self.nodes
    }

    /// Leaf blocks.
    pub fn block_count(&self) -> usize {
        self.blocks
    }

    /// Bytes of storage (nodes, blocks and the padding that keeps nodes on cache lines).
    pub fn bytes(&self) -> usize {
        self.lines.len() * 64
    }

    /// The hierarchy from `root` with nodes and blocks in separate arrays, in the arena's
    /// order (the root is node 0), its nodes' [`WideNode::after`] cleared.
    pub fn indexed(&self, root: u32) -> Indexed {
        fn take(arena: &Arena, r: u32, nodes: &mut Vec<WideNode>, blocks: &mut Vec<TriBlock>) -> u32 {
            if r == EMPTY {
                return EMPTY;
            }
            if r & LEAF_BIT != 0 {
                blocks.push(*arena.block_checked(r));
                return LEAF_BIT | (blocks.len() - 1) as u32;
            }
            let index = nodes.len();
            nodes.push(WideNode::EMPTY);
            let mut node = *arena.get(r);
            node.after = [0; WIDTH];
            for c in node.children.iter_mut().filter(|c| **c & LEAF_BIT != 0) {
                *c = take(arena, *c, nodes, blocks);
            }
            for c in node.children.iter_mut().filter(|c| **c & LEAF_BIT == 0) {
                *c = take(arena, *c, nodes, blocks);
            }
            nodes[index] = node;
            index as u32
        }
        let (mut nodes, mut blocks) = (Vec::with_capacity(self.nodes), Vec::with_capacity(self.blocks));
        let root = take(self, root, &mut nodes, &mut blocks);
        Indexed { nodes, blocks, root }
    }

    /// [`Arena::block`], checked: panics on a reference outside the storage or misaligned.
    fn block_checked(&self, r: u32) -> &TriBlock {
        let at = ((r & !LEAF_BIT) as usize) * UNIT;
        assert!(at + BLOCK_BYTES <= self.bytes(), "block reference {r:#x} outside the arena");
        // SAFETY: in bounds; every unit offset is aligned for a block (16 bytes).
        unsafe { self.block(r) }
    }
}

impl std::fmt::Debug for Arena {
    /// The counts, not the bytes (a large mesh's arena is hundreds of megabytes).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Arena")
            .field("nodes", &self.nodes)
            .field("blocks", &self.blocks)
            .field("bytes", &self.bytes())
            .finish()
    }
}

impl Nodes for Arena {
    #[inline(always)]
    unsafe fn node(&self, r: u32) -> &WideNode {
        let at = (r as usize) * UNIT;
        debug_assert!(at.is_multiple_of(64) && at + NODE_BYTES <= self.lines.len() * 64);
        &*((self.lines.as_ptr() as *const u8).add(at) as *const WideNode)
    }

    fn get(&self, r: u32) -> &WideNode {
        let at = (r as usize) * UNIT;
        assert!(
            at.is_multiple_of(64) && at + NODE_BYTES <= self.bytes(),
            "node reference {r:#x} outside the arena"
        );
        // SAFETY: in bounds and on a cache line (checked above).
        unsafe { self.node(r) }
    }

    const SHARED: bool = true;

    #[inline(always)]
    fn address(&self, r: u32) -> *const u8 {
        (self.lines.as_ptr() as *const u8).wrapping_add((r as usize) * UNIT)
    }
}

/// Whether an arena of `bytes` bytes can be addressed: every offset in [`UNIT`]s below
/// [`LEAF_BIT`].
fn fits(bytes: usize) -> Result<(), BuildError> {
    if bytes >= MAX_ARENA_BYTES {
        return Err(BuildError::TooMany {
            what: "bytes of a mesh's hierarchy",
            count: bytes,
            limit: MAX_ARENA_BYTES - 1,
        });
    }
    Ok(())
}

/// Bytes of a [`WideNode`].
pub(crate) const NODE_BYTES: usize = std::mem::size_of::<WideNode>();

/// Bytes of a [`TriBlock`] (a multiple of [`UNIT`], so blocks and nodes share the units).
const BLOCK_BYTES: usize = std::mem::size_of::<TriBlock>();

const _: () = assert!(BLOCK_BYTES.is_multiple_of(UNIT) && NODE_BYTES.is_multiple_of(64));

#[cfg(test)]
mod tests {
    use super::*;

    /// In an arena every reference, node or leaf, is the address of what it refers to (what
    /// [`Nodes::SHARED`] promises a walk that requests a child's lines by address).
    #[test]
    fn an_arenas_references_are_addresses() {
        let tris: Vec<[glam::Vec3; 3]> = (0..200)
            .map(|i| {
                let p = glam::Vec3::new((i % 17) as f32, (i / 17) as f32, (i % 5) as f32 * 0.3);
                [p, p + glam::Vec3::X, p + glam::Vec3::Y]
            })
            .collect();
        let blas = crate::blas::Blas::from_triangles(&tris).unwrap();
        let arena = &blas.arena;
        let (mut todo, mut seen) = (vec![blas.root], (0, 0));
        while let Some(r) = todo.pop() {
            let n = arena.get(r);
            assert_eq!(arena.address(r), n as *const WideNode as *const u8);
            seen.0 += 1;
            for &c in n.children.iter().filter(|&&c| c != EMPTY) {
                if c & LEAF_BIT == 0 {
                    todo.push(c);
                } else {
                    // SAFETY: a leaf reference of this arena's hierarchy.
                    let b = unsafe { arena.block(c) };
                    assert_eq!(arena.address(c & !LEAF_BIT), b as *const TriBlock as *const u8);
                    seen.1 += 1;
                }
            }
        }
        assert!(seen.0 > 1 && seen.1 > 8, "{seen:?}");
    }

    #[test]
    fn an_arena_past_its_references_is_an_error_not_a_panic() {
        assert_eq!(fits(MAX_ARENA_BYTES - 64), Ok(()));
        let err = fits(MAX_ARENA_BYTES).unwrap_err();
        assert_eq!(
            err,
            BuildError::TooMany {
                what: "bytes of a mesh's hierarchy",
                count: MAX_ARENA_BYTES,
                limit: MAX_ARENA_BYTES - 1
            }
        );
        // The largest offset in units of an arena that fits stays below the leaf bit.
        assert!((MAX_ARENA_BYTES - 1) / UNIT < LEAF_BIT as usize);
        assert!(err.to_string().contains("17179869184 bytes of a mesh's hierarchy"), "{err}");
    }
}
