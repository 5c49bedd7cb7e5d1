//! The run-time choice of kernel: each query is instantiated once per kernel, the vector copy
//! inside a function compiled for AVX2 and FMA (and a second one also compiled for AVX-512,
//! whose 32 registers the same code then uses, taken where the CPU has it), and called after
//! the CPU check made when the hierarchy's kernel was chosen. In the AVX2 copy the single-ray
//! queries run on [`crate::traverse::avx2_single`], the packets on the AVX2 kernel; the
//! AVX-512 copy keeps its own form for both (the single-ray form was measured on AMD's Zen 3
//! only).

use crate::blas::Blas;
use crate::hit::{Hit, HitFilter};
use crate::kernel::Kernel;
use crate::ray::Ray;
use crate::tlas::Tlas;
use crate::traverse::backend::PACKET;
use crate::traverse::leaves;
use crate::traverse::packet_leaves;
use crate::traverse::scalar::Scalar;

/// Which query.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Query {
    /// The closest accepted hit.
    Closest,
    /// Any accepted hit.
    Any,
}

/// The queries instantiated in a module compiled for the given CPU features: the packet
/// queries on the kernel `$backend`, the single-ray queries on `$single`.
macro_rules! instantiate {
    ($name:ident, $backend:ty, $single:ty, $features:literal) => {
        #[cfg(target_arch = "x86_64")]
        mod $name {
            use super::*;

            #[target_feature(enable = $features)]
            pub unsafe fn blas(
                blas: &Blas,
                ray: &Ray,
                filter: &mut impl HitFilter,
                query: Query,
            ) -> Option<Hit> {
                match query {
                    Query::Closest => leaves::blas_closest::<$single, _>(blas, ray, filter),
                    Query::Any => leaves::blas_any::<$single, _>(blas, ray, filter),
                }
            }

            #[target_feature(enable = $features)]
            pub unsafe fn tlas(
                tlas: &Tlas,
                ray: &Ray,
                filter: &mut impl HitFilter,
                query: Query,
            ) -> Option<Hit> {
                match query {
                    Query::Closest => leaves::tlas_closest::<$single, _>(tlas, ray, filter),
                    Query::Any => leaves::tlas_any::<$single, _>(tlas, ray, filter),
                }
            }

            #[target_feature(enable = $features)]
            pub unsafe fn closest_packet(blas: &Blas, rays: &[Ray]) -> [Option<Hit>; PACKET] {
                packet_leaves::blas_closest::<$backend>(blas, rays)
            }

            #[target_feature(enable = $features)]
            pub unsafe fn any_packet(blas: &Blas, rays: &[Ray]) -> [bool; PACKET] {
                packet_leaves::blas_any::<$backend>(blas, rays)
            }

            #[target_feature(enable = $features)]
            pub unsafe fn tlas_closest_packet(tlas: &Tlas, rays: &[Ray]) -> [Option<Hit>; PACKET] {
                packet_leaves::tlas_closest::<$backend>(tlas, rays)
            }

            #[target_feature(enable = $features)]
            pub unsafe fn tlas_any_packet(tlas: &Tlas, rays: &[Ray]) -> [bool; PACKET] {
                packet_leaves::tlas_any::<$backend>(tlas, rays)
            }
        }
    };
}

instantiate!(simd, crate::traverse::avx2::Avx2, crate::traverse::avx2_single::Avx2Single, "avx2,fma");
// Where the CPU has AVX-512: the same AVX2 code compiled with its 32 vector registers and mask
// registers, so that a walk's state need not spill, and a packet's node test sixteen rays to a
// register ([`crate::traverse::avx512`]); the same operations, so the same bits.
instantiate!(
    simd512,
    crate::traverse::avx512::Avx512,
    crate::traverse::avx512::Avx512,
    "avx2,fma,avx512f,avx512vl"
);

/// Which instantiation of the vector queries runs.
#[cfg(target_arch = "x86_64")]
macro_rules! vector {
    ($f:ident($($arg:expr),*)) => {
        if crate::kernel::wide_registers() {
            simd512::$f($($arg),*)
        } else {
            simd::$f($($arg),*)
        }
    };
}

/// Runs `query` on one mesh with the mesh's kernel.
#[inline]
pub fn blas(blas: &Blas, ray: &Ray, filter: &mut impl HitFilter, query: Query) -> Option<Hit> {
    match blas.kernel {
        // SAFETY: a hierarchy's kernel is `Simd` only when the CPU has AVX2 and FMA (`with_kernel`,
        // `kernel::best`).
        #[cfg(target_arch = "x86_64")]
        Kernel::Simd => unsafe { vector!(blas(blas, ray, filter, query)) },
        // SAFETY: the scalar kernel needs no CPU feature.
        _ => unsafe {
            match query {
                Query::Closest => leaves::blas_closest::<Scalar, _>(blas, ray, filter),
                Query::Any => leaves::blas_any::<Scalar, _>(blas, ray, filter),
            }
        },
    }
}

/// Runs `query` on a scene with the scene's kernel.
#[inline]
pub fn tlas(tlas: &Tlas, ray: &Ray, filter: &mut impl HitFilter, query: Query) -> Option<Hit> {
    match tlas.kernel {
        // SAFETY: as in [`blas`].
        #[cfg(target_arch = "x86_64")]
        Kernel::Simd => unsafe { vector!(tlas(tlas, ray, filter, query)) },
        // SAFETY: the scalar kernel needs no CPU feature.
        _ => unsafe {
            match query {
                Query::Closest => leaves::tlas_closest::<Scalar, _>(tlas, ray, filter),
                Query::Any => leaves::tlas_any::<Scalar, _>(tlas, ray, filter),
            }
        },
    }
}

/// The closest hits of a packet of rays (at most [`PACKET`]) in one mesh, with its kernel.
#[inline]
pub fn closest_packet(blas: &Blas, rays: &[Ray]) -> [Option<Hit>; PACKET] {
    match blas.kernel {
        // SAFETY: as in [`blas`].
        #[cfg(target_arch = "x86_64")]
        Kernel::Simd => unsafe { vector!(closest_packet(blas, rays)) },
        // SAFETY: the scalar kernel needs no CPU feature.
        _ => unsafe { packet_leaves::blas_closest::<Scalar>(blas, rays) },
    }
}

/// Whether each ray of a packet (at most [`PACKET`]) hits anything in one mesh.
#[inline]
pub fn any_packet(blas: &Blas, rays: &[Ray]) -> [bool; PACKET] {
    match blas.kernel {
        // SAFETY: as in [`blas`].
        #[cfg(target_arch = "x86_64")]
        Kernel::Simd => unsafe { vector!(any_packet(blas, rays)) },
        // SAFETY: the scalar kernel needs no CPU feature.
        _ => unsafe { packet_leaves::blas_any::<Scalar>(blas, rays) },
    }
}

/// The closest hits of a packet of rays (at most [`PACKET`]) in a scene, with its kernel.
#[inline]
pub fn tlas_closest_packet(tlas: &Tlas, rays: &[Ray]) -> [Option<Hit>; PACKET] {
    match tlas.kernel {
        // SAFETY: as in [`blas`].
        #[cfg(target_arch = "x86_64")]
        Kernel::Simd => unsafe { vector!(tlas_closest_packet(tlas, rays)) },
        // SAFETY: the scalar kernel needs no CPU feature.
        _ => unsafe { packet_leaves::tlas_closest::<Scalar>(tlas, rays) },
    }
}

/// Whether each ray of a packet (at most [`PACKET`]) hits anything in a scene.
#[inline]
pub fn tlas_any_packet(tlas: &Tlas, rays: &[Ray]) -> [bool; PACKET] {
    match tlas.kernel {
        // SAFETY: as in [`blas`].
        #[cfg(target_arch = "x86_64")]
        Kernel::Simd => unsafe { vector!(tlas_any_packet(tlas, rays)) },
        // SAFETY: the scalar kernel needs no CPU feature.
        _ => unsafe { packet_leaves::tlas_any::<Scalar>(tlas, rays) },
    }
}
