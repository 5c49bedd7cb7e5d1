//! What the GPU tests share: opening the device, or saying why a test cannot run.

use renderlab_gpu::rt::RtPath;
use renderlab_gpu::GpuContext;

/// Opens the device. Without one, a test fails with the reason when the environment variable
/// `CI` is set (CI installs lavapipe, so a missing adapter there is a broken set-up), and
/// otherwise reports itself skipped and passes: cargo has no "skipped" outcome, so the skip
/// is printed, never silent.
pub fn context() -> Option<GpuContext> {
    match GpuContext::new() {
        Ok(c) => Some(c),
        Err(e) if std::env::var_os("CI").is_some() => {
            panic!("CI is set but the GPU tests cannot run: {e}")
        }
        Err(e) => {
            eprintln!("SKIPPED (no GPU adapter, and CI is not set): {e}");
            None
        }
    }
}

/// The ray-tracing paths this device runs: the compute path always, the query path where the
/// device has ray queries; a path left out is printed as skipped, never silently.
pub fn paths(ctx: &GpuContext, test: &str) -> Vec<RtPath> {
    RtPath::ALL
        .into_iter()
        .filter(|p| {
            let ok = p.available(ctx);
            if !ok {
                eprintln!("SKIPPED {test} for the {p} path: {} has no ray queries", ctx.report);
            }
            ok
        })
        .collect()
}
