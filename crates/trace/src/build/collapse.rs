//! Collapsing a binary BVH into 8-wide nodes with the fewest node tests the surface area
//! heuristic expects.
//!
//! The binary build has decided the leaves; what remains is which binary nodes become wide
//! nodes. A ray that enters a wide node's box tests its eight children, so the heuristic's
//! cost of a wide tree is the sum of its wide nodes' areas (the leaves' part is the same for
//! every choice). A dynamic program over the binary tree (as Ylitie, Karras and Laine's wide
//! conversion, with the leaves fixed) finds, for every binary node and every `i ≤ 8`, the
//! cheapest way to stand for its subtree with at most `i` children of a wide node, and so the
//! cheapest tree.
//!
//! Against the greedy collapse Embree's wide builders use (a wide node opens its largest child
//! until it has eight), the same leaves sit under fewer, fuller nodes: the 69k-triangle blob's
//! 4,600 nodes become 3,537, the 1M-triangle terrain's 77,507 become 52,095, and their node
//! part of the SAH falls 3 %. Single rays (`scripts/paired_passes.py`, two builds, 3 rounds of
//! 8 pairs, AMD Zen 3), primary / bounce / shadow: terrain +1.6 / +9.3 / +3.5 %, the
//! 69k-triangle blob +0.7 / −0.4 / +2.5 %, the 1,728-triangle blob +4.6 to +5.2 %. The pass is
//! linear in the binary nodes (about 0.1 s of the terrain's build, one thread).
//!
//! Nodes are written depth-first, each node before its children's subtrees, so a ray
//! descending the nearest child reads nearby memory.

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
    let plan = Plan::new(bvh);
    let mut out = Vec::with_capacity(bvh.refs.len() / 8 + 1);
    let r = wide(bvh, &plan, 0, &mut out, make_leaf);
    (out, r)
}

/// The dynamic program's choices: per binary slot and per `i` in `1..=8`, how the slot's
/// subtree stands for itself with at most `i` children of a wide node at the least cost.
struct Plan {
    /// `split[slot][i − 1]`: 0 where the slot is one child (a leaf, or a wide node of its
    /// own), else `k`: its left child's subtree takes at most `k` children, its right one's
    /// `i − k`.
    split: Vec<[u8; WIDTH]>,
    /// Where the slot is a wide node: how its eight children are shared between its two
    /// binary children's subtrees (the left one takes at most this many).
    node: Vec<u8>,
}

impl Plan {
    fn new(bvh: &Bvh2) -> Plan {
        let len = bvh.nodes.len();
        let mut plan = Plan { split: vec![[0; WIDTH]; len], node: vec![0; len] };
        fill(bvh, 0, &mut plan.split, &mut plan.node);
        plan
    }

    /// Appends to `out[..*len]` the slots that stand for `slot`'s subtree with at most `i`
    /// children (`*len + i ≤ 8`).
    fn children(&self, bvh: &Bvh2, slot: usize, i: usize, out: &mut [usize; WIDTH], len: &mut usize) {
        let n = &bvh.nodes[slot];
        let k = if n.is_leaf() { 0 } else { self.split[slot][i - 1] as usize };
        if k == 0 {
            out[*len] = slot;
            *len += 1;
        } else {
            self.children(bvh, n.a as usize, k, out, len);
            self.children(bvh, n.b as usize, i - k, out, len);
        }
    }
}

/// Fills the plan of the subtree at slot `base`, whose slots are the slices' (the build lays
/// a subtree out in consecutive slots: the node, its left subtree, its right subtree), children
/// before their parent, and returns the subtree's least cost with at most `i` children
/// (`[i − 1]`). (The two subtrees of a large one filled in parallel took twice as long on two
/// cores: the pass is a stream through memory.)
fn fill(bvh: &Bvh2, base: usize, split: &mut [[u8; WIDTH]], node: &mut [u8]) -> [f32; WIDTH] {
    let n = &bvh.nodes[base];
    // A leaf costs the same in every choice (every choice keeps every leaf): zero.
    if n.is_leaf() {
        return [0.0; WIDTH];
    }
    let (a, b) = (n.a as usize - base, n.b as usize - base);
    debug_assert!(a == 1 && b > a && b < split.len());
    let (sl, sr) = split[1..].split_at_mut(b - 1);
    let (nl, nr) = node[1..].split_at_mut(b - 1);
    let (ca, cb) = (fill(bvh, base + a, sl, nl), fill(bvh, base + b, sr, nr));
    // The subtree as at most `i` children, shared between the two children's subtrees.
    let (mut shared, mut at) = ([f32::INFINITY; WIDTH], [0u8; WIDTH]);
    for i in 2..=WIDTH {
        for k in 1..i {
            let c = ca[k - 1] + cb[i - k - 1];
            if c < shared[i - 1] {
                (shared[i - 1], at[i - 1]) = (c, k as u8);
            }
        }
    }
    // As one child: a wide node of its own, tested by every ray that enters its box.
    let own = n.bounds().half_area() + shared[WIDTH - 1];
    let mut cost = [own; WIDTH];
    split[0][0] = 0;
    for i in 2..=WIDTH {
        (cost[i - 1], split[0][i - 1]) =
            if shared[i - 1] < own { (shared[i - 1], at[i - 1]) } else { (own, 0) };
    }
    node[0] = at[WIDTH - 1];
    cost
}

/// Writes the wide node at binary slot `slot` and, depth first, the wide nodes below it;
/// returns its index in `out`.
fn wide(
    bvh: &Bvh2,
    plan: &Plan,
    slot: usize,
    out: &mut Vec<WideNode>,
    make_leaf: &mut impl FnMut(&[PrimRef]) -> u32,
) -> u32 {
    let index = out.len();
    out.push(WideNode::EMPTY);
    let top = &bvh.nodes[slot];
    let k = plan.node[slot] as usize;
    let (mut kids, mut count) = ([0usize; WIDTH], 0);
    plan.children(bvh, top.a as usize, k, &mut kids, &mut count);
    plan.children(bvh, top.b as usize, WIDTH - k, &mut kids, &mut count);
    let mut node = WideNode::EMPTY;
    for (s, &k) in kids[..count].iter().enumerate() {
        let n = &bvh.nodes[k];
        let child =
            if n.is_leaf() { make_leaf(&bvh.refs[n.prims()]) } else { wide(bvh, plan, k, out, make_leaf) };
        node.set(s, &n.bounds(), child);
    }
    out[index] = node;
    index as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aabb::Aabb;
    use crate::build::binned::{build, SahParams};
    use crate::node::LEAF_BIT;
    use glam::Vec3;
    use proptest::prelude::*;

    /// The binary hierarchy of `boxes`, one primitive to a leaf (the most inner nodes).
    fn binary(boxes: &[([f32; 3], [f32; 3])]) -> Bvh2 {
        let refs = boxes
            .iter()
            .enumerate()
            .map(|(i, &(p, e))| {
                let (p, e) = (Vec3::from(p), Vec3::from(e));
                PrimRef::new(&Aabb::from_points(&[p, p + e]), i as u32)
            })
            .collect();
        build(refs, &SahParams { max_leaf: 1, block: 1, traversal_cost: 1.0 })
    }

    /// The sum of the wide nodes' areas of a collapsed tree, and the leaves it reaches.
    fn cost(nodes: &[WideNode], r: u32, area: f64, leaves: &mut Vec<u32>) -> f64 {
        if r & LEAF_BIT != 0 {
            leaves.push(r & !LEAF_BIT);
            return 0.0;
        }
        let n = &nodes[r as usize];
        let used: Vec<usize> = (0..WIDTH).filter(|&s| n.children[s] != EMPTY).collect();
        assert!(used.len() >= 2, "a wide node with {} children", used.len());
        area + used
            .iter()
            .map(|&s| cost(nodes, n.children[s], n.child_bounds(s).half_area() as f64, leaves))
            .sum::<f64>()
    }

    /// The least sum of wide-node areas over every choice of binary nodes to be wide nodes
    /// (the root always), each with at most eight children: by trying them all.
    fn cheapest(bvh: &Bvh2) -> f64 {
        let inner: Vec<usize> = {
            let (mut v, mut todo) = (Vec::new(), vec![0usize]);
            while let Some(s) = todo.pop() {
                let n = &bvh.nodes[s];
                if !n.is_leaf() {
                    v.push(s);
                    todo.extend([n.a as usize, n.b as usize]);
                }
            }
            v
        };
        // Children of `s` as a wide node, given which nodes are wide.
        fn frontier(bvh: &Bvh2, s: usize, wide: &dyn Fn(usize) -> bool) -> usize {
            let n = &bvh.nodes[s];
            let count = |c: usize| if bvh.nodes[c].is_leaf() || wide(c) { 1 } else { frontier(bvh, c, wide) };
            count(n.a as usize) + count(n.b as usize)
        }
        let mut best = f64::INFINITY;
        for mask in 0u32..1 << (inner.len() - 1) {
            // inner[0] is the root, always a wide node.
            let wide = |s: usize| {
                s == 0 || inner[1..].iter().position(|&x| x == s).is_some_and(|i| mask >> i & 1 != 0)
            };
            let chosen: Vec<usize> = inner.iter().copied().filter(|&s| wide(s)).collect();
            if chosen.iter().all(|&s| frontier(bvh, s, &wide) <= WIDTH) {
                best = best.min(chosen.iter().map(|&s| bvh.nodes[s].bounds().half_area() as f64).sum());
            }
        }
        best
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The collapse keeps every leaf once, gives no node more than eight children and
        /// costs what the cheapest choice found by trying every one costs.
        #[test]
        fn the_collapse_is_the_cheapest_wide_tree(
            boxes in prop::collection::vec(
                (prop::array::uniform3(-10.0f32..10.0), prop::array::uniform3(0.01f32..4.0)), 2..=13)
        ) {
            let bvh = binary(&boxes);
            let (nodes, root) = collapse(&bvh, &mut |leaf: &[PrimRef]| LEAF_BIT | leaf[0].index());
            let mut leaves = Vec::new();
            let ours = cost(&nodes, root, bvh.nodes[0].bounds().half_area() as f64, &mut leaves);
            leaves.sort_unstable();
            prop_assert_eq!(leaves, (0..boxes.len() as u32).collect::<Vec<_>>());
            let best = cheapest(&bvh);
            prop_assert!(ours <= best * (1.0 + 1e-5), "collapse {ours}, cheapest {best}");
        }
    }
}
