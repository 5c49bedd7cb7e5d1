//! The hybrid lab's run directory under damage: cameras whose names clash get their own rows,
//! a resumed run repairs what is broken in its directory (and says so), a merge reads every
//! input before it writes and leaves `--out` as it was when it fails, and a directory in use
//! is refused.

use renderlab_lab::hybrid_lab::{
    merge_runs, run_hybrid_bench, Existing, HybridBenchConfig, RunSettings, Shard, SweepKind,
};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn quiet(_: usize, _: usize, _: &str) {}

/// A tiny run of `scene`: 16×9, the report's 12 rows, a 2-spp reference.
fn tiny(scene: &str) -> HybridBenchConfig {
    HybridBenchConfig {
        scenes: vec![scene.into()],
        run: RunSettings {
            width: 16,
            height: 9,
            sweep: SweepKind::Report,
            reference_spp: 2,
            warmup: 0,
            reps: 1,
            ..RunSettings::default()
        },
        ..HybridBenchConfig::default()
    }
}

fn resume(cfg: HybridBenchConfig) -> HybridBenchConfig {
    HybridBenchConfig { existing: Existing::Resume, ..cfg }
}

/// `results.json` without its timings (which differ between renders of one row).
fn results(dir: &Path) -> Value {
    let mut v: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    fn strip(v: &mut Value) {
        match v {
            Value::Object(map) => {
                for f in [
                    "frame_ms",
                    "frame_min_ms",
                    "frame_max_ms",
                    "stage_ms",
                    "baseline_ms",
                    "delta_ms",
                    "delta_ratio",
                    "seconds",
                ] {
                    map.remove(f);
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

/// Every file under `dir`, relative to it, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    fn walk(root: &Path, d: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                out.push(p.strip_prefix(root).unwrap().to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

fn temporaries(dir: &Path) -> Vec<PathBuf> {
    files(dir).into_iter().filter(|p| p.to_string_lossy().ends_with(".tmp")).collect()
}

/// Every image `index.html` links is there.
fn page_links_resolve(dir: &Path) {
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let mut n = 0;
    for part in html.split("src=\"").skip(1) {
        let rel = &part[..part.find('"').unwrap()];
        if rel.starts_with("img/") {
            assert!(dir.join(rel).is_file(), "index.html links the missing {rel}");
            n += 1;
        }
    }
    assert!(n > 0, "the page shows images");
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let dest = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_dir(&p, &dest);
        } else {
            std::fs::copy(&p, &dest).unwrap();
        }
    }
}

/// The rows' files of `dir`, sorted.
fn row_files(dir: &Path) -> Vec<PathBuf> {
    let mut rows: Vec<PathBuf> =
        std::fs::read_dir(dir.join("rows")).unwrap().map(|e| e.unwrap().path()).collect();
    rows.sort();
    rows
}

/// A glTF scene (a floor, a point light) with four cameras at four places, named `a b`,
/// `a_b`, `c1` and `c1`: names that clash as file names, and a name given twice.
fn clashing_cameras(dir: &Path) -> PathBuf {
    let positions: [[f32; 3]; 4] = [[-3.0, 0.0, -3.0], [3.0, 0.0, -3.0], [3.0, 0.0, 3.0], [-3.0, 0.0, 3.0]];
    let indices: [u32; 6] = [0, 2, 1, 0, 3, 2];
    let mut bin: Vec<u8> = positions.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
    bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(dir.join("floor.bin"), &bin).unwrap();
    let camera = |name: &str| {
        serde_json::json!({"type": "perspective", "name": name,
            "perspective": {"yfov": 0.9, "znear": 0.05, "zfar": 100.0, "aspectRatio": 1.7778}})
    };
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 40.0}]}},
        "buffers": [{"uri": "floor.bin", "byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 24}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 4,
             "min": [-3.0, 0.0, -3.0], "max": [3.0, 0.0, 3.0]},
            {"bufferView": 1, "componentType": 5125, "type": "SCALAR", "count": 6}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "cameras": [camera("a b"), camera("a_b"), camera("c1"), camera("c1")],
        "nodes": [
            {"mesh": 0},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.5, 2.0, 0.5]},
            {"camera": 0, "translation": [0.0, 1.0, 4.0]},
            {"camera": 1, "translation": [2.0, 0.6, 4.0]},
            {"camera": 2, "translation": [-2.0, 1.5, 3.0]},
            {"camera": 3, "translation": [0.0, 2.5, 5.0]}
        ],
        "scenes": [{"nodes": [0, 1, 2, 3, 4, 5]}],
        "scene": 0
    });
    let path = dir.join("clash.gltf");
    std::fs::write(&path, serde_json::to_vec_pretty(&doc).unwrap()).unwrap();
    path
}

#[test]
fn cameras_whose_names_clash_are_rendered_each_with_its_own_rows() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = clashing_cameras(tmp.path());
    let out = tmp.path().join("run");
    let cfg = tiny(scene.to_str().unwrap());
    let s = run_hybrid_bench(&cfg, &out, &quiet).unwrap();
    assert_eq!(s.manifest.settings.views.len(), 4);
    assert_eq!((s.records.len(), s.missing), (4 * 12, 0));
    assert_eq!(row_files(&out).len(), 4 * 12, "one file per row of every camera");
    // Each camera rendered from its own place: its baseline image and error differ from
    // every other camera's.
    let base: Vec<_> = s.records.iter().filter(|r| r.stage == "baseline").collect();
    assert_eq!(base.len(), 4);
    let mut indices: Vec<usize> = base.iter().map(|r| r.camera_index).collect();
    indices.sort();
    assert_eq!(indices, [0, 1, 2, 3]);
    let images: Vec<Vec<u8>> = s
        .manifest
        .settings
        .views
        .iter()
        .map(|v| std::fs::read(out.join(format!("img/{}__reference.png", v.id))).unwrap())
        .collect();
    for i in 0..4 {
        for j in 0..i {
            assert_ne!(images[i], images[j], "cameras {i} and {j} rendered alike");
        }
    }
    // Selecting `c1` by name renders both cameras of that name; naming a camera twice is refused.
    let only = tmp.path().join("c1");
    let s = run_hybrid_bench(&HybridBenchConfig { cameras: vec!["c1".into()], ..cfg.clone() }, &only, &quiet)
        .unwrap();
    assert_eq!(s.manifest.settings.views.iter().map(|v| v.camera_index).collect::<Vec<_>>(), [2, 3]);
    let e = run_hybrid_bench(
        &HybridBenchConfig { cameras: vec!["c1".into(), "c1".into()], ..cfg },
        &tmp.path().join("twice"),
        &quiet,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("given twice"), "{e}");
}

#[test]
fn a_resumed_run_repairs_what_is_damaged_and_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let whole = tmp.path().join("whole");
    run_hybrid_bench(&tiny("showcase"), &whole, &quiet).unwrap();
    let expected = results(&whole);

    let dir = tmp.path().join("damaged");
    copy_dir(&whole, &dir);
    let rows = row_files(&dir);
    let name = |p: &Path| p.file_stem().unwrap().to_string_lossy().into_owned();
    // A truncated row, an empty row, a row file holding another row.
    let bytes = std::fs::read(&rows[0]).unwrap();
    std::fs::write(&rows[0], &bytes[..bytes.len() / 3]).unwrap();
    std::fs::write(&rows[1], b"").unwrap();
    std::fs::copy(&rows[3], &rows[2]).unwrap();
    // A finished row whose images were deleted.
    let gone = name(&rows[4]);
    std::fs::remove_file(dir.join(format!("img/{gone}.png"))).unwrap();
    // A truncated reference EXR; temporaries left by a killed run.
    let exr = std::fs::read_dir(dir.join("refs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "exr"))
        .unwrap();
    let full = std::fs::read(&exr).unwrap();
    std::fs::write(&exr, &full[..full.len() / 2]).unwrap();
    std::fs::write(dir.join("img/.x.png.4242.7.tmp"), b"half a png").unwrap();
    std::fs::write(dir.join("rows/.y.json.4242.8.tmp"), b"{\"id\"").unwrap();
    std::fs::remove_file(dir.join("results.json")).unwrap();

    let s = run_hybrid_bench(&resume(tiny("showcase")), &dir, &quiet).unwrap();
    let said = s.repairs.join("\n");
    for i in [0, 1, 2, 4] {
        assert!(
            said.contains(&format!("row {} was unusable", name(&rows[i]))),
            "row {i} not reported: {said}"
        );
    }
    assert!(said.contains("reference") && said.contains("temporary"), "{said}");
    assert_eq!(s.repairs.len(), 4 + 2, "{said}");
    assert_eq!((s.records.len(), s.missing), (12, 0));
    assert_eq!(results(&dir), expected, "a repaired run equals an undamaged one");
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    assert_eq!(std::fs::read(&exr).unwrap().len(), full.len(), "the reference is whole again");
    page_links_resolve(&dir);
    // Now whole: a second resume has nothing to repair and keeps every row.
    let kept = std::fs::read(&rows[8]).unwrap();
    let s = run_hybrid_bench(&resume(tiny("showcase")), &dir, &quiet).unwrap();
    assert!(s.repairs.is_empty(), "{:?}", s.repairs);
    assert_eq!(std::fs::read(&rows[8]).unwrap(), kept);

    // A deleted reference image is written again from the EXR, without rendering.
    let png = std::fs::read_dir(dir.join("img"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.to_string_lossy().ends_with("__reference.png"))
        .unwrap();
    std::fs::remove_file(&png).unwrap();
    let s = run_hybrid_bench(&resume(tiny("showcase")), &dir, &quiet).unwrap();
    assert_eq!(s.repairs.len(), 1, "{:?}", s.repairs);
    assert!(png.is_file());
    page_links_resolve(&dir);
}

#[test]
fn a_merge_reads_everything_first_and_a_failed_one_leaves_out_as_it_was() {
    let tmp = tempfile::tempdir().unwrap();
    let parts: Vec<PathBuf> = (1..=2).map(|k| tmp.path().join(format!("part{k}"))).collect();
    let cfg = |k: u32| HybridBenchConfig { shard: Shard { index: k, count: 2 }, ..tiny("showcase") };
    for (k, p) in parts.iter().enumerate() {
        run_hybrid_bench(&cfg(k as u32 + 1), p, &quiet).unwrap();
    }
    let good = tmp.path().join("good");
    merge_runs(&parts, &good).unwrap();
    let expected = results(&good);

    let out = tmp.path().join("merged");
    // A truncated row in the second part: refused, nothing written.
    let rows = row_files(&parts[1]);
    let bytes = std::fs::read(&rows[1]).unwrap();
    std::fs::write(&rows[1], &bytes[..bytes.len() - 9]).unwrap();
    let e = merge_runs(&parts, &out).unwrap_err().to_string();
    assert!(e.contains(&rows[1].display().to_string()) && e.contains("--resume"), "{e}");
    assert!(!out.exists(), "a refused merge writes nothing");
    // An image missing in the first part: refused, nothing written.
    run_hybrid_bench(&resume(cfg(2)), &parts[1], &quiet).unwrap();
    let row = &row_files(&parts[0])[2];
    let img = parts[0].join(format!("img/{}_flip.png", row.file_stem().unwrap().to_string_lossy()));
    std::fs::remove_file(&img).unwrap();
    let e = merge_runs(&parts, &out).unwrap_err().to_string();
    assert!(e.contains("_flip.png"), "{e}");
    assert!(!out.exists(), "a refused merge writes nothing");
    // Into an existing directory with a file of the user's: the same, and the file stays.
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("notes.txt"), b"mine").unwrap();
    assert!(merge_runs(&parts, &out).is_err());
    let left: Vec<PathBuf> = files(&out).into_iter().filter(|p| p != Path::new(".lock")).collect();
    assert_eq!(left, [PathBuf::from("notes.txt")]);
    // Repaired by resuming the shard, the merge succeeds, equal to a merge of whole parts.
    let s = run_hybrid_bench(&resume(cfg(1)), &parts[0], &quiet).unwrap();
    assert_eq!(s.repairs.len(), 1, "{:?}", s.repairs);
    let s = merge_runs(&parts, &out).unwrap();
    assert_eq!((s.records.len(), s.missing), (12, 0));
    assert_eq!(results(&out), expected);
    assert!(s.index.starts_with(&out) && s.index.is_file());
    assert!(out.join("notes.txt").is_file());
    page_links_resolve(&out);
    // No staging directory left beside it.
    let beside: Vec<String> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(beside.is_empty(), "{beside:?}");
}

#[test]
fn a_directory_in_use_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("run");
    std::fs::create_dir(&out).unwrap();
    // Another process's lock (this one's, through its own handle, counts as another).
    let holder =
        std::fs::OpenOptions::new().create(true).truncate(false).write(true).open(out.join(".lock")).unwrap();
    fs4::FileExt::try_lock(&holder).unwrap();
    std::fs::write(out.join(".lock"), b"4242\n").unwrap();
    let e = run_hybrid_bench(&tiny("showcase"), &out, &quiet).unwrap_err().to_string();
    assert!(e.contains("in use by another run (pid 4242)"), "{e}");
    assert!(!out.join("run.json").exists(), "nothing written");
    let whole = tmp.path().join("whole");
    let parts = [tmp.path().join("p")];
    run_hybrid_bench(&tiny("showcase"), &parts[0], &quiet).unwrap();
    let e = merge_runs(&parts, &out).unwrap_err().to_string();
    assert!(e.contains("in use by another run"), "{e}");
    drop(holder);
    run_hybrid_bench(&tiny("showcase"), &out, &quiet).unwrap();
    merge_runs(&parts, &whole).unwrap();
}
