//! The AVX2 backend (the marches compiled a second time with AVX-512 F and VL where the CPU
//! has them, for 32 vector registers): the packed-map gather and the kernels built on it.
//! Every kernel gives results bit-identical to its scalar twin, the file of the same name in
//! [`super::scalar`]. Three files are this backend's own helpers, with no twin: [`gather`]
//! (the scalar kernels read `PackedRelief::sample_texel`), [`math`] (the scalar kernels use
//! `renderlab_core::fastmath`) and [`lanes`] (the cone kernels' lanes; the scalar kernels
//! step one [`crate::march::cone_lanes::State`]).

pub(crate) mod adaptive;
pub(crate) mod bisect;
pub(crate) mod cone;
pub(crate) mod cone_newton;
pub(crate) mod gather;
pub(crate) mod lanes;
pub(crate) mod load;
pub(crate) mod math;
pub(crate) mod parallax;
pub(crate) mod pom;
pub(crate) mod rays;
pub(crate) mod shade;
pub(crate) mod shadow;

/// Rays in one vector.
pub const LANES: usize = 8;

/// For each 8-bit mask, each set bit's rank among the set bits (0 elsewhere): where a free
/// lane takes its ray from among the row's next ones.
pub(crate) static RANKS: [[i32; LANES]; 256] = {
    let mut r = [[0i32; LANES]; 256];
    let mut m = 0;
    while m < 256 {
        let mut rank = 0;
        let mut l = 0;
        while l < LANES {
            if m & (1 << l) != 0 {
                r[m][l] = rank;
                rank += 1;
            }
            l += 1;
        }
        m += 1;
    }
    r
};
