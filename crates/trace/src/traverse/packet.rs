//! The packet walk: up to [`PACKET`] rays share one traversal of a hierarchy, written once for
//! both levels (`PacketLeaves` says what a leaf is: [`crate::traverse::packet_leaves`]).
//!
//! Every ray keeps its own interval, best hit and kernel form (made eight rays at a time,
//! [`Backend::prepare8`], also for the rays that enter an instance together). At a node, each ray still
//! active runs the kernel's own single-ray node test ([`Backend::node`], so every box decision
//! is bit for bit the one the single-ray walk makes; the AVX-512 kernel may run the same test
//! child by child, sixteen rays to a register, [`crate::traverse::avx512`]); a child is visited when any ray enters
//! it, and only by the rays that do. A stack entry carries the child, the rays that entered
//! it and the least entry distance among them; on popping, a ray stays only if that distance
//! is within its own (possibly shortened) interval, the single-ray walk's test with a lower
//! bound in place of the ray's own distance, so it can keep a ray the single walk would drop,
//! never drop one it would keep. Children are entered nearest first by that least distance, and
//! the ones pushed are prefetched (the walk waits on memory more than on arithmetic). At
//! a leaf the active rays go on together (a bottom-level leaf: each runs the single-ray block
//! test; an instance: they are carried into its space and walk its bottom level as a packet).
//! When a node is reached by at most [`SPARSE`] rays the packet has diverged: each of them
//! walks the subtree alone with the single-ray walk.
//!
//! Rays from one origin (a pinhole camera's) whose kernel keeps them as rows have
//! [`PacketBounds`]: at a node reached by at least [`WHOLE`] of them, one test of the eight
//! children bounds every ray's test ([`Backend::whole`]). Where it decides each child (entered
//! by all of the rays or by none) its answer is each ray's own; above the leaves it may also
//! send all of the rays into a few children that only some enter, and their own tests further
//! down drop the others. Otherwise the rays are tested one by one.
//!
//! Why the hits equal the single-ray query's: a ray tests a leaf's triangles only after its
//! own conservative box test accepted the leaf (with an interval no shorter than its final
//! hit), and every node on the single walk's way to it is visited by the ray (each node test
//! above gives the ray at least the children its own test gives), so it reaches every leaf
//! holding a hit it could return; and the closest hit is chosen by [`Hit::precedes`], which
//! does not depend on the order in which leaves are tested. The any-hit walk retires a ray at
//! its first hit.

use crate::hit::Hit;
use crate::node::{WideNode, EMPTY, LEAF_BIT};
use crate::ray::Ray;
use crate::traverse::backend::{reaching_each, Backend, PacketBounds, PacketNode, Rows, PACKET};
use crate::traverse::walk::STACK;
use std::mem::MaybeUninit;

/// A node reached by this many active rays or fewer is walked by each of them alone.
pub const SPARSE: u32 = 2;

/// Active rays from which a node is first tested for the packet as a whole, where the
/// packet's rays share their origin ([`PacketBounds`]).
pub const WHOLE: u32 = 8;

#[derive(Clone, Copy)]
struct Entry {
    node: u32,
    rays: u32,
    dist: f32,
}

/// A packet's rays in kernel form, with their intervals.
pub(crate) struct Packet<B: Backend> {
    /// The lanes of `valid` written by [`Packet::set_ray`] or [`Packet::set8`]; the others never
    /// read.
    prepared: [MaybeUninit<B::Prepared>; PACKET],
    /// The rays as rows where the packet keeps them ([`Packet::keep_rows`]): the lanes of
    /// `valid` written, the others never read.
    rows: MaybeUninit<Rows>,
    /// Each ray's interval end, lowered by its hits (−∞ once it takes no further part).
    pub(crate) t_max: [f32; PACKET],
    /// Bit `i` set for each ray that can hit something.
    pub(crate) valid: u32,
    /// The bounds of the rays' slab tests, where the kernel finds them.
    bounds: Option<PacketBounds>,
    /// Whether the rays are kept as rows: for kernels with [`Backend::ROWS`], where the
    /// kernel's node test reads them ([`Backend::rows_always`]) or the rays share their
    /// origin (only then can they have bounds); rays from many points skip the writing.
    keep_rows: bool,
}

impl<B: Backend> Packet<B> {
    /// A packet of no rays, to be filled in place by [`Packet::set_ray`] (it is several
    /// kilobytes, left uninitialised until then).
    #[inline(always)]
    pub(crate) fn empty() -> Packet<B> {
        Packet {
            prepared: [const { MaybeUninit::uninit() }; PACKET],
            rows: MaybeUninit::uninit(),
            t_max: [f32::NEG_INFINITY; PACKET],
            valid: 0,
            bounds: None,
            keep_rows: B::ROWS && B::rows_always(),
        }
    }

    /// Keeps the rays as rows where the kernel has [`Backend::ROWS`] and `shared_origin` (the
    /// rays about to be put in share their origin), or where its node test reads them anyway.
    /// Called on an empty packet, before its rays are put in.
    #[inline(always)]
    pub(crate) fn keep_rows(&mut self, shared_origin: bool) {
        self.keep_rows = B::ROWS && (shared_origin || B::rows_always());
    }

    /// Whether the packet keeps its rays as rows ([`Packet::keep_rows`]).
    #[inline(always)]
    pub(crate) fn keeps_rows(&self) -> bool {
        self.keep_rows
    }

    /// Finds the packet's [`PacketBounds`] once its rays are in (packets that keep their rays
    /// as rows, [`Packet::keep_rows`], of at least [`WHOLE`] rays).
    ///
    /// # Safety
    /// The CPU has `B`'s features.
    #[inline(always)]
    unsafe fn bound(&mut self) {
        self.bounds = None;
        if self.keep_rows && self.valid.count_ones() >= WHOLE {
            self.bounds = B::bounds(&self.rows, self.valid, &self.t_max);
        }
    }

    /// Puts `ray` in lane `r` when it can hit something (else the lane stays empty).
    ///
    /// # Safety
    /// The CPU has `B`'s features.
    #[inline(always)]
    pub(crate) unsafe fn set_ray(&mut self, r: usize, ray: &Ray) {
        if let Some((p, t_max)) = B::prepare_ray(ray) {
            self.valid |= 1 << r;
            self.t_max[r] = t_max;
            if self.keep_rows {
                B::row(&p, &mut self.rows, r);
            }
            self.prepared[r].write(p);
        }
    }

    /// The packet of `rays` (at most [`PACKET`]; invalid rays leave their lane empty).
    ///
    /// # Safety
    /// The CPU has `B`'s features.
    #[inline(always)]
    pub(crate) unsafe fn load(&mut self, rays: &[Ray]) {
        let rays = &rays[..rays.len().min(PACKET)];
        // (The first origin that differs ends the comparison: rays from many points pay one.)
        self.keep_rows(rays.len() >= WHOLE as usize && rays.iter().all(|r| r.origin == rays[0].origin));
        let mut groups = rays.chunks_exact(8);
        for (h, group) in groups.by_ref().enumerate() {
            // `h < PACKET / 8`.
            self.set8(h, &*(group.as_ptr() as *const [Ray; 8]));
        }
        let base = rays.len() - groups.remainder().len();
        for (r, ray) in groups.remainder().iter().enumerate() {
            self.set_ray(base + r, ray);
        }
    }

    /// Puts `rays` in lanes `8·h .. 8·h + 8` (those that can hit something; the others stay
    /// out of `valid`), set up together by the kernel.
    ///
    /// # Safety
    /// The CPU has `B`'s features; `h < PACKET / 8`.
    #[inline(always)]
    pub(crate) unsafe fn set8(&mut self, h: usize, rays: &[Ray; 8]) {
        debug_assert!(h < PACKET / 8);
        let out = &mut *(self.prepared.as_mut_ptr().add(8 * h) as *mut [MaybeUninit<B::Prepared>; 8]);
        let t_max = &mut *(self.t_max.as_mut_ptr().add(8 * h) as *mut [f32; 8]);
        let valid = if self.keep_rows {
            B::prepare8_rows(rays, out, t_max, &mut self.rows, h)
        } else {
            B::prepare8(rays, out, t_max)
        };
        self.valid |= valid << (8 * h);
    }

    /// Ray `r`'s kernel form.
    ///
    /// # Safety
    /// Lane `r` holds a ray (bit `r` of `valid`).
    #[inline(always)]
    pub(crate) unsafe fn ray(&self, r: usize) -> &B::Prepared {
        self.prepared.get_unchecked(r).assume_init_ref()
    }

    /// Which rays of `active` enter each child, and their least entry distance.
    #[inline(always)]
    unsafe fn node(&self, node: &WideNode, active: u32) -> PacketNode {
        if let Some(b) = &self.bounds {
            if active.count_ones() >= WHOLE {
                if let Some((children, dist)) = B::whole(b, node, B::t_low(&self.t_max, active)) {
                    let rays = std::array::from_fn(|c| if children >> c & 1 != 0 { active } else { 0 });
                    return PacketNode { children, rays, dist };
                }
            }
        }
        // The walks keep `active` within `valid`, whose lanes are written.
        B::node_packet_rows(&self.prepared, &self.rows, node, active, &self.t_max)
    }

    /// The rays of `rays` whose interval still reaches distance `dist`.
    ///
    /// # Safety
    /// The CPU has `B`'s features.
    #[inline(always)]
    unsafe fn reaching(&self, rays: u32, dist: f32) -> u32 {
        if rays.count_ones() <= 4 {
            // Few rays (a thinned-out packet): test just those.
            return reaching_each(&self.t_max, rays, dist);
        }
        B::reaching(&self.t_max, rays, dist)
    }
}

/// What a packet walk does at the leaves of one level, and for a ray that goes on alone.
pub(crate) trait PacketLeaves<B: Backend> {
    /// The hierarchy's node with reference `r`.
    ///
    /// # Safety
    /// `r` is a node reference of the hierarchy.
    unsafe fn node(&self, r: u32) -> &WideNode;

    /// Starts loading what `child` refers to (and, for a node, the `after` lines that follow
    /// it, [`WideNode::after`]).
    ///
    /// # Safety
    /// `child` comes from this hierarchy.
    unsafe fn fetch(&self, child: u32, after: u32);

    /// The rays of `active` look for closer hits in leaf `leaf` (its reference without
    /// [`LEAF_BIT`]), lowering their `t_max` to them.
    ///
    /// # Safety
    /// The CPU has `B`'s features; the lanes of the rays walked hold rays.
    unsafe fn closest_leaf(&mut self, p: &mut Packet<B>, best: &mut [Hit; PACKET], leaf: u32, active: u32);

    /// Ray `r` looks for closer hits in the subtree at `node` with the single-ray walk.
    ///
    /// # Safety
    /// As for [`PacketLeaves::closest_leaf`].
    unsafe fn closest_alone(&mut self, p: &mut Packet<B>, best: &mut [Hit; PACKET], node: u32, r: usize);

    /// The rays of `active` that have a hit in leaf `leaf`.
    ///
    /// # Safety
    /// As for [`PacketLeaves::closest_leaf`].
    unsafe fn any_leaf(&mut self, p: &Packet<B>, leaf: u32, active: u32) -> u32;

    /// Whether ray `r` has a hit in the subtree at `node` (single-ray walk).
    ///
    /// # Safety
    /// As for [`PacketLeaves::closest_leaf`].
    unsafe fn any_alone(&mut self, p: &Packet<B>, node: u32, r: usize) -> bool;
}

/// Walks the hierarchy from `root` for each ray's closest hit, updating `best` and `p.t_max`.
///
/// # Safety
/// The CPU has `B`'s features; the lanes of the rays walked hold rays; `root` and the leaves come from one
/// build.
#[inline(always)]
pub(crate) unsafe fn closest<B: Backend, L: PacketLeaves<B>>(
    root: u32,
    p: &mut Packet<B>,
    best: &mut [Hit; PACKET],
    leaves: &mut L,
) {
    if root == EMPTY {
        return;
    }
    p.bound();
    let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
    let mut sp = 0usize;
    let (mut cur, mut active) = (root, p.valid);
    'walk: loop {
        if active.count_ones() <= SPARSE {
            // Diverged: each remaining ray walks this subtree alone.
            while active != 0 {
                let r = active.trailing_zeros() as usize;
                active &= active - 1;
                leaves.closest_alone(p, best, cur, r);
            }
        } else if cur & LEAF_BIT == 0 {
            let node = leaves.node(cur);
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
                leaves.fetch(child, node.after[c]);
                debug_assert!(sp < STACK);
                stack.get_unchecked_mut(sp).write(Entry { node: child, rays: n.rays[c], dist: n.dist[c] });
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
            leaves.closest_leaf(p, best, cur & !LEAF_BIT, active);
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

/// Walks the hierarchy from `root` until every ray has a hit or none is left to find; returns
/// the rays that have one (each then has `t_max` −∞).
///
/// # Safety
/// As for [`closest`].
#[inline(always)]
pub(crate) unsafe fn any<B: Backend, L: PacketLeaves<B>>(
    root: u32,
    p: &mut Packet<B>,
    leaves: &mut L,
) -> u32 {
    let mut done = 0u32;
    if root == EMPTY {
        return done;
    }
    p.bound();
    let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
    let mut sp = 0usize;
    let (mut cur, mut active) = (root, p.valid);
    'walk: loop {
        if active.count_ones() <= SPARSE || cur & LEAF_BIT != 0 {
            // A leaf, or a diverged packet.
            let hits = if cur & LEAF_BIT != 0 {
                leaves.any_leaf(p, cur & !LEAF_BIT, active)
            } else {
                let mut hits = 0;
                while active != 0 {
                    let r = active.trailing_zeros() as usize;
                    active &= active - 1;
                    hits |= (leaves.any_alone(p, cur, r) as u32) << r;
                }
                hits
            };
            done |= hits;
            let mut h = hits;
            while h != 0 {
                // An interval no box test accepts: the ray takes no further part.
                p.t_max[h.trailing_zeros() as usize] = f32::NEG_INFINITY;
                h &= h - 1;
            }
            if done == p.valid {
                break 'walk;
            }
        } else {
            let node = leaves.node(cur);
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
                leaves.fetch(child, node.after[c]);
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
    done
}
