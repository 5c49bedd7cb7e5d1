//! Traversal: one generic walk ([`walk`]) over a backend trait ([`backend`]) with four
//! implementations, [`scalar`], [`avx2`] (with its ray form, [`avx2_ray`]), [`avx2_single`] (the
//! AVX2 kernel's tests with a single ray's form made straight from the ray) and [`avx512`] (the
//! AVX2 kernel with a sixteen-ray packet node test), that compute bit-identical node and
//! triangle results; [`leaves`] says what a leaf is in each level; [`packet`] walks several
//! rays together over the same kernels and [`packet_leaves`] says what a leaf is to it;
//! [`dispatch`] picks the kernel.

pub mod avx2;
pub mod avx2_ray;
pub mod avx2_single;
pub mod avx512;
pub mod backend;
pub mod dispatch;
pub mod leaves;
pub mod packet;
pub mod packet_leaves;
pub mod scalar;
pub mod walk;
