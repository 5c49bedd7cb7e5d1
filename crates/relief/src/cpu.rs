//! Run-time CPU-feature detection for the vector kernels of [`crate::simd`] (shared with the
//! other crates' vector kernels through `renderlab_core::kernel`).

pub use renderlab_core::kernel::{has_avx2, has_avx512};
