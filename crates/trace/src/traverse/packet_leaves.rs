//! What a leaf is to a packet walk at each level, and the packet queries assembled from them.
//!
//! A bottom-level leaf is a block of four triangles: each active ray runs the single-ray block
//! test on it (the single-ray walk's `Triangles` leaves). A top-level leaf is an instance: the
//! active rays are carried into its object space one by one (by [`Ray::transformed`], as the
//! single-ray query carries them, with their current intervals) and walk its bottom level
//! together as a packet whose lanes are the same rays, so their hits and intervals come back
//! to the same lanes. A ray that goes on alone takes the single-ray walk of its level.

use crate::blas::Blas;
use crate::hit::{Hit, Opaque};
use crate::node::{Nodes, WideNode, LEAF_BIT};
use crate::ray::Ray;
use crate::tlas::Tlas;
use crate::traverse::backend::{prefetch, Backend, PACKET};
use crate::traverse::leaves::{no_hit, Instances, Triangles};
use crate::traverse::packet::{self, Packet, PacketLeaves};
use crate::traverse::walk::{self, Leaves};
use glam::Vec3;
use std::marker::PhantomData;

/// A bottom level's leaves for a packet, reporting hits with `instance`.
struct Blocks<'a> {
    blas: &'a Blas,
    instance: u32,
}

impl<'a> Blocks<'a> {
    /// Ray `r`'s single-ray leaves.
    #[inline(always)]
    unsafe fn ray<'b, B: Backend>(
        &self,
        p: &'b Packet<B>,
        r: usize,
        best: &'b mut Hit,
        filter: &'b mut Opaque,
    ) -> Triangles<'b, B, Opaque>
    where
        'a: 'b,
    {
        Triangles { blocks: &self.blas.arena, prepared: p.ray(r), instance: self.instance, best, filter }
    }
}

impl<B: Backend> PacketLeaves<B> for Blocks<'_> {
    #[inline(always)]
    unsafe fn node(&self, r: u32) -> &WideNode {
        self.blas.arena.node(r)
    }

    #[inline(always)]
    unsafe fn fetch(&self, child: u32, after: u32) {
        if child & LEAF_BIT == 0 {
            walk::prefetch_node(self.blas.arena.node(child), after);
        } else {
            prefetch(self.blas.arena.block(child));
        }
    }

    #[inline(always)]
    unsafe fn closest_leaf(
        &mut self,
        p: &mut Packet<B>,
        best: &mut [Hit; PACKET],
        leaf: u32,
        mut active: u32,
    ) {
        while active != 0 {
            let r = active.trailing_zeros() as usize;
            active &= active - 1;
            let mut t_max = p.t_max[r];
            self.ray(p, r, &mut best[r], &mut Opaque).closest(leaf, &mut t_max);
            p.t_max[r] = t_max;
        }
    }

    #[inline(always)]
    unsafe fn closest_alone(&mut self, p: &mut Packet<B>, best: &mut [Hit; PACKET], node: u32, r: usize) {
        let mut t_max = p.t_max[r];
        let mut opaque = Opaque;
        let mut leaves = self.ray(p, r, &mut best[r], &mut opaque);
        walk::closest::<B, _, _>(&self.blas.arena, node, p.ray(r), &mut leaves, &mut t_max);
        p.t_max[r] = t_max;
    }

    #[inline(always)]
    unsafe fn any_leaf(&mut self, p: &Packet<B>, leaf: u32, mut active: u32) -> u32 {
        let mut scratch = no_hit(0.0);
        let mut hits = 0;
        while active != 0 {
            let r = active.trailing_zeros() as usize;
            active &= active - 1;
            hits |= (self.ray(p, r, &mut scratch, &mut Opaque).any(leaf, p.t_max[r]) as u32) << r;
        }
        hits
    }

    #[inline(always)]
    unsafe fn any_alone(&mut self, p: &Packet<B>, node: u32, r: usize) -> bool {
        let mut scratch = no_hit(0.0);
        let mut opaque = Opaque;
        let mut leaves = self.ray(p, r, &mut scratch, &mut opaque);
        walk::any::<B, _, _>(&self.blas.arena, node, p.ray(r), &mut leaves, p.t_max[r])
    }
}

/// Rays of one group of eight entering an instance above which the group is set up together
/// ([`Packet::set8`]) rather than one by one.
const GROUP: u32 = 2;

/// A top level's leaves for a packet: the instances, entered with the world rays `rays`.
struct Placed<'a> {
    tlas: &'a Tlas,
    rays: &'a [Ray],
}

impl Placed<'_> {
    /// Fills `object` (empty) with the rays of `active` in `instance`'s object space over
    /// their current intervals; returns the instance's mesh.
    #[inline(always)]
    unsafe fn enter<B: Backend>(
        &self,
        p: &Packet<B>,
        instance: u32,
        active: u32,
        object: &mut Packet<B>,
    ) -> &Blas {
        debug_assert!((instance as usize) < self.tlas.placed.len());
        let placed = self.tlas.placed.get_unchecked(instance as usize);
        // World rays from one origin are carried to one origin (the same map of the same point).
        object.keep_rows(p.keeps_rows());
        let carried = |r: usize| {
            let mut ray = self.rays.get_unchecked(r).transformed(&placed.world_to_object);
            ray.t_max = p.t_max[r];
            ray
        };
        for h in 0..PACKET / 8 {
            let mut group = (active >> (8 * h)) & 0xff;
            if group.count_ones() > GROUP {
                // Set up together; the idle lanes hold a ray with no direction, which is left out.
                let mut rays = [Ray::new(Vec3::ZERO, Vec3::ZERO); 8];
                while group != 0 {
                    let i = group.trailing_zeros() as usize;
                    group &= group - 1;
                    rays[i] = carried(8 * h + i);
                }
                object.set8(h, &rays);
            }
            while group != 0 {
                let r = 8 * h + group.trailing_zeros() as usize;
                group &= group - 1;
                object.set_ray(r, &carried(r));
            }
        }
        self.tlas.meshes.get_unchecked(placed.mesh as usize)
    }

    /// Ray `r`'s single-ray leaves.
    #[inline(always)]
    fn ray<'b, B: Backend>(
        &'b self,
        r: usize,
        best: &'b mut Hit,
        filter: &'b mut Opaque,
    ) -> Instances<'b, B, Opaque> {
        Instances { tlas: self.tlas, ray: &self.rays[r], best, filter, backend: PhantomData }
    }
}

impl<B: Backend> PacketLeaves<B> for Placed<'_> {
    #[inline(always)]
    unsafe fn node(&self, r: u32) -> &WideNode {
        self.tlas.nodes.as_slice().node(r)
    }

    #[inline(always)]
    unsafe fn fetch(&self, child: u32, _after: u32) {
        if child & LEAF_BIT == 0 {
            prefetch(self.tlas.nodes.as_slice().node(child));
        }
    }

    #[inline(always)]
    unsafe fn closest_leaf(
        &mut self,
        p: &mut Packet<B>,
        best: &mut [Hit; PACKET],
        instance: u32,
        active: u32,
    ) {
        let mut object = Packet::<B>::empty();
        let blas = self.enter(p, instance, active, &mut object);
        packet::closest(blas.root, &mut object, best, &mut Blocks { blas, instance });
        let mut valid = object.valid;
        while valid != 0 {
            let r = valid.trailing_zeros() as usize;
            valid &= valid - 1;
            p.t_max[r] = object.t_max[r];
        }
    }

    #[inline(always)]
    unsafe fn closest_alone(&mut self, p: &mut Packet<B>, best: &mut [Hit; PACKET], node: u32, r: usize) {
        let mut t_max = p.t_max[r];
        let mut opaque = Opaque;
        let mut leaves = self.ray::<B>(r, &mut best[r], &mut opaque);
        walk::closest::<B, _, _>(self.tlas.nodes.as_slice(), node, p.ray(r), &mut leaves, &mut t_max);
        p.t_max[r] = t_max;
    }

    #[inline(always)]
    unsafe fn any_leaf(&mut self, p: &Packet<B>, instance: u32, active: u32) -> u32 {
        let mut object = Packet::<B>::empty();
        let blas = self.enter(p, instance, active, &mut object);
        packet::any(blas.root, &mut object, &mut Blocks { blas, instance })
    }

    #[inline(always)]
    unsafe fn any_alone(&mut self, p: &Packet<B>, node: u32, r: usize) -> bool {
        let mut scratch = no_hit(0.0);
        let mut opaque = Opaque;
        let mut leaves = self.ray::<B>(r, &mut scratch, &mut opaque);
        walk::any::<B, _, _>(self.tlas.nodes.as_slice(), node, p.ray(r), &mut leaves, p.t_max[r])
    }
}

/// Each lane's hit, from the best hits of a walk.
fn hits(valid: u32, best: &[Hit; PACKET]) -> [Option<Hit>; PACKET] {
    std::array::from_fn(|i| (valid & (1 << i) != 0 && best[i].primitive != u32::MAX).then_some(best[i]))
}

/// The closest hit of each ray of `rays` (at most [`PACKET`]) in one mesh.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn blas_closest<B: Backend>(blas: &Blas, rays: &[Ray]) -> [Option<Hit>; PACKET] {
    let mut p = Packet::<B>::empty();
    p.load(rays);
    let mut best = p.t_max.map(no_hit);
    packet::closest(blas.root, &mut p, &mut best, &mut Blocks { blas, instance: Hit::NO_INSTANCE });
    hits(p.valid, &best)
}

/// Whether each ray of `rays` (at most [`PACKET`]) hits anything in one mesh.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn blas_any<B: Backend>(blas: &Blas, rays: &[Ray]) -> [bool; PACKET] {
    let mut p = Packet::<B>::empty();
    p.load(rays);
    let done = packet::any(blas.root, &mut p, &mut Blocks { blas, instance: Hit::NO_INSTANCE });
    std::array::from_fn(|i| done & (1 << i) != 0)
}

/// The closest hit of each ray of `rays` (at most [`PACKET`]) among all instances.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn tlas_closest<B: Backend>(tlas: &Tlas, rays: &[Ray]) -> [Option<Hit>; PACKET] {
    let mut p = Packet::<B>::empty();
    p.load(rays);
    let mut best = p.t_max.map(no_hit);
    packet::closest(tlas.root, &mut p, &mut best, &mut Placed { tlas, rays });
    hits(p.valid, &best)
}

/// Whether each ray of `rays` (at most [`PACKET`]) hits anything among all instances.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn tlas_any<B: Backend>(tlas: &Tlas, rays: &[Ray]) -> [bool; PACKET] {
    let mut p = Packet::<B>::empty();
    p.load(rays);
    let done = packet::any(tlas.root, &mut p, &mut Placed { tlas, rays });
    std::array::from_fn(|i| done & (1 << i) != 0)
}
