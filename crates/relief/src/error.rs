//! Typed errors of the relief crate: what a caller asked for that cannot run, named so that
//! the command-line tool can print it as one line.

/// A technique that cannot run on the given inputs or on this CPU.
#[derive(Debug, thiserror::Error)]
pub enum ReliefError {
    /// A precomputed map the technique reads was not built.
    #[error("{technique} needs the {map}, which material '{material}' lacks")]
    MissingMap {
        /// The technique's name.
        technique: String,
        /// The map's name.
        map: &'static str,
        /// The material without it.
        material: String,
    },
    /// The technique has no such kernel.
    #[error("{technique} has no {kernel} kernel (it has: {have})")]
    NoKernel {
        /// The technique's name.
        technique: String,
        /// The kernel asked for.
        kernel: &'static str,
        /// The kernels it has.
        have: String,
    },
    /// This CPU cannot run the kernel.
    #[error("the {kernel} kernel needs AVX2, which this CPU lacks (use --kernel scalar or auto)")]
    KernelUnavailable {
        /// The kernel asked for.
        kernel: &'static str,
    },
}
