//! The marches the techniques are built from: the layered march and its interpolation, binary
//! refinement, relaxed cone stepping (with binary or secant refinement), Newton-finished cone
//! stepping on the packed map, POM's layer rules on the packed map, space leaping on the
//! min-depth pyramid, and the exact intersection used as the reference. Each is written once; the techniques in
//! [`crate::techniques`] choose and parameterise them, and the kernels in [`crate::simd`] run
//! the packed-map ones. What those kernels share sits here, below them: a ray's set-up
//! ([`ray`]), the layer rules ([`pom_lanes`], adaptive POM's in [`adaptive`]) and the cone
//! marches' lane state ([`cone_lanes`]).

pub mod adaptive;
pub mod bisect;
pub mod cone_lanes;
pub mod cone_newton;
pub mod cone_step;
pub mod exact;
pub mod layered;
pub mod leap;
pub mod pom_lanes;
pub mod ray;
