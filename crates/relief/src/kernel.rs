//! Kernels: how a technique's computation runs, as opposed to which method it is. A method
//! may offer a vector kernel beside its scalar one; the choice is an option recorded with
//! every result, never a technique name of its own.

use std::fmt;
use std::str::FromStr;

/// A kernel a technique runs on: [`Kernel::Scalar`] marches one ray at a time on the
/// technique's own maps; [`Kernel::Simd`] marches rays in AVX2 vector lanes on the packed map
/// (with AVX-512 registers where present). Where the lanes cannot run on a map (sides not
/// powers of two), the scalar twin gives bit-identical results.
pub use renderlab_core::kernel::Kernel;

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
