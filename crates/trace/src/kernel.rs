//! Kernels: how a query's arithmetic runs. [`Kernel::Scalar`] tests one child box and one
//! triangle at a time; [`Kernel::Simd`] tests eight child boxes in one AVX2 register and four
//! triangles in one SSE register, with fused multiply-adds where the scalar test calls
//! `f32::mul_add`, so it needs FMA beside AVX2 ([`available`]). Both give bit-identical hits;
//! the choice is recorded with results, never a method of its own. The type is shared with the
//! relief kernels (`renderlab_core::kernel`).

pub use renderlab_core::kernel::{has_avx2, Kernel};

/// Whether this CPU runs the trace crate's `kernel`: [`Kernel::available`], and for
/// [`Kernel::Simd`] also FMA.
pub fn available(kernel: Kernel) -> bool {
    kernel.available() && (kernel == Kernel::Scalar || has_fma())
}

/// The fastest kernel this CPU runs the queries on.
pub fn best() -> Kernel {
    if available(Kernel::Simd) {
        Kernel::Simd
    } else {
        Kernel::Scalar
    }
}

/// Whether the vector kernel may be compiled with AVX-512's registers: the CPU has AVX-512 F
/// and VL, and the environment variable [`NO_AVX512`] is not set (it selects the plain AVX2
/// copy on such CPUs, to test or time it). Read once, on the first query.
#[inline]
pub fn wide_registers() -> bool {
    static WIDE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *WIDE.get_or_init(|| renderlab_core::kernel::has_avx512() && std::env::var_os(NO_AVX512).is_none())
}

/// The environment variable that keeps the vector kernel to its AVX2 copy on AVX-512 CPUs.
pub const NO_AVX512: &str = "RENDERLAB_NO_AVX512";

/// Whether the AVX-512 kernel tests a packet's nodes child by child, sixteen rays to a
/// register ([`crate::traverse::avx512`]): on Intel processors, whose AVX-512 cores execute
/// 512-bit operations at full width, and not on others (AMD's Zen 4 splits them in two, where
/// it measured 8 % slower than ray by ray). The environment variable [`CHILD_BY_CHILD`] set to
/// `1` or `0` overrides the choice, to test or time either. Read once; both give the same hits.
#[inline]
pub fn child_by_child() -> bool {
    static BY_CHILD: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *BY_CHILD.get_or_init(|| match std::env::var(CHILD_BY_CHILD).as_deref() {
        Ok("1") => true,
        Ok("0") => false,
        _ => renderlab_core::kernel::intel(),
    })
}

/// The environment variable that overrides [`child_by_child`] (`1` or `0`).
pub const CHILD_BY_CHILD: &str = "RENDERLAB_CHILD_BY_CHILD";

/// Whether the CPU has fused multiply-add instructions.
fn has_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}
