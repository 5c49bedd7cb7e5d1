//! What the BVH benchmarks share beyond the workload (`renderlab_trace::workload`, re-exported
//! here): per-thread CPU time and the machine's load.

#![allow(dead_code)]

pub use renderlab_trace::workload::*;
use std::time::Duration;

/// This thread's CPU time (so that other processes sharing the cores do not count).
pub fn thread_cpu() -> Duration {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `ts` is a valid timespec to write to.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

/// The load average over 1, 5 and 15 minutes.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}
