//! The traversal loop, written once for every kernel and both levels.
//!
//! Closest hit: at a node the kernel tests all eight child boxes; one hit child is entered
//! directly, two are ordered by entry distance (the farther pushed), more are pushed and sorted
//! so the nearest is on top, and the nearest is entered. A leaf may shorten the ray (`t_max`);
//! popped entries farther than the shortened ray are dropped. Any hit: the same without
//! ordering, stopping at the first accepted hit. Every hit child (a node, or a leaf's data) is
//! prefetched as soon as it is known: a lone one so that its reference line (read after its
//! box test) comes with its box rows; where there are two or more, before the closest walk
//! compares distances, so that the child entered next is on its way even when the comparison's
//! branch is mispredicted, and the pushed ones while the walk descends. A node child is
//! requested with the leaf blocks that follow it in an arena (up to [`AFTER`] lines, as its
//! parent records, [`crate::node::WideNode::after`]): most of a walk's time on a large mesh is
//! waiting for memory, and those blocks are the ones it tests next.
//!
//! A ray whose every `1/dir` is finite takes the kernel's [`Backend::node_tree`], whose
//! chain of dependent operations is shorter; the walk is compiled once for each form.
//!
//! The stack is a fixed array: each level of a path leaves at most seven entries, and the
//! builder bounds paths to [`MAX_DEPTH`] levels.

use crate::build::binned::MAX_DEPTH;
use crate::node::{Nodes, WideNode, EMPTY, LEAF_BIT, WIDTH};
use crate::traverse::backend::{prefetch, prefetch_lines, Backend, IZE};
use std::mem::MaybeUninit;

/// Stack entries a walk can need.
pub const STACK: usize = (WIDTH - 1) * MAX_DEPTH + 1;

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

#[derive(Clone, Copy)]
struct Entry {
    node: u32,
    dist: f32,
}

/// Lines after a node, at most, requested with it ([`WideNode::after`]).
pub const AFTER: u32 = 8;

/// Starts loading child `slot` of `node`: a node's box rows and references and the leaf blocks
/// that follow it in an arena (up to [`AFTER`] lines), or what the leaves say a leaf needs, so
/// that the walk need not wait when it gets there.
#[inline(always)]
unsafe fn fetch<N: Nodes + ?Sized, L: Leaves>(nodes: &N, leaves: &L, node: &WideNode, slot: usize) {
    let child = *node.children.get_unchecked(slot);
    if child & LEAF_BIT == 0 {
        prefetch_node(nodes.node(child), *node.after.get_unchecked(slot));
    } else {
        leaves.fetch(child & !LEAF_BIT);
    }
}

/// Starts loading node `n` and the first `after` lines that follow it (at most [`AFTER`]): its
/// leaf blocks in an arena ([`WideNode::after`]).
#[inline(always)]
pub(crate) fn prefetch_node(n: &WideNode, after: u32) {
    prefetch(n);
    prefetch_lines((n as *const WideNode).wrapping_add(1) as *const u8, after.min(AFTER) as usize);
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
                    let (near, far) = if dist[i1] < dist[i0] { (i1, i0) } else { (i0, i1) };
                    debug_assert!(sp < STACK);
                    stack.get_unchecked_mut(sp).write(Entry { node: node.children[far], dist: dist[far] });
                    sp += 1;
                    cur = node.children[near];
                    continue 'walk;
                }
                // Three or more: push all, then sort them so that the nearest is on top (and,
                // at equal distances, the lowest slot).
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
                for k in base + 1..sp {
                    let x = stack.get_unchecked(k).assume_init();
                    let mut j = k;
                    while j > base && stack.get_unchecked(j - 1).assume_init().dist <= x.dist {
                        let y = stack.get_unchecked(j - 1).assume_init();
                        stack.get_unchecked_mut(j).write(y);
                        j -= 1;
                    }
                    stack.get_unchecked_mut(j).write(x);
                }
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
    let mut stack = [const { MaybeUninit::<u32>::uninit() }; STACK];
    let mut sp = 0usize;
    let mut cur = root;
    loop {
        if cur & LEAF_BIT == 0 {
            let node = nodes.node(cur);
            let (mut mask, _) = if TREE { B::node_tree(p, node, t_max) } else { B::node(p, node, t_max) };
            if mask != 0 {
                let first = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    fetch(nodes, leaves, node, i);
                    debug_assert!(sp < STACK);
                    stack.get_unchecked_mut(sp).write(node.children[i]);
                    sp += 1;
                }
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
