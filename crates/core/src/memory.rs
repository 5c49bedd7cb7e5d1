//! The memory budget every run is held to. Each renderer fits its peak resident memory to
//! measurements (`renderlab_hybrid::memory`, `renderlab_relief::memory`; BENCHMARKS.md,
//! "Memory") and refuses, before any work, a size whose estimate exceeds this budget, so that
//! an accepted size never aborts in an allocation halfway.

/// The most a run's estimated peak resident memory may be: 8 GiB, which leaves room on a
/// 16 GB machine for the system and the page cache.
pub const BUDGET: u64 = 8 << 30;

/// `bytes` in GiB, for messages.
pub fn gib(bytes: u64) -> f64 {
    bytes as f64 / (1u64 << 30) as f64
}
