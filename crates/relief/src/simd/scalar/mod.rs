//! The scalar backend: each kernel of [`super::avx2`] one ray (or pixel) at a time, in the
//! file of the same name, performing each lane's IEEE operations in the same order, so the
//! results are bit-identical. It runs where the vector kernels cannot (no AVX2, a map whose
//! sides are not powers of two) and where a caller asks for it, for comparisons.

pub(crate) mod adaptive;
pub(crate) mod bisect;
pub(crate) mod cone;
pub(crate) mod cone_newton;
pub(crate) mod load;
pub(crate) mod parallax;
pub(crate) mod pom;
pub(crate) mod rays;
pub(crate) mod shade;
pub(crate) mod shadow;
