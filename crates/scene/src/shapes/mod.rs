//! Meshes and scenes built in code, for the built-in scenes and for the tests, examples and
//! benchmarks: rectangles, boxes and wedges (flat faces), surfaces of revolution with
//! creases (spheres, shafts, vases, bowls, hulls), tori, height fields and a closed water
//! slab, and a [`SceneBuilder`] that places them with materials, lights and cameras.
//!
//! Conventions: every generator returns a mesh counter-clockwise seen from outside (its
//! front), with normals, UVs and tangents. Generators of closed solids (everything except
//! [`quad`] and [`height_field`]) produce meshes in which every edge is shared by exactly
//! two triangles when vertices are identified by position, so that a ray entering them
//! always leaves them: the refraction stage relies on that for glass and water. Degenerate
//! triangles (the collapsed half of a quad at a pole) are never emitted.
//!
//! Where two ways of building one shape exist ([`cuboid`] and [`sphere`]), one parameter
//! ([`CuboidUv`], [`SphereStyle`]) chooses, so that every scene keeps the exact mesh its
//! images were made with.
//!
//! Layout: `mesh.rs` (the mesh builder and operations on meshes), `solids.rs` (flat-faced
//! shapes), `revolution.rs` (lathed shapes, spheres, torus), `terrain.rs` (height fields),
//! `scene_builder.rs` (the scene builder).

mod mesh;
mod revolution;
mod scene_builder;
mod solids;
mod terrain;

pub use mesh::{signed_volume, translated, MeshBuilder};
pub use revolution::{cylinder, lathe, sphere, torus, SphereStyle};
pub use scene_builder::{light, SceneBuilder};
pub use solids::{arch, cuboid, hexahedron, quad, stairs, CuboidUv};
pub use terrain::{height_field, water_slab};
