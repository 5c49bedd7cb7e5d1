//! What the BVH benchmarks share beyond the workload (`renderlab_trace::workload`, re-exported
//! here): per-thread CPU time, the machine's load, and the one-mesh-or-instances hierarchy the
//! Embree comparison and its profiling example trace ([`Accel`]).

#![allow(dead_code)]

// (Not every includer uses the workload: `profile_set` reads its scenes from files.)
#[allow(unused_imports)]
pub use renderlab_trace::workload::*;
use renderlab_trace::{Blas, Hit, Ray, Tlas, PACKET};
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

/// What we trace: one mesh's hierarchy, or a two-level scene of instances of one mesh of
/// `triangles` triangles, whose hits are numbered as in the flattened mesh
/// (instance · triangles + triangle) to compare with Embree's.
pub enum Accel {
    /// One mesh's hierarchy.
    Mesh(Blas),
    /// Instances of one mesh, and the mesh's triangle count.
    Scene(Tlas, u32),
}

impl Accel {
    /// `hit` numbered as in the flattened mesh.
    pub fn number(&self, hit: Option<Hit>) -> Option<Hit> {
        match self {
            Accel::Mesh(_) => hit,
            Accel::Scene(_, n) => hit.map(|h| Hit { primitive: h.instance * n + h.primitive, ..h }),
        }
    }

    /// The closest hit of `r`.
    pub fn closest_hit(&self, r: &Ray) -> Option<Hit> {
        match self {
            Accel::Mesh(b) => b.closest_hit(r),
            Accel::Scene(t, _) => self.number(t.closest_hit(r)),
        }
    }

    /// Whether anything lies on `r`.
    pub fn any_hit(&self, r: &Ray) -> bool {
        match self {
            Accel::Mesh(b) => b.any_hit(r),
            Accel::Scene(t, _) => t.any_hit(r),
        }
    }

    /// The closest hits of a packet.
    pub fn closest_packet(&self, rays: &[Ray]) -> [Option<Hit>; PACKET] {
        match self {
            Accel::Mesh(b) => b.closest_packet(rays),
            Accel::Scene(t, _) => t.closest_packet(rays).map(|h| self.number(h)),
        }
    }

    /// Whether anything lies on each ray of a packet.
    pub fn any_packet(&self, rays: &[Ray]) -> [bool; PACKET] {
        match self {
            Accel::Mesh(b) => b.any_packet(rays),
            Accel::Scene(t, _) => t.any_packet(rays),
        }
    }
}
