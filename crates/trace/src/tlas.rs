//! The top level: an 8-wide BVH over instances (a mesh placed by an affine transform), like
//! DXR's top-level acceleration structure. A ray reaching an instance's leaf is carried into
//! the mesh's space by the instance's world-to-object transform and continues in the mesh's
//! bottom level with the same distances.

use crate::aabb::Aabb;
use crate::blas::Blas;
use crate::build::binned::{self, PrimRef, SahParams, MAX_PRIMS};
use crate::build::collapse::collapse;
use crate::error::BuildError;
use crate::kernel::Kernel;
use crate::node::{WideNode, LEAF_BIT};
use glam::Affine3A;

/// The SAH of the top level: one instance per leaf, a node visit priced as an instance visit.
pub const TLAS_SAH: SahParams = SahParams { max_leaf: 1, block: 1, traversal_cost: 1.0 };

/// A mesh placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Index of the mesh in the list given to [`Tlas::build`].
    pub mesh: u32,
    /// Object to world.
    pub object_to_world: Affine3A,
}

impl Instance {
    /// An instance of `mesh` placed by `object_to_world`.
    pub fn new(mesh: u32, object_to_world: Affine3A) -> Instance {
        Instance { mesh, object_to_world }
    }

    /// World to object, or `None` when the transform is not finite or not invertible; such an
    /// instance is never hit (like a zero-scale instance in DXR).
    pub fn world_to_object(&self) -> Option<Affine3A> {
        let m = &self.object_to_world;
        let det = m.matrix3.determinant();
        if !(m.is_finite() && det.is_finite() && det != 0.0) {
            return None;
        }
        let inv = m.inverse();
        inv.is_finite().then_some(inv)
    }
}

/// An instance as the queries see it (and as a GPU copy of the structure needs it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// Index of the instance's mesh in [`Tlas::meshes`].
    pub mesh: u32,
    /// World to object (the identity for an instance that is never hit).
    pub world_to_object: Affine3A,
    /// Object to world, as given to the build.
    pub object_to_world: Affine3A,
    /// Whether the instance is in the hierarchy (an invertible transform and a mesh with
    /// something to hit): only these are ever hit.
    pub live: bool,
}

/// The scene's acceleration structure: its meshes' bottom levels and a top level over the
/// instances. Instance `i` of the list given to [`Tlas::build`] reports `instance == i`.
#[derive(Clone, Debug)]
pub struct Tlas {
    pub(crate) meshes: Vec<Blas>,
    pub(crate) placed: Vec<Placed>,
    pub(crate) nodes: Vec<WideNode>,
    pub(crate) root: u32,
    pub(crate) kernel: Kernel,
    bounds: Aabb,
    live: usize,
}

impl Tlas {
    /// Builds the top level over `instances` of `meshes`. Instances whose transform is not
    /// invertible or whose mesh has nothing to hit are left out of the hierarchy.
    pub fn build(meshes: Vec<Blas>, instances: &[Instance]) -> Result<Tlas, BuildError> {
        if instances.len() > MAX_PRIMS {
            return Err(BuildError::TooMany { what: "instances", count: instances.len(), limit: MAX_PRIMS });
        }
        let mut placed = Vec::with_capacity(instances.len());
        let mut refs = Vec::with_capacity(instances.len());
        for (i, inst) in instances.iter().enumerate() {
            let Some(blas) = meshes.get(inst.mesh as usize) else {
                return Err(BuildError::MeshOutOfRange {
                    instance: i,
                    mesh: inst.mesh,
                    meshes: meshes.len(),
                });
            };
            let w2o = inst.world_to_object();
            let mut live = false;
            if let Some(bounds) = w2o.map(|_| blas.bounds().transformed(&inst.object_to_world)) {
                if !bounds.is_empty() && bounds.min.is_finite() && bounds.max.is_finite() {
                    refs.push(PrimRef::new(&bounds, i as u32));
                    live = true;
                }
            }
            placed.push(Placed {
                mesh: inst.mesh,
                world_to_object: w2o.unwrap_or(Affine3A::IDENTITY),
                object_to_world: inst.object_to_world,
                live,
            });
        }
        let live = refs.len();
        let bvh = binned::build(refs, &TLAS_SAH);
        let (nodes, root) = collapse(&bvh, &mut |leaf: &[PrimRef]| LEAF_BIT | leaf[0].index());
        let bounds = if live == 0 { Aabb::EMPTY } else { bvh.nodes[0].bounds() };
        Ok(Tlas { meshes, placed, nodes, root, kernel: crate::kernel::best(), bounds, live })
    }

    /// The same structure queried with `kernel` (the scalar kernel where the CPU lacks it).
    pub fn with_kernel(mut self, kernel: Kernel) -> Tlas {
        self.kernel = if crate::kernel::available(kernel) { kernel } else { Kernel::Scalar };
        self
    }

    /// The kernel queries run on.
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }

    /// The meshes' bottom levels.
    pub fn meshes(&self) -> &[Blas] {
        &self.meshes
    }

    /// Instances given to the build.
    pub fn instance_count(&self) -> usize {
        self.placed.len()
    }

    /// Instances in the hierarchy (those that can be hit).
    pub fn live_instance_count(&self) -> usize {
        self.live
    }

    /// The world bounds of the instances in the hierarchy.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Top-level wide levels on the longest path (0 when the root is a leaf or empty).
    pub fn depth(&self) -> usize {
        crate::node::depth(self.nodes.as_slice(), self.root)
    }

    /// Top-level wide nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The top level's wide nodes (leaf references are instance indices), for inspection and
    /// for uploading to a GPU.
    pub fn nodes(&self) -> &[WideNode] {
        &self.nodes
    }

    /// The top level's root reference: node 0, a leaf (a single instance) or
    /// [`crate::node::EMPTY`].
    pub fn root(&self) -> u32 {
        self.root
    }

    /// The instances in the order given to the build (instance `i` reports `instance == i`).
    pub fn placed(&self) -> &[Placed] {
        &self.placed
    }
}
