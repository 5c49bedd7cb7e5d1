//! Traversal: one generic walk ([`walk`]) over a backend trait ([`backend`]) with two
//! implementations, [`scalar`] and [`avx2`] (with its ray form, [`avx2_ray`]), that compute
//! bit-identical node and triangle results; [`leaves`] says what a leaf is in each level; [`packet`] walks several rays
//! together over the same kernels and [`packet_leaves`] says what a leaf is to it; [`dispatch`] picks the kernel.

pub mod avx2;
pub mod avx2_ray;
pub mod backend;
pub mod dispatch;
pub mod leaves;
pub mod packet;
pub mod packet_leaves;
pub mod scalar;
pub mod walk;
