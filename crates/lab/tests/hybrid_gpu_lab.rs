//! The hybrid lab on the GPU: `--backend both` runs every row on both renderers and records
//! the GPU's device, times and errors beside the CPU's; `--backend gpu` draws every row and
//! its references on the GPU. Without an adapter the tests say they skipped (and fail where
//! `CI` is set).

use renderlab_gpu::GpuContext;
use renderlab_lab::hybrid_lab::{
    run_hybrid_bench, HybridBackend, HybridBenchConfig, RowResult, RunSettings, SweepKind,
};

fn adapter() -> bool {
    match GpuContext::new() {
        Ok(_) => true,
        Err(e) if std::env::var_os("CI").is_some() => panic!("CI is set but the GPU tests cannot run: {e}"),
        Err(e) => {
            eprintln!("SKIPPED (no GPU adapter, and CI is not set): {e}");
            false
        }
    }
}

fn tiny(backend: HybridBackend) -> HybridBenchConfig {
    HybridBenchConfig {
        scenes: vec!["showcase".into()],
        run: RunSettings {
            width: 32,
            height: 18,
            sweep: SweepKind::Report,
            reference_spp: 4,
            warmup: 0,
            reps: 2,
            gpu_warmup: 1,
            backend,
            ..RunSettings::default()
        },
        ..HybridBenchConfig::default()
    }
}

#[test]
fn both_backends_record_the_gpu_beside_the_cpu() {
    if !adapter() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("both");
    let quiet = |_: usize, _: usize, _: &str| {};
    let s = run_hybrid_bench(&tiny(HybridBackend::Both), &out, &quiet).unwrap();
    assert_eq!(s.missing, 0);
    let mut on_gpu = 0;
    for entry in std::fs::read_dir(out.join("rows")).unwrap() {
        let row: RowResult = serde_json::from_slice(&std::fs::read(entry.unwrap().path()).unwrap()).unwrap();
        assert_eq!(row.backend, HybridBackend::Cpu, "both: the main fields are the CPU's");
        match &row.gpu {
            Some(g) => {
                on_gpu += 1;
                assert!(g.frame_ms > 0.0 && g.frame_ms.is_finite(), "{}: {}", row.id, g.frame_ms);
                let ratio = g.cpu_over_gpu.expect("both renderers: a ratio");
                assert!(ratio > 0.0 && ratio.is_finite(), "{}: {ratio}", row.id);
                assert_eq!(g.reps, 2);
                assert_eq!(g.stages_ms.len(), 7, "{}: geometry, five stages, composition", row.id);
                assert!(g.stages_ms.iter().all(|(_, ms)| ms.is_finite() && *ms >= 0.0), "{}", row.id);
                assert!(!g.device.adapter.is_empty() && !g.device.rt_path.is_empty());
                // The same frame drawn twice: the GPU's error against the reference is the
                // CPU's within what edge pixels and rounding change.
                assert!(
                    (g.psnr_db - row.psnr_db).abs() <= 1.0,
                    "{}: GPU {} dB, CPU {} dB",
                    row.id,
                    g.psnr_db,
                    row.psnr_db
                );
                assert_eq!(g.terms.len(), row.terms.len());
            }
            None => panic!("{}: both renderers, but no GPU results", row.id),
        }
    }
    assert_eq!(on_gpu, 12, "every row of the report's sweep ran on the GPU");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    for column in ["backend", "gpu_adapter", "gpu_frame_ms", "gpu_stage_ms", "cpu_over_gpu", "gpu_rt_path"] {
        assert!(header.split(',').any(|c| c == column), "results.csv lacks {column}: {header}");
    }
}

#[test]
fn a_gpu_run_draws_every_row_and_its_references_on_the_gpu() {
    if !adapter() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("gpu");
    let quiet = |_: usize, _: usize, _: &str| {};
    let s = run_hybrid_bench(&tiny(HybridBackend::Gpu), &out, &quiet).unwrap();
    assert_eq!(s.missing, 0);
    assert_eq!(s.records.len(), 12);
    for r in &s.records {
        assert_eq!(r.backend, "gpu", "{}", r.label);
        assert_eq!(r.gpu_frame_ms, Some(r.frame_ms), "{}: the row's times are the GPU's", r.label);
        assert!(r.cpu_over_gpu.is_none(), "{}: no CPU frames in a GPU run", r.label);
        assert!(r.psnr_db.is_finite() && r.psnr_db > 5.0, "{}: {} dB", r.label, r.psnr_db);
    }
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.contains("path traced on the same GPU"), "the page says where the references ran");
}
