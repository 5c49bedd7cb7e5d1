//! The portable kernel: every lane of the vector kernel, one after another, with the same
//! operations in the same order (so the same bits).

use crate::node::{TriBlock, WideNode, BLOCK, WIDTH};
use crate::traverse::backend::{max_ps, min_ps, Backend, BlockHits, RayQuery, IZE};
use crate::triangle::intersect;

/// The scalar kernel.
#[derive(Clone, Copy, Debug)]
pub struct Scalar;

impl Backend for Scalar {
    type Prepared = RayQuery;

    #[inline(always)]
    unsafe fn prepare(q: &RayQuery) -> RayQuery {
        *q
    }

    #[inline(always)]
    unsafe fn node(q: &RayQuery, node: &WideNode, t_max: f32) -> (u32, [f32; 8]) {
        let mut mask = 0;
        let mut dist = [0.0; WIDTH];
        for (i, d) in dist.iter_mut().enumerate() {
            let near = |a: usize| (node.bounds[q.near[a]][i] - q.org[a]) * q.inv[a];
            let far = |a: usize| (node.bounds[q.far[a]][i] - q.org[a]) * q.inv_far[a];
            let near = max_ps(near(0), max_ps(near(1), max_ps(near(2), q.t_min)));
            let far = min_ps(far(0), min_ps(far(1), min_ps(far(2), t_max * IZE)));
            mask |= ((near <= far) as u32) << i;
            *d = near;
        }
        (mask, dist)
    }

    #[inline(always)]
    unsafe fn block(q: &RayQuery, block: &TriBlock, t_max: f32) -> BlockHits {
        let mut hits = BlockHits::default();
        for lane in 0..BLOCK {
            let [v0, v1, v2] = block.vertices(lane);
            if let Some(h) = intersect(&q.tri, v0, v1, v2, q.t_min, t_max) {
                hits.mask |= 1 << lane;
                hits.t[lane] = h.t;
                hits.u[lane] = h.u;
                hits.v[lane] = h.v;
            }
        }
        hits
    }
}
