//! Packet queries: up to [`PACKET`] rays traced through one mesh ([`Blas`]) or a scene
//! ([`Tlas`]) together, for coherent rays
//! (primary rays of neighbouring pixels, shadow rays from neighbouring points to one light).
//!
//! The rays share one walk of the hierarchy: a node is visited when any of them enters it, by
//! those that do, and a packet that has thinned out continues ray by ray
//! ([`crate::traverse::packet`]). Each ray keeps its own interval and gets exactly the hit the
//! single-ray query gives it (the same triangle, distance and barycentrics, bit for bit), so a
//! caller may batch or not without changing an image.
//!
//! How to batch: put rays that start near each other and point the same way in one packet,
//! e.g. the primary rays of an 8 × 4 block of pixels (walk the image in tiles, pixels in Morton
//! order inside a tile, and take [`PACKET`] consecutive rays), or the shadow rays from such a
//! block's surface points towards the same light, in the same order. Rays that diverge
//! (diffuse bounces, even from neighbouring pixels) share only the top of the walk and then
//! continue ray by ray, so they gain less; measure before batching them. A short last packet
//! is fine; lanes
//! past the slice's end report no hit, and invalid rays in a packet hit nothing, as alone.
//! A query keeps its rays' kernel forms and its stack on the thread's stack: about 10 KB with the
//! AVX2 kernel (twice that through a scene's instances).

use crate::blas::Blas;
use crate::hit::Hit;
use crate::ray::Ray;
use crate::tlas::Tlas;
use crate::traverse::dispatch;

pub use crate::traverse::backend::PACKET;

impl Blas {
    /// The closest hit of each ray of `rays` in `[t_min, t_max]`, as [`Blas::closest_hit`]
    /// would return it; entries past `rays.len()` are `None`.
    ///
    /// # Panics
    /// If `rays` holds more than [`PACKET`] rays.
    #[inline]
    pub fn closest_packet(&self, rays: &[Ray]) -> [Option<Hit>; PACKET] {
        assert!(rays.len() <= PACKET, "a packet holds at most {PACKET} rays, not {}", rays.len());
        dispatch::closest_packet(self, rays)
    }

    /// Whether anything lies on each ray of `rays` in `[t_min, t_max]`, as [`Blas::any_hit`]
    /// would say (for shadow rays); entries past `rays.len()` are `false`.
    ///
    /// # Panics
    /// If `rays` holds more than [`PACKET`] rays.
    #[inline]
    pub fn any_packet(&self, rays: &[Ray]) -> [bool; PACKET] {
        assert!(rays.len() <= PACKET, "a packet holds at most {PACKET} rays, not {}", rays.len());
        dispatch::any_packet(self, rays)
    }
}

impl Tlas {
    /// The closest hit of each ray of `rays` among all instances, as [`Tlas::closest_hit`]
    /// would return it; entries past `rays.len()` are `None`.
    ///
    /// # Panics
    /// If `rays` holds more than [`PACKET`] rays.
    #[inline]
    pub fn closest_packet(&self, rays: &[Ray]) -> [Option<Hit>; PACKET] {
        assert!(rays.len() <= PACKET, "a packet holds at most {PACKET} rays, not {}", rays.len());
        dispatch::tlas_closest_packet(self, rays)
    }

    /// Whether anything lies on each ray of `rays`, as [`Tlas::any_hit`] would say (for
    /// shadow rays); entries past `rays.len()` are `false`.
    ///
    /// # Panics
    /// If `rays` holds more than [`PACKET`] rays.
    #[inline]
    pub fn any_packet(&self, rays: &[Ray]) -> [bool; PACKET] {
        assert!(rays.len() <= PACKET, "a packet holds at most {PACKET} rays, not {}", rays.len());
        dispatch::tlas_any_packet(self, rays)
    }
}
