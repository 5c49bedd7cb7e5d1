//! Kernels: how a technique's computation runs, as opposed to which method it is. A method
//! may offer a vector kernel beside its scalar one; the choice is an option recorded with
//! every result, never a technique name of its own.

use crate::cpu::has_avx2;
use std::fmt;
use std::str::FromStr;

/// A kernel a technique runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kernel {
    /// One ray at a time in scalar code, on the technique's own maps.
    Scalar,
    /// Rays in AVX2 vector lanes on the packed map (with AVX-512 registers where present).
    /// Where the lanes cannot run on a map (sides not powers of two), its scalar twin gives
    /// bit-identical results.
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
}

impl fmt::Display for Kernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl serde::Serialize for Kernel {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

/// The kernel a user asks for: a kernel, or the fastest one the technique and the CPU offer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum KernelChoice {
    /// The fastest kernel the technique offers and this CPU runs.
    #[default]
    Auto,
    /// Exactly this kernel.
    Exactly(Kernel),
}

/// Syntax of [`KernelChoice`] for help texts and errors.
pub const KERNEL_CHOICES: &str = "auto, scalar, simd";

impl FromStr for KernelChoice {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(KernelChoice::Auto),
            "scalar" => Ok(KernelChoice::Exactly(Kernel::Scalar)),
            "simd" => Ok(KernelChoice::Exactly(Kernel::Simd)),
            _ => Err(format!("unknown kernel '{s}' (known: {KERNEL_CHOICES})")),
        }
    }
}

impl fmt::Display for KernelChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KernelChoice::Auto => f.write_str("auto"),
            KernelChoice::Exactly(k) => f.write_str(k.name()),
        }
    }
}
