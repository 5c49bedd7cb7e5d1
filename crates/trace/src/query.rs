//! The queries of DXR's `TraceRay`: the closest hit (with `RAY_FLAG_NONE`) and any hit (with
//! `RAY_FLAG_ACCEPT_FIRST_HIT_AND_END_SEARCH`, for shadow and occlusion rays), on one mesh or a
//! whole scene, with or without an any-hit filter.

use crate::blas::Blas;
use crate::hit::{Hit, HitFilter, Opaque};
use crate::ray::Ray;
use crate::tlas::Tlas;
use crate::traverse::dispatch::{self, Query};

impl Blas {
    /// The closest hit of `ray` in `[t_min, t_max]` (instance [`Hit::NO_INSTANCE`]).
    #[inline]
    pub fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        dispatch::blas(self, ray, &mut Opaque, Query::Closest)
    }

    /// The closest hit that `filter` accepts.
    #[inline]
    pub fn closest_hit_filtered(&self, ray: &Ray, filter: &mut impl HitFilter) -> Option<Hit> {
        dispatch::blas(self, ray, filter, Query::Closest)
    }

    /// Whether anything lies on `ray` in `[t_min, t_max]`; stops at the first hit.
    #[inline]
    pub fn any_hit(&self, ray: &Ray) -> bool {
        dispatch::blas(self, ray, &mut Opaque, Query::Any).is_some()
    }

    /// The first hit found that `filter` accepts (not necessarily the closest).
    #[inline]
    pub fn any_hit_filtered(&self, ray: &Ray, filter: &mut impl HitFilter) -> Option<Hit> {
        dispatch::blas(self, ray, filter, Query::Any)
    }
}

impl Tlas {
    /// The closest hit of `ray` in `[t_min, t_max]` among all instances.
    #[inline]
    pub fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        dispatch::tlas(self, ray, &mut Opaque, Query::Closest)
    }

    /// The closest hit that `filter` accepts.
    #[inline]
    pub fn closest_hit_filtered(&self, ray: &Ray, filter: &mut impl HitFilter) -> Option<Hit> {
        dispatch::tlas(self, ray, filter, Query::Closest)
    }

    /// Whether anything lies on `ray` in `[t_min, t_max]`; stops at the first hit.
    #[inline]
    pub fn any_hit(&self, ray: &Ray) -> bool {
        dispatch::tlas(self, ray, &mut Opaque, Query::Any).is_some()
    }

    /// The first hit found that `filter` accepts (not necessarily the closest).
    #[inline]
    pub fn any_hit_filtered(&self, ray: &Ray, filter: &mut impl HitFilter) -> Option<Hit> {
        dispatch::tlas(self, ray, filter, Query::Any)
    }
}
