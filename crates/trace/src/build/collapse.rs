//! Collapsing a binary BVH into 8-wide nodes, the way Embree's wide builders do: a wide node
//! starts from a binary node's two children and repeatedly opens the child with the largest
//! surface area (the one most rays would enter) into its two children, until it has eight or
//! only leaves remain. Binary leaves stay leaves. Nodes are written depth-first, each node
//! before its children's subtrees, so a ray descending the nearest child reads nearby memory.

use crate::build::binned::{Bvh2, PrimRef};
use crate::node::{WideNode, EMPTY, WIDTH};

/// The wide nodes of `bvh` and the root's reference: [`EMPTY`] for no primitives, a leaf
/// reference when the whole hierarchy is one leaf (then there are no nodes), else node 0.
/// `make_leaf` turns a binary leaf's primitives into a leaf reference.
pub fn collapse(bvh: &Bvh2, make_leaf: &mut impl FnMut(&[PrimRef]) -> u32) -> (Vec<WideNode>, u32) {
    if bvh.refs.is_empty() {
        return (Vec::new(), EMPTY);
    }
    let root = &bvh.nodes[0];
    if root.is_leaf() {
        return (Vec::new(), make_leaf(&bvh.refs[root.prims()]));
    }
    let mut out = Vec::with_capacity(bvh.refs.len() / 8 + 1);
    let r = wide(bvh, 0, &mut out, make_leaf);
    (out, r)
}

fn wide(
    bvh: &Bvh2,
    slot: usize,
    out: &mut Vec<WideNode>,
    make_leaf: &mut impl FnMut(&[PrimRef]) -> u32,
) -> u32 {
    let index = out.len();
    out.push(WideNode::EMPTY);
    let top = &bvh.nodes[slot];
    let mut kids = [0usize; WIDTH];
    kids[0] = top.a as usize;
    kids[1] = top.b as usize;
    let mut count = 2;
    while count < WIDTH {
        let mut open = None;
        let mut largest = f32::NEG_INFINITY;
        for (i, &k) in kids[..count].iter().enumerate() {
            let n = &bvh.nodes[k];
            if !n.is_leaf() && n.bounds().half_area() > largest {
                largest = n.bounds().half_area();
                open = Some(i);
            }
        }
        let Some(i) = open else { break };
        let n = bvh.nodes[kids[i]];
        kids[i] = n.a as usize;
        kids[count] = n.b as usize;
        count += 1;
    }
    let mut node = WideNode::EMPTY;
    for (s, &k) in kids[..count].iter().enumerate() {
        let n = &bvh.nodes[k];
        let child = if n.is_leaf() { make_leaf(&bvh.refs[n.prims()]) } else { wide(bvh, k, out, make_leaf) };
        node.set(s, &n.bounds(), child);
    }
    out[index] = node;
    index as u32
}
