//! Kernels: how a query's arithmetic runs (scalar code or AVX2 lanes), chosen at run time. Both
//! give bit-identical hits; the choice is recorded with results, never a method of its own.

use std::fmt;
use std::str::FromStr;

/// A traversal kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kernel {
    /// One child box and one triangle at a time, in portable code.
    Scalar,
    /// Eight child boxes in one AVX2 register, four triangles in one SSE register.
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

    /// Whether this CPU runs the kernel.
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

/// Whether the CPU has AVX2 (the vector kernel's baseline).
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
