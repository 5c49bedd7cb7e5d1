//! The relief lab on a machine without a GPU adapter (hidden from Vulkan's loader, which reads
//! its driver list from the environment; this file holds one test so that the setting cannot
//! reach another test's process): a run that asks for the GPU fails with the adapter named,
//! and the report's run, which must work anywhere, says the GPU was skipped and still writes
//! its CPU records and page.

use renderlab_lab::relief_lab::{run_relief_bench, Backend, Method, RecordBackend, ReliefBenchConfig};
use renderlab_relief::{Kernel, KernelChoice, Technique};
use renderlab_texture::materials;

#[test]
fn without_an_adapter_gpu_runs_fail_and_optional_ones_say_skipped() {
    std::env::set_var("VK_ICD_FILENAMES", "/nonexistent.json");
    std::env::set_var("VK_DRIVER_FILES", "/nonexistent.json");
    let material = materials::material("bricks", 64).unwrap();
    let cfg = |backend, gpu_required| ReliefBenchConfig {
        width: 32,
        height: 20,
        angles: vec![0.0],
        techniques: vec![Method {
            technique: Technique::parse("pom:8").unwrap(),
            kernel: KernelChoice::Exactly(Kernel::Scalar),
        }],
        warmup: 0,
        reps: 1,
        write_images: false,
        backend,
        gpu_required,
        ..ReliefBenchConfig::default()
    };
    for backend in [Backend::Gpu, Backend::Both] {
        let dir = tempfile::tempdir().unwrap();
        let e = run_relief_bench(&material, &cfg(backend, true), dir.path(), &|_, _, _| {}).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("adapter") && !msg.contains('\n'), "{msg}");
        assert!(!dir.path().join("results.json").exists(), "nothing written after the error");
    }
    let dir = tempfile::tempdir().unwrap();
    let s = run_relief_bench(&material, &cfg(Backend::Both, false), dir.path(), &|_, _, _| {}).unwrap();
    let note = s.gpu_note.expect("the skip is stated");
    assert!(note.starts_with("no GPU adapter: skipped"), "{note}");
    assert_eq!(s.records.len(), 1);
    assert_eq!(s.records[0].backend, RecordBackend::Cpu);
    assert!(s.records[0].cpu_over_gpu.is_none());
    let html = std::fs::read_to_string(&s.index).unwrap();
    assert!(html.contains("no GPU adapter: skipped"));
}
