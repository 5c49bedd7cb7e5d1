//! The bottom level: one 8-wide BVH over one mesh's triangles, in the mesh's own (object)
//! space, like DXR's bottom-level acceleration structure.

use crate::aabb::Aabb;
use crate::build::binned::{self, PrimRef, SahParams, MAX_PRIMS};
use crate::build::collapse::collapse;
use crate::build::spatial::{self, SPLITS};
use crate::error::BuildError;
use crate::kernel::Kernel;
pub use crate::node::Indexed;
use crate::node::{Arena, TriBlock, BLOCK, LEAF_BIT};
use crate::triangle::is_hittable;
use glam::Vec3;
use rayon::prelude::*;

/// The SAH of bottom levels: leaves of up to one 4-triangle block, and a node visit priced as
/// one block test (both are one vector operation on a handful of registers).
pub const BLAS_SAH: SahParams = SahParams { max_leaf: BLOCK, block: BLOCK, traversal_cost: 1.0 };

/// Whether a bottom-level build cuts triangles by spatial splits ([`crate::build::spatial`]).
///
/// Cutting makes the boxes around a surface tighter where the object splits' boxes overlap,
/// which most helps rays that start on the surface; it costs build time (the spatial build
/// bins every large node's triangles' clipped parts) and memory (a cut triangle is stored in
/// two leaves). Whether it pays depends on the mesh: on the 69k-triangle blob it takes 6 %
/// fewer node tests a ray; on the 1M-triangle terrain (an even grid) 1 to 2 % more.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Splits {
    /// Build with and without cuts, keep the tree of lower SAH cost (the default: two to three
    /// times the plain build's time; the terrain's 0.86 → 1.8 s, the 48 blobs' about 2.3 → 7 s).
    #[default]
    Auto,
    /// Never cut (the fastest build).
    Never,
    /// Always take the tree with cuts.
    Always,
}

/// A mesh's BVH: 8-wide nodes over leaves of up to four triangles, stored with the leaves'
/// vertices (so a query never reads the mesh), nodes and leaves together in one [`Arena`].
#[derive(Clone, Debug)]
pub struct Blas {
    pub(crate) arena: Arena,
    pub(crate) root: u32,
    pub(crate) kernel: Kernel,
    bounds: Aabb,
    triangles: usize,
    hittable: usize,
}

impl Blas {
    /// Builds the BVH of an indexed mesh, with [`Splits::Auto`]. Triangles with a non-finite
    /// vertex or zero area are left out (they can never be hit; see
    /// [`crate::triangle::is_hittable`]).
    pub fn build(positions: &[Vec3], indices: &[[u32; 3]]) -> Result<Blas, BuildError> {
        Blas::build_with_splits(positions, indices, Splits::Auto)
    }

    /// [`Blas::build`] choosing whether the build cuts triangles ([`Splits`]).
    pub fn build_with_splits(
        positions: &[Vec3],
        indices: &[[u32; 3]],
        splits: Splits,
    ) -> Result<Blas, BuildError> {
        if let Some((triangle, &index)) = indices
            .iter()
            .enumerate()
            .find_map(|(t, ix)| ix.iter().find(|&&i| i as usize >= positions.len()).map(|i| (t, i)))
        {
            return Err(BuildError::IndexOutOfRange { triangle, index, vertices: positions.len() });
        }
        Blas::build_with(indices.len(), |t| indices[t].map(|i| positions[i as usize]), splits)
    }

    /// Builds the BVH of a triangle soup (three vertices per triangle), with [`Splits::Auto`].
    pub fn from_triangles(triangles: &[[Vec3; 3]]) -> Result<Blas, BuildError> {
        Blas::from_triangles_with_splits(triangles, Splits::Auto)
    }

    /// [`Blas::from_triangles`] choosing whether the build cuts triangles ([`Splits`]).
    pub fn from_triangles_with_splits(triangles: &[[Vec3; 3]], splits: Splits) -> Result<Blas, BuildError> {
        Blas::build_with(triangles.len(), |t| triangles[t], splits)
    }

    fn build_with(
        count: usize,
        tri: impl Fn(usize) -> [Vec3; 3] + Sync,
        splits: Splits,
    ) -> Result<Blas, BuildError> {
        if count > MAX_PRIMS {
            return Err(BuildError::TooMany { what: "triangles", count, limit: MAX_PRIMS });
        }
        let refs: Vec<PrimRef> = (0..count)
            .into_par_iter()
            .with_min_len(4096)
            .filter_map(|t| {
                let [a, b, c] = tri(t);
                is_hittable(a, b, c).then(|| PrimRef::new(&Aabb::from_points(&[a, b, c]), t as u32))
            })
            .collect();
        let hittable = refs.len();
        let bvh = match splits {
            Splits::Never => binned::build(refs, &BLAS_SAH),
            Splits::Always => spatial::build(refs, &|t| tri(t as usize), &BLAS_SAH, &SPLITS),
            Splits::Auto => {
                let copy = refs.clone();
                let (plain, split) = rayon::join(
                    || binned::build(copy, &BLAS_SAH),
                    || spatial::build(refs, &|t| tri(t as usize), &BLAS_SAH, &SPLITS),
                );
                if split.sah(&BLAS_SAH) < plain.sah(&BLAS_SAH) {
                    split
                } else {
                    plain
                }
            }
        };
        let mut blocks = Vec::with_capacity(hittable.div_ceil(3));
        let (nodes, root) = collapse(&bvh, &mut |leaf: &[PrimRef]| {
            blocks.push(TriBlock::new(leaf.iter().map(|r| (r.index(), tri(r.index() as usize)))));
            LEAF_BIT | (blocks.len() - 1) as u32
        });
        let bounds = if hittable == 0 { Aabb::EMPTY } else { bvh.nodes[0].bounds() };
        drop(bvh);
        let (arena, root) = Arena::new(&Indexed { nodes, blocks, root })?;
        Ok(Blas { arena, root, kernel: crate::kernel::best(), bounds, triangles: count, hittable })
    }

    /// The same hierarchy queried with `kernel` (the scalar kernel where the CPU lacks it).
    pub fn with_kernel(mut self, kernel: Kernel) -> Blas {
        self.kernel = if crate::kernel::available(kernel) { kernel } else { Kernel::Scalar };
        self
    }

    /// The kernel queries run on.
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }

    /// The bounds of the hittable triangles (empty when there are none).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Triangles given to the build.
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// Triangles in the hierarchy (those that can be hit).
    pub fn hittable_count(&self) -> usize {
        self.hittable
    }

    /// Wide nodes.
    pub fn node_count(&self) -> usize {
        self.arena.node_count()
    }

    /// Leaf blocks.
    pub fn block_count(&self) -> usize {
        self.arena.block_count()
    }

    /// The hierarchy with its nodes and leaf blocks in separate arrays (a copy, made on each
    /// call): node references are node indices, root first, and leaf references block
    /// indices (with [`LEAF_BIT`]). For inspection, and for uploading to a GPU.
    pub fn indexed(&self) -> Indexed {
        self.arena.indexed(self.root)
    }

    /// Wide levels on the longest root-to-leaf path (0 when the root is a leaf or empty).
    pub fn depth(&self) -> usize {
        crate::node::depth(&self.arena, self.root)
    }

    /// Bytes of nodes and leaf blocks (with the padding that keeps nodes on cache lines).
    pub fn memory_bytes(&self) -> usize {
        self.arena.bytes()
    }
}
