//! The traversal loop, written once for every kernel and both levels.
//!
//! Closest hit: at a node the kernel tests all eight child boxes; one hit child is entered
//! directly, two are ordered by entry distance (the farther pushed), more are pushed and sorted
//! so the nearest is on top, and the nearest is entered. Neither ordering branches on the
//! distances, which for rays in all directions mispredicts: two children by the minimum and
//! maximum of their stack entries read as keys (against a branch, `scripts/paired_passes.py`,
//! AMD Zen 3: the blob's primary / bounce rays +2.0 / +4.0 %, 8 rounds of 20 pairs, the
//! instances' bounce rays +3.2 %), more by a sorting network of conditional moves (against an
//! insertion sort's branches: bounce rays +1 to +4 % on the blob, +3 % on the 48 blobs, +6 to
//! +12 % on the terrain). A leaf may shorten the ray (`t_max`); popped entries farther than
//! the shortened ray are dropped. Any hit: the same without ordering, stopping at the first
//! accepted hit, and with the node on top of the stack tested together with the node entered
//! (their hit children pushed, its own below the entered node's): the two tests are
//! independent, so their loads and chains of operations overlap, where one after the other
//! each waited for its own. Against testing them apart (`scripts/paired_passes.py`, AMD Zen 3,
//! 10 rounds of 20 pairs), shadow rays: the blob +2.8 %, the 1,728-triangle blob +4.9 %, the
//! 3.3M-triangle blobs +4.9 %, the instances +3.4 %, the terrain +0.4 % (+3.6 % in 8 rounds of
//! 16). The closest walk does not pair: there a node tested ahead is wasted wherever a hit in
//! the entered subtree would have dropped it (the blob's primary rays 0.84–0.97 in six forms,
//! its bounce rays, which mostly leave the mesh without a hit, 0.96–1.02; BENCHMARKS.md,
//! Round 14). Every hit child (a node, or a leaf's data) is prefetched as soon as it is
//! known: a lone one so that its reference line (read after its box test) comes with its box
//! rows; where there are two or more, all of them before the nearest is known, and the pushed
//! ones load while the walk descends. A node child is requested with the [`AHEAD`] lines that
//! follow it, in an arena its first leaf blocks: most of a walk's time on a large mesh is
//! waiting for memory, and those blocks are the ones it tests next.
//!
//! A ray whose every `1/dir` is finite takes the kernel's [`Backend::node_tree`], whose
//! chain of dependent operations is shorter; the walk is compiled once for each form.
//!
//! The stack is a fixed array: each level of a path leaves at most seven entries, and the
//! builder bounds paths to [`MAX_DEPTH`] levels.

use crate::build::binned::MAX_DEPTH;
use crate::node::{Nodes, WideNode, EMPTY, LEAF_BIT, NODE_BYTES, WIDTH};
use crate::traverse::backend::{prefetch, prefetch_lines, Backend, IZE};
use std::mem::MaybeUninit;

/// Stack entries a walk can need.
pub const STACK: usize = (WIDTH - 1) * MAX_DEPTH + 1;

/// Stack entries the any-hit walk can need, as it pairs node tests ([`any`]): it pairs only
/// while it holds at most [`STACK`] entries, a paired step adds at most `2·WIDTH − 2` (the
/// paired node's hit children for its entry, the entered node's other hit children), and a
/// walk from any node then adds at most `WIDTH − 1` a level below it.
const PAIRED_STACK: usize = STACK + 2 * WIDTH - 2 + (WIDTH - 1) * MAX_DEPTH;

/// What a walk does at a leaf.
pub trait Leaves {
    /// Tests the leaf with payload `leaf` (its reference without [`LEAF_BIT`]) for a closer
    /// hit, lowering `*t_max` to it.
    ///
    /// # Safety
    /// The CPU has the walk's kernel features.
    unsafe fn closest(&mut self, leaf: u32, t_max: &mut f32);

    /// Whether the leaf has any accepted hit before `t_max`.
    ///
    /// # Safety
    /// The CPU has the walk's kernel features.
    unsafe fn any(&mut self, leaf: u32, t_max: f32) -> bool;

    /// Starts loading the leaf with payload `leaf`, which the walk may visit next.
    #[inline(always)]
    fn fetch(&self, leaf: u32) {
        let _ = leaf;
    }
}

/// A closest walk's stack entry: a node or leaf reference and its entry distance. Its eight
/// bytes read as a `u64` are a key that orders as the distance, then the reference ([`sort`]):
/// the distance is the high half.
#[cfg(target_endian = "little")]
#[derive(Clone, Copy)]
#[repr(C, align(8))]
struct Entry {
    node: u32,
    dist: f32,
}

/// As above, for a big-endian target.
#[cfg(target_endian = "big")]
#[derive(Clone, Copy)]
#[repr(C, align(8))]
struct Entry {
    dist: f32,
    node: u32,
}

/// Lines after a node, at most, that a packet walk requests with it ([`WideNode::after`]).
pub const AFTER: u32 = 8;

/// A node's cache lines.
const NODE_LINES: usize = NODE_BYTES / 64;

/// Lines after a node that a single ray's walk requests with it, whatever the node's own leaf
/// blocks take ([`WideNode::after`]): in an arena they are its first leaf blocks and, where its
/// leaves take fewer lines, the start of its largest node child's subtree.
///
/// A fixed count needs neither the count's load nor a branch on it. The count-bounded
/// requests (up to [`AFTER`]) branched on each of them, and rays in all directions stop at a
/// different line from node to node. Against them (`scripts/paired_passes.py`, 5 or 6
/// rounds of 12 to 16 pairs, AMD Zen 3), primary / bounce / shadow rays:
/// - 2 lines: the blob (69k triangles, a 3.8 MB hierarchy) +2 to +3 %, but the 1M-triangle
///   terrain 0.95–0.99 and the instances 0.95–0.96;
/// - 4 lines: the blob 0.99 / 1.04 / 1.03, the terrain and the instances 0.96–1.01;
/// - 6 lines: the blob 1.00–1.02 / 1.02–1.04 / 1.00–1.02, the terrain 0.98–1.01, the instances
///   0.98–1.03, the 3.3M-triangle blobs 0.965–0.971;
/// - 8 lines: the blob 1.00 / 1.01 / 1.01, the terrain 0.97–0.98.
pub const AHEAD: usize = 6;

/// Starts loading child `slot` of `node`: a node's box rows and references and the [`AHEAD`]
/// lines that follow it (in an arena its first leaf blocks), or what the leaves say a leaf
/// needs, so that the walk need not wait when it gets there.
///
/// Where the store holds leaves too ([`Nodes::SHARED`], an arena), the same lines are requested
/// from the child's address whatever its kind, without a branch on it (which for rays in all
/// directions mispredicts): for a leaf, its block and the blocks after it, its parent's next
/// leaves by area. Against the branch (`scripts/paired_passes.py`, AMD Zen 3, 6 rounds of 16
/// pairs): bounce rays +2 % on the blob and the terrain, +3 % on the instances, +5 % on the
/// 3.3M-triangle blobs; primary and shadow rays 0.99–1.04 (8 rounds of 16; a first 6 rounds
/// read the blob's 0.992 / 0.972).
#[inline(always)]
unsafe fn fetch<N: Nodes + ?Sized, L: Leaves>(nodes: &N, leaves: &L, node: &WideNode, slot: usize) {
    let child = *node.children.get_unchecked(slot);
    if N::SHARED || child & LEAF_BIT == 0 {
        prefetch_lines(nodes.address(child & !LEAF_BIT), NODE_LINES + AHEAD);
    } else {
        leaves.fetch(child & !LEAF_BIT);
    }
}

/// Starts loading node `n` and the first `after` lines that follow it (at most [`AFTER`]): its
/// leaf blocks in an arena ([`WideNode::after`]). For packet walks, which test a node once for
/// many rays.
#[inline(always)]
pub(crate) fn prefetch_node(n: &WideNode, after: u32) {
    prefetch(n);
    prefetch_lines((n as *const WideNode).wrapping_add(1) as *const u8, after.min(AFTER) as usize);
}

/// Pushes the references of `node`'s children in `mask` on the any-hit walk's stack `stack`
/// from `sp` up, requesting each one's lines; returns the new top.
#[inline(always)]
unsafe fn push_hits<N: Nodes + ?Sized, L: Leaves>(
    nodes: &N,
    leaves: &L,
    stack: &mut [MaybeUninit<u32>; PAIRED_STACK],
    mut sp: usize,
    node: &WideNode,
    mut mask: u32,
) -> usize {
    while mask != 0 {
        let i = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        fetch(nodes, leaves, node, i);
        debug_assert!(sp < PAIRED_STACK);
        stack.get_unchecked_mut(sp).write(*node.children.get_unchecked(i));
        sp += 1;
    }
    sp
}

/// Child `i`'s stack entry read as a key ([`Entry`]): its distance's bits above its
/// reference.
#[inline(always)]
unsafe fn key(node: &WideNode, dist: &[f32; WIDTH], i: usize) -> u64 {
    (u64::from(dist.get_unchecked(i).to_bits()) << 32) | u64::from(*node.children.get_unchecked(i))
}

/// Sorting networks for 3 to 8 entries (pairs of positions to compare and exchange), the
/// fewest comparisons known for each count.
#[rustfmt::skip]
const NETWORKS: [&[(usize, usize)]; 6] = [
    &[(0, 1), (1, 2), (0, 1)],
    &[(0, 1), (2, 3), (0, 2), (1, 3), (1, 2)],
    &[(0, 1), (3, 4), (2, 4), (2, 3), (0, 3), (0, 2), (1, 4), (1, 3), (1, 2)],
    &[(1, 2), (4, 5), (0, 2), (3, 5), (0, 1), (3, 4), (2, 5), (0, 3), (1, 4), (2, 4), (1, 3), (2, 3)],
    &[
        (1, 2), (3, 4), (5, 6), (0, 2), (3, 5), (4, 6), (0, 1), (4, 5),
        (2, 6), (0, 4), (1, 5), (0, 3), (2, 5), (1, 3), (2, 4), (2, 3),
    ],
    &[
        (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7), (0, 1), (2, 3),
        (4, 5), (6, 7), (2, 4), (3, 5), (1, 4), (3, 6), (1, 2), (3, 4), (5, 6),
    ],
];

/// Sorts `n` (3 to 8) stack entries at `s`, read as keys (a distance's bits above its
/// reference: distances are never negative, so the keys order as the distances do), so that
/// the nearest is on top (last), by a sorting network: conditional moves, no branch on the
/// data, which for rays in all directions mispredicts.
#[inline(always)]
unsafe fn sort(s: *mut u64, n: usize) {
    macro_rules! network {
        ($k:expr) => {
            for &(i, j) in NETWORKS[$k - 3] {
                let (x, y) = (*s.add(i), *s.add(j));
                *s.add(i) = x.max(y);
                *s.add(j) = x.min(y);
            }
        };
    }
    match n {
        3 => network!(3),
        4 => network!(4),
        5 => network!(5),
        6 => network!(6),
        7 => network!(7),
        _ => network!(8),
    }
}

/// Walks the hierarchy `nodes` from `root` for the closest hit.
///
/// # Safety
/// The CPU has `B`'s features; `nodes` and `root` come from one build (child references in
/// range, depth within [`MAX_DEPTH`]).
#[inline(always)]
pub unsafe fn closest<B: Backend, N: Nodes + ?Sized, L: Leaves>(
    nodes: &N,
    root: u32,
    p: &B::Prepared,
    leaves: &mut L,
    t_max: &mut f32,
) {
    if B::tree_safe(p) {
        closest_with::<B, N, L, true>(nodes, root, p, leaves, t_max)
    } else {
        closest_with::<B, N, L, false>(nodes, root, p, leaves, t_max)
    }
}

/// [`closest`] with [`Backend::node_tree`] where `TREE`, else [`Backend::node`].
#[inline(always)]
unsafe fn closest_with<B: Backend, N: Nodes + ?Sized, L: Leaves, const TREE: bool>(
    nodes: &N,
    root: u32,
    p: &B::Prepared,
    leaves: &mut L,
    t_max: &mut f32,
) {
    if root == EMPTY {
        return;
    }
    let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
    let mut sp = 0usize;
    let mut cur = root;
    'walk: loop {
        if cur & LEAF_BIT == 0 {
            let node = nodes.node(cur);
            let (mut mask, dist) =
                if TREE { B::node_tree(p, node, *t_max) } else { B::node(p, node, *t_max) };
            if mask != 0 {
                let i0 = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if mask == 0 {
                    cur = node.children[i0];
                    // All of the child's lines at once: the test reads its box rows, then its
                    // references (another line), which would otherwise wait for the test.
                    fetch(nodes, leaves, node, i0);
                    continue 'walk;
                }
                let i1 = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                // Both are requested before the order is known, so that a mispredicted
                // comparison does not delay the loads of the child entered.
                fetch(nodes, leaves, node, i0);
                fetch(nodes, leaves, node, i1);
                if mask == 0 {
                    // The nearer by their keys' minimum, without a branch on the distances:
                    // for rays in all directions it mispredicts half the time.
                    let (k0, k1) = (key(node, &dist, i0), key(node, &dist, i1));
                    debug_assert!(sp < STACK);
                    *(stack.as_mut_ptr().add(sp) as *mut u64) = k0.max(k1);
                    sp += 1;
                    cur = k0.min(k1) as u32;
                    continue 'walk;
                }
                // Three or more: push all, then sort them so that the nearest is on top (at
                // equal distances, the lower reference), without branching on the distances.
                let base = sp;
                for i in [i0, i1] {
                    stack.get_unchecked_mut(sp).write(Entry { node: node.children[i], dist: dist[i] });
                    sp += 1;
                }
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    fetch(nodes, leaves, node, i);
                    stack.get_unchecked_mut(sp).write(Entry { node: node.children[i], dist: dist[i] });
                    sp += 1;
                }
                debug_assert!(sp <= STACK);
                sort(stack.as_mut_ptr().add(base) as *mut u64, sp - base);
                sp -= 1;
                cur = stack.get_unchecked(sp).assume_init().node;
                continue 'walk;
            }
        } else {
            leaves.closest(cur & !LEAF_BIT, t_max);
        }
        loop {
            if sp == 0 {
                break 'walk;
            }
            sp -= 1;
            let e = stack.get_unchecked(sp).assume_init();
            if e.dist <= *t_max * IZE {
                cur = e.node;
                continue 'walk;
            }
        }
    }
}

/// Walks the hierarchy for any accepted hit; returns whether there is one.
///
/// # Safety
/// As for [`closest`].
#[inline(always)]
pub unsafe fn any<B: Backend, N: Nodes + ?Sized, L: Leaves>(
    nodes: &N,
    root: u32,
    p: &B::Prepared,
    leaves: &mut L,
    t_max: f32,
) -> bool {
    if B::tree_safe(p) {
        any_with::<B, N, L, true>(nodes, root, p, leaves, t_max)
    } else {
        any_with::<B, N, L, false>(nodes, root, p, leaves, t_max)
    }
}

/// [`any`] with [`Backend::node_tree`] where `TREE`, else [`Backend::node`].
#[inline(always)]
unsafe fn any_with<B: Backend, N: Nodes + ?Sized, L: Leaves, const TREE: bool>(
    nodes: &N,
    root: u32,
    p: &B::Prepared,
    leaves: &mut L,
    t_max: f32,
) -> bool {
    if root == EMPTY {
        return false;
    }
    let mut stack = [const { MaybeUninit::<u32>::uninit() }; PAIRED_STACK];
    let mut sp = 0usize;
    let mut cur = root;
    loop {
        if cur & LEAF_BIT == 0 {
            let node = nodes.node(cur);
            let (mask, _) = if TREE { B::node_tree(p, node, t_max) } else { B::node(p, node, t_max) };
            // The node on top of the stack, tested now rather than after this one's subtree:
            // the two tests do not depend on each other, so they overlap, and most of a
            // walk's time is waiting on one test's loads and its chain of operations.
            if sp != 0 && sp <= STACK {
                let top = stack.get_unchecked(sp - 1).assume_init();
                if top & LEAF_BIT == 0 {
                    let alt = nodes.node(top);
                    let (amask, _) = if TREE { B::node_tree(p, alt, t_max) } else { B::node(p, alt, t_max) };
                    sp = push_hits(nodes, leaves, &mut stack, sp - 1, alt, amask);
                }
            }
            if mask != 0 {
                let first = mask.trailing_zeros() as usize;
                sp = push_hits(nodes, leaves, &mut stack, sp, node, mask & (mask - 1));
                cur = node.children[first];
                fetch(nodes, leaves, node, first);
                continue;
            }
        } else if leaves.any(cur & !LEAF_BIT, t_max) {
            return true;
        }
        if sp == 0 {
            return false;
        }
        sp -= 1;
        cur = stack.get_unchecked(sp).assume_init();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every network sorts: by the 0-1 principle, a comparator network that sorts every
    /// sequence of zeros and ones sorts every sequence.
    #[test]
    fn networks_sort_every_sequence_of_zeros_and_ones() {
        for n in 3..=8 {
            for bits in 0u32..1 << n {
                let mut keys: Vec<u64> = (0..n).map(|i| u64::from((bits >> i) & 1)).collect();
                // SAFETY: `keys` holds `n` keys.
                unsafe { sort(keys.as_mut_ptr(), n) };
                assert!(keys.windows(2).all(|w| w[0] >= w[1]), "{n} keys {bits:#b}: {keys:?}");
            }
        }
    }

    /// A key written as a stack entry reads back as the entry it stands for (the two-child
    /// ordering pushes keys).
    #[test]
    fn keys_are_entries() {
        let mut node = WideNode::EMPTY;
        node.children = [7, 0, u32::MAX, 12345, 1 << 31, 3, 9, 11];
        let dist = [0.0f32, 1e-30, 0.5, 1.0, 3.5, 1e30, f32::INFINITY, 2.0];
        for i in 0..WIDTH {
            let mut slot = MaybeUninit::<Entry>::uninit();
            // SAFETY: `i < WIDTH`; `Entry` is 8 bytes, aligned to 8.
            let e = unsafe {
                *(slot.as_mut_ptr() as *mut u64) = key(&node, &dist, i);
                slot.assume_init()
            };
            assert_eq!((e.node, e.dist.to_bits()), (node.children[i], dist[i].to_bits()));
        }
    }

    /// An entry read as a key orders as its distance, then its reference (the layout `sort`
    /// relies on), for distances the node tests produce (never negative).
    #[test]
    fn keys_order_as_distances() {
        let key = |node: u32, dist: f32| {
            let e = Entry { node, dist };
            // SAFETY: `Entry` is two 4-byte fields, 8 bytes, aligned to 8.
            unsafe { *(&e as *const Entry as *const u64) }
        };
        let dists = [0.0f32, 1e-30, 0.5, 1.0, 3.5, 1e30, f32::INFINITY];
        for (i, &a) in dists.iter().enumerate() {
            for &b in &dists[i + 1..] {
                assert!(key(u32::MAX, a) < key(0, b), "{a} {b}");
            }
            assert!(key(1, a) < key(2, a));
        }
    }
}
