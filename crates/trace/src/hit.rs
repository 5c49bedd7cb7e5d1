//! What a query returns, and DXR's any-hit shader as a filter.

/// The closest (or any) intersection of a ray.
///
/// `u` and `v` are DXR's barycentrics: the hit point is `v0 + u·(v1 − v0) + v·(v2 − v0)` for
/// the triangle's vertices in the order the mesh gave them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray, in units of its direction.
    pub t: f32,
    /// Weight of the triangle's second vertex.
    pub u: f32,
    /// Weight of the triangle's third vertex.
    pub v: f32,
    /// The triangle's index in its mesh.
    pub primitive: u32,
    /// The instance's index in the top level's instance list ([`Hit::NO_INSTANCE`] for a query
    /// on a single mesh).
    pub instance: u32,
}

impl Hit {
    /// The instance of a hit found by querying a bottom level directly.
    pub const NO_INSTANCE: u32 = u32::MAX;

    /// The three vertex weights `(1 − u − v, u, v)`.
    pub fn barycentrics(&self) -> [f32; 3] {
        [1.0 - self.u - self.v, self.u, self.v]
    }

    /// The order queries use to pick one hit among several: nearer first, and at equal
    /// distances the smaller instance, then the smaller primitive. This makes the closest hit
    /// independent of the order in which the hierarchy happens to offer candidates.
    #[inline(always)]
    pub fn precedes(t: f32, instance: u32, primitive: u32, other: &Hit) -> bool {
        t < other.t || (t == other.t && (instance, primitive) < (other.instance, other.primitive))
    }
}

/// DXR's any-hit shader: called for every candidate intersection that would be accepted, it
/// returns whether to accept it (an alpha-tested or translucent surface returns `false` to let
/// the ray pass). Closures `FnMut(&Hit) -> bool` are filters.
///
/// A triangle that the build cut ([`crate::Splits`]) lies in two leaves, so an any-hit query
/// may offer the same hit twice (as DXR may, unless a geometry asks for no duplicate any-hit
/// calls): a filter should decide by the hit, not count its calls.
pub trait HitFilter {
    /// Whether `hit` counts.
    fn accept(&mut self, hit: &Hit) -> bool;
}

impl<F: FnMut(&Hit) -> bool> HitFilter for F {
    #[inline(always)]
    fn accept(&mut self, hit: &Hit) -> bool {
        self(hit)
    }
}

/// The filter that accepts every hit (opaque geometry); it costs nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct Opaque;

impl HitFilter for Opaque {
    #[inline(always)]
    fn accept(&mut self, _: &Hit) -> bool {
        true
    }
}
