//! Kernels: how a query's arithmetic runs. [`Kernel::Scalar`] tests one child box and one
//! triangle at a time; [`Kernel::Simd`] tests eight child boxes in one AVX2 register and four
//! triangles in one SSE register. Both give bit-identical hits; the choice is recorded with
//! results, never a method of its own. The type is shared with the relief kernels
//! (`renderlab_core::kernel`).

pub use renderlab_core::kernel::{has_avx2, Kernel};
