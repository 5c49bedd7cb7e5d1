//! The relief lab's GPU phase on a small frame: both pipelines measured for every technique
//! and angle, each record with its steady timing; the CPU record's ratio is against the
//! faster pipeline's whole frame; `auto` probes once and says why; a CPU-only run has no GPU
//! columns. Without an adapter these tests fail when `CI` is set (CI installs lavapipe) and
//! are reported skipped otherwise.

use renderlab_gpu::{GpuContext, SteadySettings};
use renderlab_lab::relief_lab::{
    run_relief_bench, Backend, Method, PipelineSelection, RecordBackend, ReliefBenchConfig, ReliefSummary,
};
use renderlab_relief::{Kernel, KernelChoice, Technique};
use renderlab_texture::materials;

/// Whether an adapter opens here; without one, a skip outside CI and a failure under it.
fn adapter_or_skip() -> bool {
    match GpuContext::new() {
        Ok(_) => true,
        Err(e) => {
            assert!(std::env::var_os("CI").is_none(), "CI needs a GPU adapter (lavapipe): {e}");
            eprintln!("SKIPPED (no GPU adapter, and CI is not set): {e}");
            false
        }
    }
}

/// A short steady timing: batches of 2 frames, 2 measured rounds, at most 5 warm-up rounds.
const STEADY: SteadySettings = SteadySettings {
    batch: 2,
    rounds: 2,
    window: 3,
    tolerance: 0.03,
    max_warmup_rounds: 5,
    max_warmup_ms: 30_000.0,
};

fn run(backend: Backend, pipelines: PipelineSelection) -> ReliefSummary {
    let material = materials::material("bricks", 64).unwrap();
    let cfg = ReliefBenchConfig {
        width: 48,
        height: 30,
        angles: vec![0.0, 60.0],
        techniques: ["basic", "pom:8"]
            .into_iter()
            .map(|t| Method {
                technique: Technique::parse(t).unwrap(),
                kernel: KernelChoice::Exactly(Kernel::Scalar),
            })
            .collect(),
        warmup: 0,
        reps: 2,
        write_images: false,
        backend,
        pipelines,
        steady: STEADY,
        ..ReliefBenchConfig::default()
    };
    let dir = tempfile::tempdir().unwrap();
    run_relief_bench(&material, &cfg, dir.path(), &|_, _, _| {}).unwrap()
}

#[test]
fn both_pipelines_are_measured_with_their_steady_timing() {
    if !adapter_or_skip() {
        return;
    }
    let s = run(Backend::Both, PipelineSelection::Both);
    assert_eq!(s.gpu_pipelines, ["fragment", "compute"]);
    assert!(s.pipeline_probe.is_none(), "no probe when the pipelines are named");
    let (cpu, gpu): (Vec<_>, Vec<_>) = s.records.iter().partition(|r| r.backend == RecordBackend::Cpu);
    assert_eq!((cpu.len(), gpu.len()), (4, 8), "2 techniques × 2 angles, on the CPU and on 2 pipelines");
    for g in &gpu {
        let rounds = g.gpu_warmup_rounds.expect("warm-up rounds on GPU records");
        assert!(rounds <= STEADY.max_warmup_rounds, "{g:?}");
        assert!(!g.gpu_settled.expect("settled flag") || rounds >= STEADY.window, "{g:?}");
        assert_eq!(g.gpu_ms.is_some(), g.gpu_timestamps == Some(true), "{g:?}");
        if let (Some(lo), Some(mid), Some(hi)) = (g.gpu_min_ms, g.gpu_ms, g.gpu_max_ms) {
            assert!(0.0 < lo && lo <= mid && mid <= hi, "{g:?}");
        }
        assert!(g.cpu_over_gpu.is_some_and(|r| r.is_finite() && r > 0.0), "{g:?}");
    }
    for c in &cpu {
        assert!(c.pipeline.is_none() && c.gpu_settled.is_none() && c.gpu_spread.is_none());
        // The CPU frame over the faster pipeline's whole frame: the larger of the two ratios.
        let best = gpu
            .iter()
            .filter(|g| g.technique == c.technique && g.angle_deg == c.angle_deg)
            .filter_map(|g| g.cpu_over_gpu)
            .reduce(f64::max);
        assert_eq!(c.cpu_over_gpu, best, "{c:?}");
    }
    assert!(
        s.findings.iter().any(|f| f.starts_with("Compute pipeline / fragment pipeline")),
        "{:?}",
        s.findings
    );
    assert!(s.findings.iter().any(|f| f.starts_with("GPU timings")), "{:?}", s.findings);
    // What the GPU phases cost: at least the measured rounds' frames of 4 configurations at
    // 2 angles, and one whole frame per configuration and repetition.
    let cost = s.findings.iter().find(|f| f.starts_with("GPU phases: ")).expect("the GPU phases' cost");
    let frames: u64 = cost["GPU phases: ".len()..].split(' ').next().unwrap().parse().unwrap();
    assert!(frames >= (STEADY.rounds * STEADY.batch * 4 * 2) as u64, "{cost}");
    assert!(cost.contains("16 whole frames with read-back"), "{cost}");
}

#[test]
fn auto_probes_once_and_says_why() {
    if !adapter_or_skip() {
        return;
    }
    let s = run(Backend::Gpu, PipelineSelection::Auto);
    assert_eq!(s.gpu_pipelines.len(), 1);
    let reason = s.pipeline_probe.as_deref().expect("the probe's reason");
    assert!(reason.starts_with("pom:32 at 48×30"), "{reason}");
    assert!(s.records.iter().all(|r| r.pipeline == Some(s.gpu_pipelines[0])));
    assert!(s.findings.iter().any(|f| f.contains(reason)), "{:?}", s.findings);
}

#[test]
fn a_cpu_run_has_no_gpu_columns() {
    let s = run(Backend::Cpu, PipelineSelection::Both);
    assert!(s.gpu_pipelines.is_empty() && s.pipeline_probe.is_none());
    for r in &s.records {
        assert_eq!(r.backend, RecordBackend::Cpu);
        assert!(
            r.pipeline.is_none() && r.gpu_ms.is_none() && r.gpu_min_ms.is_none() && r.gpu_max_ms.is_none()
        );
        assert!(r.gpu_spread.is_none() && r.gpu_warmup_rounds.is_none() && r.gpu_settled.is_none());
        assert!(r.cpu_over_gpu.is_none());
    }
}
