//! One of the analytic shapes, chosen at run time ([`AnyShape`]), for views that mix them.

use super::cylinder::Cylinder;
use super::patch::Patch;
use super::shape::{Geometry, ReliefShape};
use super::sphere::Sphere;
use glam::{DVec2, DVec3};

/// One of the analytic shapes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AnyShape {
    /// A sphere.
    Sphere(Sphere),
    /// A cylinder.
    Cylinder(Cylinder),
    /// A finite flat patch.
    Patch(Patch),
}

macro_rules! each_shape {
    ($self:ident, $s:ident => $e:expr) => {
        match $self {
            AnyShape::Sphere($s) => $e,
            AnyShape::Cylinder($s) => $e,
            AnyShape::Patch($s) => $e,
        }
    };
}

impl ReliefShape for AnyShape {
    fn world_per_uv(&self) -> f64 {
        each_shape!(self, s => s.world_per_uv())
    }
    fn uv_rect(&self) -> (DVec2, DVec2) {
        each_shape!(self, s => s.uv_rect())
    }
    fn intersect(&self, o: DVec3, d: DVec3) -> Option<(f64, DVec2)> {
        each_shape!(self, s => s.intersect(o, d))
    }
    fn geometry(&self, uv: DVec2) -> Geometry {
        each_shape!(self, s => s.geometry(uv))
    }
    fn span(&self, o: DVec3, d: DVec3, thickness: f64) -> Option<(f64, f64)> {
        each_shape!(self, s => s.span(o, d, thickness))
    }
    fn locate(&self, x: DVec3, hint: DVec2) -> Option<(DVec2, f64)> {
        each_shape!(self, s => s.locate(x, hint))
    }
}
