//! The packet walk: up to [`PACKET`] rays share one traversal of a bottom level.
//!
//! Every ray keeps its own interval, best hit and kernel form. At a node, each ray still
//! active runs the kernel's own single-ray node test ([`Backend::node`], so every box decision
//! is bit for bit the one the single-ray walk makes); a child is visited when any ray enters
//! it, and only by the rays that do. A stack entry carries the child, the rays that entered
//! it and the least entry distance among them; on popping, a ray stays only if that distance
//! is within its own (possibly shortened) interval, the single-ray walk's test with a lower
//! bound in place of the ray's own distance, so it can keep a ray the single walk would drop,
//! never drop one it would keep. Children are entered nearest first by that least distance, and
//! the ones pushed are prefetched (the walk waits on memory more than on arithmetic). At
//! a leaf each active ray runs the single-ray block test. When a node is reached by at most
//! [`SPARSE`] rays the packet has diverged: each of them walks the subtree alone with the
//! single-ray walk.
//!
//! Why the hits equal the single-ray query's: a ray tests a leaf's triangles only after its
//! own conservative box test accepted every node on the way (with an interval no shorter than
//! its final hit), so it reaches every leaf holding a hit it could return; and the closest
//! hit is chosen by [`Hit::precedes`], which does not depend on the order in which leaves are
//! tested. The any-hit walk retires a ray at its first hit.

use crate::blas::Blas;
use crate::hit::{Hit, Opaque};
use crate::node::{WideNode, EMPTY, LEAF_BIT};
use crate::ray::Ray;
use crate::traverse::backend::{prefetch, Backend, PacketNode, RayQuery, IZE, PACKET};
use crate::traverse::leaves::{no_hit, Triangles};
use crate::traverse::walk::{self, Leaves, STACK};
use glam::Vec3;
use std::mem::MaybeUninit;

/// A node reached by this many active rays or fewer is walked by each of them alone.
pub const SPARSE: u32 = 2;

#[derive(Clone, Copy)]
struct Entry {
    node: u32,
    rays: u32,
    dist: f32,
}

/// The packet's rays in kernel form, with their intervals.
struct Packet<B: Backend> {
    /// Every lane written by [`Packet::new`].
    prepared: [MaybeUninit<B::Prepared>; PACKET],
    t_max: [f32; PACKET],
    /// Bit `i` set for each ray that can hit something.
    valid: u32,
}

impl<B: Backend> Packet<B> {
    /// A packet of no rays, to be filled in place by [`Packet::load`].
    #[inline(always)]
    fn empty() -> Packet<B> {
        Packet {
            prepared: [const { MaybeUninit::uninit() }; PACKET],
            t_max: [f32::NEG_INFINITY; PACKET],
            valid: 0,
        }
    }

    /// Fills the packet with `rays` (written in place: the packet is several kilobytes).
    ///
    /// # Safety
    /// The CPU has `B`'s features.
    #[inline(always)]
    unsafe fn load(&mut self, rays: &[Ray]) {
        // Lanes without a valid ray get a harmless query and stay out of every mask.
        let idle = RayQuery::new(&Ray::new(Vec3::ZERO, Vec3::X)).expect("a valid ray");
        for i in 0..PACKET {
            let q = rays.get(i).and_then(RayQuery::new);
            if let Some(q) = &q {
                self.valid |= 1 << i;
                self.t_max[i] = q.t_max;
            }
            self.prepared[i].write(B::prepare(q.as_ref().unwrap_or(&idle)));
        }
    }

    #[inline(always)]
    unsafe fn ray(&self, i: usize) -> &B::Prepared {
        self.prepared.get_unchecked(i).assume_init_ref()
    }

    /// Which rays of `active` enter each child, and their least entry distance.
    #[inline(always)]
    unsafe fn node(&self, node: &WideNode, active: u32) -> PacketNode {
        // SAFETY: every lane is initialised, and `MaybeUninit<T>` has the layout of `T`.
        let prepared =
            &*(&self.prepared as *const [MaybeUninit<B::Prepared>; PACKET] as *const [B::Prepared; PACKET]);
        B::node_packet(prepared, node, active, &self.t_max)
    }

    /// The rays of `rays` whose interval still reaches distance `dist`.
    #[inline(always)]
    fn reaching(&self, rays: u32, dist: f32) -> u32 {
        let mut keep = 0;
        for (i, t) in self.t_max.iter().enumerate() {
            keep |= ((dist <= *t * IZE) as u32) << i;
        }
        rays & keep
    }
}

/// Starts loading the node or leaf block that `child` refers to.
#[inline(always)]
unsafe fn fetch(blas: &Blas, child: u32) {
    if child & LEAF_BIT == 0 {
        prefetch(blas.nodes.get_unchecked(child as usize));
    } else {
        prefetch(blas.blocks.get_unchecked((child & !LEAF_BIT) as usize));
    }
}

/// Ray `r`'s leaves: the bottom level's blocks, tested with its kernel form.
#[inline(always)]
unsafe fn triangles<'a, B: Backend>(
    blas: &'a Blas,
    p: &'a Packet<B>,
    r: usize,
    best: &'a mut Hit,
    filter: &'a mut Opaque,
) -> Triangles<'a, B, Opaque> {
    Triangles { blocks: &blas.blocks, prepared: p.ray(r), instance: Hit::NO_INSTANCE, best, filter }
}

/// The closest hit of each ray of `rays` (at most [`PACKET`]) in `blas`.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn closest<B: Backend>(blas: &Blas, rays: &[Ray]) -> [Option<Hit>; PACKET] {
    let mut p = Packet::<B>::empty();
    p.load(rays);
    let mut best = p.t_max.map(no_hit);
    let mut opaque = Opaque;
    if blas.root != EMPTY {
        let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
        let mut sp = 0usize;
        let (mut cur, mut active) = (blas.root, p.valid);
        'walk: loop {
            if active.count_ones() <= SPARSE {
                // Diverged: each remaining ray walks this subtree alone.
                while active != 0 {
                    let r = active.trailing_zeros() as usize;
                    active &= active - 1;
                    let mut t_max = p.t_max[r];
                    let mut leaves = triangles(blas, &p, r, &mut best[r], &mut opaque);
                    walk::closest::<B, _>(&blas.nodes, cur, p.ray(r), &mut leaves, &mut t_max);
                    p.t_max[r] = t_max;
                }
            } else if cur & LEAF_BIT == 0 {
                debug_assert!((cur as usize) < blas.nodes.len());
                let node = blas.nodes.get_unchecked(cur as usize);
                let n = p.node(node, active);
                let mut children = n.children;
                if children.count_ones() == 1 {
                    let c = children.trailing_zeros() as usize;
                    (cur, active) = (node.children[c], n.rays[c]);
                    continue 'walk;
                }
                let base = sp;
                while children != 0 {
                    let c = children.trailing_zeros() as usize;
                    children &= children - 1;
                    let child = node.children[c];
                    fetch(blas, child);
                    debug_assert!(sp < STACK);
                    stack.get_unchecked_mut(sp).write(Entry {
                        node: child,
                        rays: n.rays[c],
                        dist: n.dist[c],
                    });
                    sp += 1;
                }
                // Nearest on top (and, at equal distances, the lowest slot), as the single walk.
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
            } else {
                let leaf = cur & !LEAF_BIT;
                while active != 0 {
                    let r = active.trailing_zeros() as usize;
                    active &= active - 1;
                    let mut t_max = p.t_max[r];
                    triangles(blas, &p, r, &mut best[r], &mut opaque).closest(leaf, &mut t_max);
                    p.t_max[r] = t_max;
                }
            }
            loop {
                if sp == 0 {
                    break 'walk;
                }
                sp -= 1;
                let e = stack.get_unchecked(sp).assume_init();
                active = p.reaching(e.rays, e.dist);
                if active != 0 {
                    cur = e.node;
                    continue 'walk;
                }
            }
        }
    }
    std::array::from_fn(|i| (p.valid & (1 << i) != 0 && best[i].primitive != u32::MAX).then_some(best[i]))
}

/// Whether each ray of `rays` (at most [`PACKET`]) hits anything in `blas`.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn any<B: Backend>(blas: &Blas, rays: &[Ray]) -> [bool; PACKET] {
    let mut p = Packet::<B>::empty();
    p.load(rays);
    let mut done = 0u32;
    let mut scratch = no_hit(0.0);
    let mut opaque = Opaque;
    if blas.root != EMPTY {
        let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
        let mut sp = 0usize;
        let (mut cur, mut active) = (blas.root, p.valid);
        'walk: loop {
            if active.count_ones() <= SPARSE || cur & LEAF_BIT != 0 {
                // A leaf, or a diverged packet: each remaining ray on its own.
                while active != 0 {
                    let r = active.trailing_zeros() as usize;
                    active &= active - 1;
                    let mut leaves = triangles(blas, &p, r, &mut scratch, &mut opaque);
                    let hit = if cur & LEAF_BIT != 0 {
                        leaves.any(cur & !LEAF_BIT, p.t_max[r])
                    } else {
                        walk::any::<B, _>(&blas.nodes, cur, p.ray(r), &mut leaves, p.t_max[r])
                    };
                    if hit {
                        done |= 1 << r;
                        // An interval no box test accepts: the ray takes no further part.
                        p.t_max[r] = f32::NEG_INFINITY;
                    }
                }
                if done == p.valid {
                    break 'walk;
                }
            } else {
                debug_assert!((cur as usize) < blas.nodes.len());
                let node = blas.nodes.get_unchecked(cur as usize);
                let n = p.node(node, active);
                let mut children = n.children;
                if children.count_ones() == 1 {
                    let c = children.trailing_zeros() as usize;
                    (cur, active) = (node.children[c], n.rays[c]);
                    continue 'walk;
                }
                while children != 0 {
                    let c = children.trailing_zeros() as usize;
                    children &= children - 1;
                    let child = node.children[c];
                    fetch(blas, child);
                    debug_assert!(sp < STACK);
                    stack.get_unchecked_mut(sp).write(Entry { node: child, rays: n.rays[c], dist: 0.0 });
                    sp += 1;
                }
            }
            loop {
                if sp == 0 {
                    break 'walk;
                }
                sp -= 1;
                let e = stack.get_unchecked(sp).assume_init();
                active = e.rays & !done;
                if active != 0 {
                    cur = e.node;
                    continue 'walk;
                }
            }
        }
    }
    std::array::from_fn(|i| done & (1 << i) != 0)
}
