//! The shading kernel's contract: eight pixels' inputs in arrays ([`ShadeLanes`]) and the
//! constants of a material and frame ([`ShadeConsts`]). The kernels that shade them, scalar
//! and vector, are `crate::simd`'s (`shade_lanes`).

use super::texture8::Texture8;
use crate::trace::{ReliefHit, Shading};
use renderlab_core::srgb8::ENCODE_BUCKETS;
use renderlab_core::ShadePoint;

/// Pixels per kernel call.
pub const LANES: usize = 8;

/// Eight pixels' shading inputs, one array per quantity (the layout the vector kernel loads).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(32))]
pub struct ShadeLanes {
    /// Displaced texture coordinate, u (unwrapped; the textures repeat).
    pub u: [f32; LANES],
    /// Displaced texture coordinate, v.
    pub v: [f32; LANES],
    /// ∂u/∂x of the pixel's footprint.
    pub dudx: [f32; LANES],
    /// ∂v/∂x.
    pub dvdx: [f32; LANES],
    /// ∂u/∂y.
    pub dudy: [f32; LANES],
    /// ∂v/∂y.
    pub dvdy: [f32; LANES],
    /// Unit vector toward the light in tangent space, x.
    pub lx: [f32; LANES],
    /// … y.
    pub ly: [f32; LANES],
    /// … z.
    pub lz: [f32; LANES],
    /// Unit vector toward the eye in tangent space, x.
    pub vx: [f32; LANES],
    /// … y.
    pub vy: [f32; LANES],
    /// … z.
    pub vz: [f32; LANES],
    /// Light reaching the point, in [0, 1] (1 without self-shadowing).
    pub shadow: [f32; LANES],
}

/// What is the same for every pixel of a material in a frame.
#[derive(Clone, Copy)]
pub struct ShadeConsts<'a> {
    /// Albedo, sRGB-encoded.
    pub albedo: &'a Texture8,
    /// Tangent-space normals, unorm-encoded.
    pub normal: &'a Texture8,
    /// Unlit (albedo only) or lit.
    pub shading: Shading,
    /// Ambient factor.
    pub ambient: f32,
    /// Blinn–Phong exponent.
    pub exponent: f32,
    /// Blinn–Phong strength.
    pub strength: f32,
    /// The sRGB encoding table.
    pub encode: &'a [u32; ENCODE_BUCKETS],
}

impl ShadeConsts<'_> {
    /// The exponent as a whole number, when it is one in [0, 256] (then raised by squaring;
    /// otherwise by `powf` per lane).
    #[inline]
    pub fn whole_exponent(&self) -> Option<u32> {
        let e = self.exponent;
        ((0.0..=256.0).contains(&e) && e == e.trunc()).then_some(e as u32)
    }
}

impl ShadeLanes {
    /// Lane `i` from a traced pixel.
    #[inline]
    pub(crate) fn set(&mut self, i: usize, hit: &ReliefHit, sp: &ShadePoint, shadow: f32) {
        self.u[i] = hit.uv.x;
        self.v[i] = hit.uv.y;
        self.dudx[i] = sp.duv_dx.x;
        self.dvdx[i] = sp.duv_dx.y;
        self.dudy[i] = sp.duv_dy.x;
        self.dvdy[i] = sp.duv_dy.y;
        self.lx[i] = sp.light_ts.x;
        self.ly[i] = sp.light_ts.y;
        self.lz[i] = sp.light_ts.z;
        self.vx[i] = sp.view_ts.x;
        self.vy[i] = sp.view_ts.y;
        self.vz[i] = sp.view_ts.z;
        self.shadow[i] = shadow;
    }

    /// Fills lanes `n..` with lane `n − 1` (a partial group computes valid values there,
    /// which are not written out).
    #[inline]
    pub(crate) fn pad(&mut self, n: usize) {
        for a in [
            &mut self.u,
            &mut self.v,
            &mut self.dudx,
            &mut self.dvdx,
            &mut self.dudy,
            &mut self.dvdy,
            &mut self.lx,
            &mut self.ly,
            &mut self.lz,
            &mut self.vx,
            &mut self.vy,
            &mut self.vz,
            &mut self.shadow,
        ] {
            let last = a[n - 1];
            a[n..].fill(last);
        }
    }
}
