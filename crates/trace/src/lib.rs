//! Ray tracing's acceleration structure: a two-level bounding volume hierarchy like DXR's.
//!
//! A [`Blas`] (bottom level) is one mesh's BVH in the mesh's own space; a [`Tlas`] (top level)
//! is a BVH over [`Instance`]s, each a mesh placed by an affine object-to-world transform. A
//! ray reaching an instance is carried into the mesh's space by the inverse transform (its
//! direction is not renormalised, so distances agree in both spaces) and continues in that
//! mesh's bottom level. Queries are DXR's: the closest hit ([`Tlas::closest_hit`]) and any hit
//! for shadow rays ([`Tlas::any_hit`], stopping at the first), each optionally with an any-hit
//! filter ([`HitFilter`], DXR's any-hit shader: accept or ignore a candidate, for alpha-tested
//! or translucent surfaces).
//!
//! ```
//! use glam::{Affine3A, Vec3};
//! use renderlab_trace::{Blas, Instance, Ray, Tlas};
//!
//! let quad = [Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0), Vec3::new(-1.0, 1.0, 0.0)];
//! let mesh = Blas::build(&quad, &[[0, 1, 2], [0, 2, 3]])?;
//! let scene = Tlas::build(vec![mesh], &[
//!     Instance::new(0, Affine3A::IDENTITY),
//!     Instance::new(0, Affine3A::from_translation(Vec3::new(0.0, 0.0, -3.0))),
//! ])?;
//! let hit = scene.closest_hit(&Ray::new(Vec3::new(0.5, 0.2, 5.0), -Vec3::Z)).unwrap();
//! assert_eq!((hit.instance, hit.t), (0, 5.0));
//! assert!(scene.any_hit(&Ray::segment(Vec3::new(0.5, 0.2, -1.0), -Vec3::Z, 0.0, 10.0)));
//! # Ok::<(), renderlab_trace::BuildError>(())
//! ```
//!
//! # Layout
//!
//! Both levels use the same 8-wide node ([`node::WideNode`], 256 bytes, four cache lines): the
//! eight children's boxes stored as six rows of eight floats (min x, max x, min y, …), so that
//! one AVX2 load brings one plane of all eight children and a node visit is a couple of dozen
//! vector instructions, eight 32-bit child references whose top bit marks a leaf, and per child
//! the lines of leaf blocks that follow it in memory (so a walk requests them with it). Bounds
//! stay full-precision floats: compressed nodes (8-bit child planes, as in the compressed wide
//! BVH that obvhs uses) save memory but cost a decompression per visit, and exact boxes are
//! what the conservative slab test below reasons about. A bottom-level leaf is one block of up
//! to four triangles ([`node::TriBlock`], 160 bytes) holding the vertices themselves in
//! structure-of-arrays form, so a leaf test reads one contiguous block and follows no index; a
//! bottom level keeps nodes and blocks in one [`node::Arena`], each node followed by its own
//! leaf blocks; the top level's leaves are instance indices.
//!
//! # Build
//!
//! A binary BVH is built top-down by binned SAH ([`build::binned`]: up to 32 bins on each of
//! the three axes, the cost counted in 4-triangle blocks so leaves come out full), in parallel
//! with rayon (subtrees as tasks, the large top nodes binned in parallel chunks), and its
//! result does not depend on the number of threads. It is then collapsed into 8-wide nodes
//! by a dynamic program that picks, of every way to group the binary nodes into wide ones, the
//! one with the least expected node tests ([`build::collapse`]; fewer and fuller nodes than
//! Embree's greedy opening of the largest child). Below a fixed depth the build splits at the
//! object median, which bounds every path, so the traversal's stack is a fixed array that
//! cannot overflow.
//!
//! # Traversal
//!
//! One generic walk ([`traverse::walk`]) serves both levels and both kernels: for the closest
//! hit it enters the nearest child and pushes the others ordered by entry distance, dropping
//! popped entries beyond the current hit; for any hit it stops at the first accepted one. The
//! kernel ([`traverse::backend::Backend`]) computes a node's eight slab tests and a block's four
//! triangle tests: [`traverse::avx2`] in vector registers, [`traverse::scalar`] lane by lane
//! with the same operations in the same order, so both give the same hits bit for bit; the
//! kernel is chosen at run time from the CPU's features ([`Kernel`]). Packet queries
//! ([`Blas::closest_packet`], [`Blas::any_packet`], and the same on a [`Tlas`]) walk up to
//! [`PACKET`] coherent rays together over the same kernels ([`traverse::packet`]) and give each
//! ray the single-ray hit; on Intel's AVX-512 processors a packet's node is tested child by
//! child, sixteen rays to a register ([`traverse::avx512`]), with the same results, and
//! packets of rays from one origin test a node's children once for all of their rays where
//! interval bounds decide them ([`traverse::backend::PacketBounds`]).
//!
//! # Exactness
//!
//! * Watertight: the ray–triangle test is Woop, Benthin and Wald's ([`triangle`]), in which a
//!   shared edge is computed identically for both of its triangles, with edge functions that
//!   round to zero recomputed in f64; the slab test scales the far distance by Ize's
//!   `1 + 2γ₃` and ignores the NaN of a ray lying in a box's plane, so it never drops a box a
//!   ray touches. A ray through a shared vertex or edge of a closed mesh always hits.
//! * Order-independent: among hits at the same distance the smaller (instance, primitive) wins
//!   ([`Hit::precedes`]), so the result equals the brute-force reference ([`brute`]) bit for
//!   bit, whatever order the hierarchy offers candidates in.
//! * Bad input is well defined: triangles with a non-finite vertex or zero area are left out,
//!   instances with a non-invertible transform are never hit, invalid rays hit nothing,
//!   out-of-range indices are [`BuildError`]s; nothing panics.

#![warn(missing_docs)]

pub mod aabb;
pub mod blas;
pub mod brute;
pub mod build;
pub mod error;
pub mod hit;
pub mod kernel;
pub mod lanes;
pub mod node;
pub mod packet;
mod pages;
pub mod query;
pub mod ray;
pub mod tlas;
pub mod traverse;
pub mod triangle;
pub mod workload;

pub use aabb::Aabb;
pub use blas::{Blas, Splits};
pub use error::BuildError;
pub use hit::{Hit, HitFilter, Opaque};
pub use kernel::Kernel;
pub use packet::PACKET;
pub use ray::Ray;
pub use tlas::{Instance, Placed, Tlas};
