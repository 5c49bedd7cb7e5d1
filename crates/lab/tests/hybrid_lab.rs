//! The hybrid lab's run directory: N shards merged equal one run, an interrupted run resumed
//! equals an uninterrupted one, and bad merges are refused before anything is written.

use renderlab_lab::hybrid_lab::{
    merge_runs, run_hybrid_bench, Existing, HybridBenchConfig, RunSettings, Shard, SweepKind,
};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A tiny run: the showcase scene at 32×18, the report's 12 rows, a 4-spp reference.
fn tiny() -> HybridBenchConfig {
    HybridBenchConfig {
        scenes: vec!["showcase".into()],
        run: RunSettings {
            width: 32,
            height: 18,
            sweep: SweepKind::Report,
            reference_spp: 4,
            warmup: 0,
            reps: 1,
            ..RunSettings::default()
        },
        ..HybridBenchConfig::default()
    }
}

const TIMING_FIELDS: [&str; 8] = [
    "frame_ms",
    "frame_min_ms",
    "frame_max_ms",
    "stage_ms",
    "baseline_ms",
    "delta_ms",
    "delta_ratio",
    "seconds",
];

/// `results.json` with every timing field checked to be a positive number, then removed.
fn results_without_timings(dir: &Path) -> Value {
    let mut v: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    fn strip(v: &mut Value) {
        match v {
            Value::Object(map) => {
                for f in TIMING_FIELDS {
                    if let Some(t) = map.remove(f) {
                        let ok =
                            t.as_f64().is_some_and(|x| x.is_finite() && x > 0.0 || f.starts_with("delta"));
                        assert!(ok, "{f} = {t}");
                    }
                }
                map.values_mut().for_each(strip);
            }
            Value::Array(a) => a.iter_mut().for_each(strip),
            _ => {}
        }
    }
    strip(&mut v);
    v
}

fn quiet(_: usize, _: usize, _: &str) {}

fn run(cfg: &HybridBenchConfig, dir: &Path) {
    let s = run_hybrid_bench(cfg, dir, &quiet).unwrap();
    assert!(s.index.is_file());
}

#[test]
fn shards_merged_equal_one_run_and_resume_completes_a_run() {
    let tmp = tempfile::tempdir().unwrap();
    let whole = tmp.path().join("whole");
    run(&tiny(), &whole);
    let reference = results_without_timings(&whole);
    let records = reference["records"].as_array().unwrap();
    assert_eq!(records.len(), 12);
    assert!(records.iter().all(|r| r["psnr_db"].as_f64().is_some() && r["rays"].as_u64().is_some()));
    assert!(records.iter().any(|r| r["stage_rays"].as_u64() > Some(0)), "ray-traced rows trace rays");
    // Every row carries every term's score; a stage's own term is among them.
    for r in records {
        let names: Vec<&str> =
            r["term_scores"].as_array().unwrap().iter().map(|t| t["term"].as_str().unwrap()).collect();
        // (TermScore writes the occlusion term as `occlusion`; the record's `term` column names it `ao`.)
        assert_eq!(names, ["emitted", "direct", "diffuse", "specular", "translucent", "ao"], "{r}");
        assert!(r["direct_area_lit"].is_object() || r["direct_area_lit"].is_null());
    }
    // The page tests the thesis's claims, sets its tables beside ours and shows each stage's front.
    let page = std::fs::read_to_string(whole.join("index.html")).unwrap();
    for needle in ["claims tested", "Claim (d)", "Table 3.9", "What each stage buys", "on the front"] {
        assert!(page.contains(needle), "{needle}");
    }

    // Three shards, merged.
    let parts: Vec<PathBuf> = (1..=3).map(|k| tmp.path().join(format!("part{k}"))).collect();
    for (k, p) in parts.iter().enumerate() {
        run(&HybridBenchConfig { shard: Shard { index: k as u32 + 1, count: 3 }, ..tiny() }, p);
    }
    let merged = tmp.path().join("merged");
    let s = merge_runs(&parts, &merged).unwrap();
    assert_eq!((s.records.len(), s.missing), (12, 0));
    assert_eq!(results_without_timings(&merged), reference);
    assert_eq!(
        std::fs::read(merged.join("results.csv")).unwrap().iter().filter(|&&b| b == b'\n').count(),
        13
    );

    // An interrupted run: delete four finished rows (and the results), then resume.
    let resumed = tmp.path().join("resumed");
    std::fs::create_dir(&resumed).unwrap();
    copy_dir(&whole, &resumed);
    let mut rows: Vec<PathBuf> =
        std::fs::read_dir(resumed.join("rows")).unwrap().map(|e| e.unwrap().path()).collect();
    rows.sort();
    let kept = std::fs::read(&rows[0]).unwrap();
    for r in &rows[5..] {
        std::fs::remove_file(r).unwrap();
    }
    std::fs::remove_file(resumed.join("results.json")).unwrap();
    // Without --resume the directory is refused.
    let e = run_hybrid_bench(&tiny(), &resumed, &quiet).unwrap_err().to_string();
    assert!(e.contains("--resume"), "{e}");
    let s = run_hybrid_bench(&HybridBenchConfig { existing: Existing::Resume, ..tiny() }, &resumed, &quiet)
        .unwrap();
    assert_eq!(s.missing, 0);
    assert_eq!(results_without_timings(&resumed), reference);
    assert_eq!(std::fs::read(&rows[0]).unwrap(), kept, "a finished row is not rendered again");

    // Resuming with other settings is refused.
    let e = run_hybrid_bench(
        &HybridBenchConfig {
            existing: Existing::Resume,
            run: RunSettings { seed: 9, ..tiny().run },
            ..tiny()
        },
        &resumed,
        &quiet,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("other settings") && e.contains("seed"), "{e}");

    bad_merges(tmp.path(), &parts);
}

/// Different settings, overlapping or missing parts, different versions: one clear error,
/// and the output directory is not created.
fn bad_merges(tmp: &Path, parts: &[PathBuf]) {
    let out = tmp.join("bad");
    let expect = |inputs: Vec<PathBuf>, needle: &str| {
        let e = merge_runs(&inputs, &out).unwrap_err().to_string();
        assert!(e.contains(needle), "{needle}: {e}");
        assert!(!e.contains('\n'));
        assert!(!out.exists(), "nothing written for a refused merge");
    };
    expect(vec![parts[0].clone(), parts[1].clone()], "missing shards: 3/3");
    expect(vec![parts[0].clone(), parts[0].clone(), parts[1].clone(), parts[2].clone()], "overlapping");
    let other = tmp.join("other");
    run(
        &HybridBenchConfig {
            shard: Shard { index: 3, count: 3 },
            run: RunSettings { seed: 5, ..tiny().run },
            ..tiny()
        },
        &other,
    );
    expect(vec![parts[0].clone(), parts[1].clone(), other.clone()], "different settings");
    let old = tmp.join("old");
    std::fs::create_dir(&old).unwrap();
    copy_dir(&parts[2], &old);
    let manifest = std::fs::read_to_string(old.join("run.json"))
        .unwrap()
        .replace("\"version\": \"", "\"version\": \"0.0.0-");
    std::fs::write(old.join("run.json"), manifest).unwrap();
    expect(vec![parts[0].clone(), parts[1].clone(), old], "different versions");
    // A shard that did not finish: its rows are missing.
    let unfinished = tmp.join("unfinished");
    std::fs::create_dir(&unfinished).unwrap();
    copy_dir(&parts[2], &unfinished);
    let row = std::fs::read_dir(unfinished.join("rows")).unwrap().next().unwrap().unwrap().path();
    std::fs::remove_file(row).unwrap();
    expect(vec![parts[0].clone(), parts[1].clone(), unfinished], "missing");
    expect(vec![tmp.join("nowhere")], "run.json");
}

fn copy_dir(from: &Path, to: &Path) {
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let dest = to.join(p.file_name().unwrap());
        if p.is_dir() {
            std::fs::create_dir_all(&dest).unwrap();
            copy_dir(&p, &dest);
        } else {
            std::fs::copy(&p, &dest).unwrap();
        }
    }
}
