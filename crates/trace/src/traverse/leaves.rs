//! What a leaf is at each level, and the queries assembled from walks and leaves.
//!
//! A bottom-level leaf is a block of four triangles: the kernel tests them together and each
//! hit lane, in lane order, is offered to the filter if it precedes the best hit so far
//! ([`Hit::precedes`]). A top-level leaf is an instance: the ray is carried into its object
//! space and walks the mesh's bottom level with the same (shortened) interval.

use crate::blas::Blas;
use crate::hit::{Hit, HitFilter};
use crate::node::Arena;
use crate::ray::Ray;
use crate::tlas::Tlas;
use crate::traverse::backend::{prefetch, Backend};
use crate::traverse::walk::{self, Leaves};
use std::marker::PhantomData;

/// The best hit so far, starting as a sentinel at the ray's `t_max` that every real hit there
/// precedes.
pub(crate) fn no_hit(t_max: f32) -> Hit {
    Hit { t: t_max, u: 0.0, v: 0.0, primitive: u32::MAX, instance: u32::MAX }
}

/// Leaves of a bottom level: triangle blocks.
pub(crate) struct Triangles<'a, B: Backend, F> {
    pub(crate) blocks: &'a Arena,
    pub(crate) prepared: &'a B::Prepared,
    pub(crate) instance: u32,
    pub(crate) best: &'a mut Hit,
    pub(crate) filter: &'a mut F,
}

impl<B: Backend, F: HitFilter> Leaves for Triangles<'_, B, F> {
    #[inline(always)]
    unsafe fn closest(&mut self, leaf: u32, t_max: &mut f32) {
        let block = self.blocks.block(leaf);
        let hits = B::block(self.prepared, block, *t_max);
        let mut mask = hits.mask;
        while mask != 0 {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let (t, primitive) = (hits.t[lane], block.prim[lane]);
            if Hit::precedes(t, self.instance, primitive, self.best) {
                let hit = Hit { t, u: hits.u[lane], v: hits.v[lane], primitive, instance: self.instance };
                if self.filter.accept(&hit) {
                    *self.best = hit;
                    *t_max = t;
                }
            }
        }
    }

    #[inline(always)]
    unsafe fn any(&mut self, leaf: u32, t_max: f32) -> bool {
        let block = self.blocks.block(leaf);
        let hits = B::block(self.prepared, block, t_max);
        let mut mask = hits.mask;
        while mask != 0 {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let hit = Hit {
                t: hits.t[lane],
                u: hits.u[lane],
                v: hits.v[lane],
                primitive: block.prim[lane],
                instance: self.instance,
            };
            if self.filter.accept(&hit) {
                *self.best = hit;
                return true;
            }
        }
        false
    }

    #[inline(always)]
    fn fetch(&self, leaf: u32) {
        // SAFETY: leaf payloads come from the same build as `blocks`.
        prefetch(unsafe { self.blocks.block(leaf) });
    }
}

/// Leaves of the top level: instances.
pub(crate) struct Instances<'a, B: Backend, F> {
    pub(crate) tlas: &'a Tlas,
    pub(crate) ray: &'a Ray,
    pub(crate) best: &'a mut Hit,
    pub(crate) filter: &'a mut F,
    pub(crate) backend: PhantomData<B>,
}

impl<'a, B: Backend, F: HitFilter> Instances<'a, B, F> {
    /// The instance's mesh and the ray in its space over `[t_min, t_max]`.
    #[inline(always)]
    unsafe fn enter(&self, instance: u32, t_max: f32) -> Option<(&'a Blas, B::Prepared)> {
        debug_assert!((instance as usize) < self.tlas.placed.len());
        let placed = self.tlas.placed.get_unchecked(instance as usize);
        let (p, _) = B::prepare_transformed(self.ray, &placed.world_to_object, t_max)?;
        Some((self.tlas.meshes.get_unchecked(placed.mesh as usize), p))
    }
}

impl<B: Backend, F: HitFilter> Leaves for Instances<'_, B, F> {
    #[inline(always)]
    unsafe fn closest(&mut self, instance: u32, t_max: &mut f32) {
        let Some((blas, p)) = self.enter(instance, *t_max) else { return };
        let mut tris = Triangles::<B, F> {
            blocks: &blas.arena,
            prepared: &p,
            instance,
            best: self.best,
            filter: self.filter,
        };
        walk::closest::<B, _, _>(&blas.arena, blas.root, &p, &mut tris, t_max);
    }

    #[inline(always)]
    unsafe fn any(&mut self, instance: u32, t_max: f32) -> bool {
        let Some((blas, p)) = self.enter(instance, t_max) else { return false };
        let mut tris = Triangles::<B, F> {
            blocks: &blas.arena,
            prepared: &p,
            instance,
            best: self.best,
            filter: self.filter,
        };
        walk::any::<B, _, _>(&blas.arena, blas.root, &p, &mut tris, t_max)
    }
}

/// The closest accepted hit of `ray` in one mesh.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn blas_closest<B: Backend, F: HitFilter>(blas: &Blas, ray: &Ray, filter: &mut F) -> Option<Hit> {
    let (p, t_max0) = B::prepare_ray(ray)?;
    let mut best = no_hit(t_max0);
    let mut t_max = t_max0;
    let mut tris = Triangles::<B, F> {
        blocks: &blas.arena,
        prepared: &p,
        instance: Hit::NO_INSTANCE,
        best: &mut best,
        filter,
    };
    walk::closest::<B, _, _>(&blas.arena, blas.root, &p, &mut tris, &mut t_max);
    (best.primitive != u32::MAX).then_some(best)
}

/// Any accepted hit of `ray` in one mesh (the first found, not the closest).
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn blas_any<B: Backend, F: HitFilter>(blas: &Blas, ray: &Ray, filter: &mut F) -> Option<Hit> {
    let (p, t_max) = B::prepare_ray(ray)?;
    let mut best = no_hit(t_max);
    let mut tris = Triangles::<B, F> {
        blocks: &blas.arena,
        prepared: &p,
        instance: Hit::NO_INSTANCE,
        best: &mut best,
        filter,
    };
    walk::any::<B, _, _>(&blas.arena, blas.root, &p, &mut tris, t_max).then_some(best)
}

/// The closest accepted hit of `ray` among all instances.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn tlas_closest<B: Backend, F: HitFilter>(tlas: &Tlas, ray: &Ray, filter: &mut F) -> Option<Hit> {
    let (p, t_max0) = B::prepare_ray(ray)?;
    let mut best = no_hit(t_max0);
    let mut t_max = t_max0;
    let mut insts = Instances::<B, F> { tlas, ray, best: &mut best, filter, backend: PhantomData };
    walk::closest::<B, _, _>(tlas.nodes.as_slice(), tlas.root, &p, &mut insts, &mut t_max);
    (best.primitive != u32::MAX).then_some(best)
}

/// Any accepted hit of `ray` among all instances.
///
/// # Safety
/// The CPU has `B`'s features.
#[inline(always)]
pub unsafe fn tlas_any<B: Backend, F: HitFilter>(tlas: &Tlas, ray: &Ray, filter: &mut F) -> Option<Hit> {
    let (p, t_max) = B::prepare_ray(ray)?;
    let mut best = no_hit(t_max);
    let mut insts = Instances::<B, F> { tlas, ray, best: &mut best, filter, backend: PhantomData };
    walk::any::<B, _, _>(tlas.nodes.as_slice(), tlas.root, &p, &mut insts, t_max).then_some(best)
}
