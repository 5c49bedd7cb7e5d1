//! Kernels: how a computation runs (portable scalar code or vector lanes), as opposed to which
//! method it is. The relief techniques and the BVH traversal both offer a vector kernel beside
//! their scalar one, chosen at run time from the CPU's features; the choice is an option
//! recorded with every result, never a method of its own. Each crate says what its lanes hold
//! and how its kernels agree (bit-identical, or within a stated bound).

use std::fmt;
use std::str::FromStr;

/// A kernel a computation runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kernel {
    /// Portable scalar code, one item at a time.
    Scalar,
    /// AVX2 vector lanes (compiled with AVX-512's 32 registers where the CPU has them).
    Simd,
}

impl Kernel {
    /// Every kernel, slowest first.
    pub const ALL: [Kernel; 2] = [Kernel::Scalar, Kernel::Simd];

    /// The kernel's name (`scalar`, `simd`).
    pub fn name(self) -> &'static str {
        match self {
            Kernel::Scalar => "scalar",
            Kernel::Simd => "simd",
        }
    }

    /// Whether this CPU can run the kernel.
    pub fn available(self) -> bool {
        match self {
            Kernel::Scalar => true,
            Kernel::Simd => has_avx2(),
        }
    }

    /// The fastest kernel this CPU runs.
    pub fn best() -> Kernel {
        if Kernel::Simd.available() {
            Kernel::Simd
        } else {
            Kernel::Scalar
        }
    }
}

impl fmt::Display for Kernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Kernel {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "scalar" => Ok(Kernel::Scalar),
            "simd" => Ok(Kernel::Simd),
            _ => Err(format!("unknown kernel '{s}' (known: scalar, simd)")),
        }
    }
}

impl serde::Serialize for Kernel {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

/// Whether the CPU has AVX2 (the vector kernels' baseline).
#[inline]
pub fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Whether the CPU has AVX-512 F and VL: vector kernels can then be compiled with 32 vector
/// registers, so that their lanes' state need not spill.
#[inline]
pub fn has_avx512() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512vl")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Whether the CPU is Intel's (its CPUID vendor string, "GenuineIntel"): for choices that
/// depend on how a core executes 512-bit operations (Intel's AVX-512 cores at full width,
/// AMD's Zen 4 in two halves), where a feature flag does not tell.
pub fn intel() -> bool {
    vendor() == *b"GenuineIntel"
}

/// The CPU's vendor string as CPUID leaf 0 gives it (EBX, EDX, ECX); zeros off x86-64.
fn vendor() -> [u8; 12] {
    // (Written only on x86-64.)
    #[allow(unused_mut)]
    let mut v = [0u8; 12];
    #[cfg(target_arch = "x86_64")]
    {
        let id = std::arch::x86_64::__cpuid(0);
        for (i, word) in [id.ebx, id.edx, id.ecx].into_iter().enumerate() {
            v[4 * i..4 * i + 4].copy_from_slice(&word.to_le_bytes());
        }
    }
    v
}

/// AVX2 building blocks that the vector kernels of several crates share (the raster's
/// eight-pixel resolve, the relief kernels' lane loads).
#[cfg(target_arch = "x86_64")]
pub mod avx2 {
    use std::arch::x86_64::*;

    /// Rows `a`, `b`, `c`, `d` to columns within each 128-bit half: element `i` of result `j`
    /// is element `j` of input `i`, lanes 0–3 in the low halves and 4–7 in the high ones (the
    /// halves transposed apart).
    ///
    /// # Safety
    ///
    /// The CPU must support AVX2.
    #[inline]
    #[target_feature(enable = "avx2")]
    pub unsafe fn transpose_halves(a: __m256, b: __m256, c: __m256, d: __m256) -> [__m256; 4] {
        let (ab_lo, ab_hi) = (_mm256_unpacklo_ps(a, b), _mm256_unpackhi_ps(a, b));
        let (cd_lo, cd_hi) = (_mm256_unpacklo_ps(c, d), _mm256_unpackhi_ps(c, d));
        [
            _mm256_shuffle_ps::<0x44>(ab_lo, cd_lo),
            _mm256_shuffle_ps::<0xee>(ab_lo, cd_lo),
            _mm256_shuffle_ps::<0x44>(ab_hi, cd_hi),
            _mm256_shuffle_ps::<0xee>(ab_hi, cd_hi),
        ]
    }
}

#[cfg(test)]
mod tests {

    /// The vendor check agrees with the kernel's own account of the CPU (Linux's
    /// `/proc/cpuinfo`), where there is one.
    #[test]
    fn intel_matches_the_vendor_the_kernel_reports() {
        let Ok(info) = std::fs::read_to_string("/proc/cpuinfo") else { return };
        let Some(vendor) = info.lines().find_map(|l| l.strip_prefix("vendor_id")) else { return };
        let vendor = vendor.trim_start_matches([' ', '\t', ':']).trim();
        assert_eq!(std::str::from_utf8(&super::vendor()), Ok(vendor));
        assert_eq!(super::intel(), vendor == "GenuineIntel", "vendor_id {vendor:?}");
    }
    use super::*;

    #[test]
    fn names_parse_back_and_scalar_always_runs() {
        for k in Kernel::ALL {
            assert_eq!(k.name().parse::<Kernel>(), Ok(k));
        }
        assert!(Kernel::Scalar.available());
        assert!(Kernel::best().available());
        assert!("avx".parse::<Kernel>().unwrap_err().contains("known: scalar, simd"));
    }
}
