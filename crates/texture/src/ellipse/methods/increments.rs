//! The per-polygon constants of (2.16)–(2.19) that the incremental and analytic methods share.

use crate::mapping::ops::OpCounter;
use crate::mapping::Coeffs;

/// Per-polygon constants shared by the incremental and analytic methods: the numerators are
/// `M·y + (AI − CG)`, `N·y + (DI − FG)` for the x-derivatives and `O·x + (BI − CH)`,
/// `P·x + (EI − FH)` for the y-derivatives.
#[derive(Clone, Copy, Debug)]
pub(super) struct Increments {
    pub(super) m: f32,
    pub(super) n: f32,
    pub(super) o: f32,
    pub(super) p: f32,
    pub(super) ux0: f32,
    pub(super) vx0: f32,
    pub(super) uy0: f32,
    pub(super) vy0: f32,
}

impl Increments {
    pub(super) fn new<O: OpCounter>(c: &Coeffs, ops: &mut O) -> Self {
        ops.mul(16);
        ops.sub(8);
        let m = c.a * c.h - c.b * c.g; // (2.16)
        let n = c.d * c.h - c.e * c.g; // (2.17), as the thesis states its value
        Increments {
            m,
            n,
            o: c.b * c.g - c.a * c.h, // (2.18)
            p: c.e * c.g - c.d * c.h, // (2.19)
            ux0: c.a * c.i - c.c * c.g,
            vx0: c.d * c.i - c.f * c.g,
            uy0: c.b * c.i - c.c * c.h,
            vy0: c.e * c.i - c.f * c.h,
        }
    }
}
