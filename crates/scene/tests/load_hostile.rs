//! Files built to exhaust the loader: buffers, images, MTL files and scene files that are
//! FIFOs or devices (`/dev/zero` has no end, a FIFO blocks its reader), and accessors whose
//! counts ask for far more than the file holds. Each is refused with one error naming the
//! problem, before anything large is allocated or any read waits.

#![cfg(unix)]

mod common;

use common::*;
use renderlab_scene::load::gltf::MAX_SPARSE_ONLY_ELEMENTS;
use renderlab_scene::load::{gltf, load, load_with, LoadLimits};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// Creates a FIFO at `path` with the system's `mkfifo`.
fn mkfifo(path: &Path) {
    let status = std::process::Command::new("mkfifo").arg(path).status().expect("run mkfifo");
    assert!(status.success(), "mkfifo failed");
}

/// Runs `f` on another thread and returns its result, failing the test (instead of hanging
/// it) if `f` has not returned after a minute: a read that waits on a FIFO never returns.
fn without_blocking<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(60)).expect("the load blocked (waiting for a writer on a FIFO)")
}

/// The error of loading `path`, as one line, without waiting forever.
fn load_error(path: PathBuf) -> String {
    without_blocking(move || match load(&path) {
        Ok(_) => panic!("{} loaded", path.display()),
        Err(e) => e.to_string(),
    })
}

/// A triangle whose buffer is the external file `uri`.
fn triangle_with_buffer(dir: &Path, name: &str, uri: &str) -> PathBuf {
    let path = dir.join(name);
    let json = triangle().json(Some(uri.to_string()));
    std::fs::write(&path, json.to_string()).unwrap();
    path
}

#[test]
fn a_buffer_that_is_a_device_is_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    for device in ["/dev/zero", "/dev/urandom"] {
        // Named directly (absolute URIs are allowed) and through a link with a plain name.
        let link = dir.path().join("data.bin");
        let _ = std::fs::remove_file(&link);
        std::os::unix::fs::symlink(device, &link).unwrap();
        for uri in [device, "data.bin"] {
            let msg = load_error(triangle_with_buffer(dir.path(), "t.gltf", uri));
            assert!(msg.contains("not a regular file (it is a character device)"), "{uri}: {msg}");
        }
    }
}

#[test]
fn a_glb_whose_buffer_is_a_device_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mut d = triangle();
    // The GLB's own binary chunk stays, a second buffer names the device.
    let mut json = d.json(None);
    json["buffers"].as_array_mut().unwrap().push(json!({"uri": "/dev/zero", "byteLength": 16}));
    d.extra.push(("buffers", json["buffers"].clone()));
    let path = dir.path().join("t.glb");
    std::fs::write(&path, d.glb()).unwrap();
    let msg = load_error(path);
    assert!(msg.contains("t.glb") && msg.contains("character device"), "{msg}");
}

#[test]
fn a_fifo_anywhere_a_scene_reads_is_refused_without_waiting() {
    let dir = tempfile::tempdir().unwrap();
    // The scene file itself, as each format.
    for name in ["pipe.gltf", "pipe.glb", "pipe.obj"] {
        let path = dir.path().join(name);
        mkfifo(&path);
        let msg = load_error(path);
        assert!(msg.contains(name) && msg.contains("FIFO"), "{msg}");
    }
    // A glTF buffer.
    mkfifo(&dir.path().join("buffer.bin"));
    let msg = load_error(triangle_with_buffer(dir.path(), "b.gltf", "buffer.bin"));
    assert!(msg.contains("buffer.bin") && msg.contains("FIFO"), "{msg}");
    // A glTF image.
    mkfifo(&dir.path().join("image.png"));
    let mut d = triangle();
    d.images.push(json!({"uri": "image.png"}));
    d.textures.push(json!({"source": 0}));
    d.materials.push(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}));
    d.meshes[0]["primitives"][0]["material"] = json!(0);
    let path = dir.path().join("i.gltf");
    std::fs::write(&path, d.gltf_embedded()).unwrap();
    let msg = load_error(path);
    assert!(msg.contains("image 0") && msg.contains("FIFO"), "{msg}");
}

#[test]
fn an_obj_whose_mtl_or_texture_is_a_fifo_or_device_is_not_read() {
    let dir = tempfile::tempdir().unwrap();
    // The material library: a missing or unreadable one gives the default material with a
    // warning that says why.
    mkfifo(&dir.path().join("cube.mtl"));
    let obj_path = dir.path().join("cube.obj");
    std::fs::write(&obj_path, CUBE_OBJ).unwrap();
    let p = obj_path.clone();
    let loaded = without_blocking(move || load(&p)).expect("loads with the default material");
    assert!(
        loaded.warnings.iter().any(|w| w.contains("cube.mtl") && w.contains("FIFO")),
        "{:?}",
        loaded.warnings
    );
    // The texture (`map_Kd red.png`), a FIFO and then a link to /dev/zero.
    std::fs::remove_file(dir.path().join("cube.mtl")).unwrap();
    std::fs::write(dir.path().join("cube.mtl"), CUBE_MTL).unwrap();
    mkfifo(&dir.path().join("red.png"));
    let msg = load_error(obj_path.clone());
    assert!(msg.contains("red.png") && msg.contains("FIFO"), "{msg}");
    std::fs::remove_file(dir.path().join("red.png")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("red.png")).unwrap();
    let msg = load_error(obj_path);
    assert!(msg.contains("red.png") && msg.contains("character device"), "{msg}");
}

#[test]
fn an_mtl_file_larger_than_the_limit_is_not_read_whole() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cube.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.path().join("cube.mtl"), "#".repeat(4096)).unwrap();
    let limits = LoadLimits { max_file_bytes: 2048, ..LoadLimits::default() };
    let loaded = load_with(dir.path().join("cube.obj"), &limits).unwrap();
    assert!(
        loaded.warnings.iter().any(|w| w.contains("cube.mtl") && w.contains("larger than 2048 bytes")),
        "{:?}",
        loaded.warnings
    );
}

/// A triangle whose POSITION accessor has no buffer view: `count` zero positions of which
/// `sparse` are given by sparse data (at indices 1, 2, …, each value (k, 1, 0)).
fn sparse_only_triangle(count: usize, sparse: u32) -> Doc {
    let mut d = Doc::default();
    let idx: Vec<u8> = (1..=sparse).flat_map(|i| i.to_le_bytes()).collect();
    let idx = d.view(&idx);
    let val: Vec<u8> = (1..=sparse).flat_map(|k| [k as f32, 1.0, 0.0]).flat_map(f32::to_le_bytes).collect();
    let val = d.view(&val);
    d.accessors.push(json!({
        "componentType": FLOAT, "type": "VEC3", "count": count,
        "min": [0.0, 0.0, 0.0], "max": [sparse as f32, 1.0, 0.0],
        "sparse": {"count": sparse, "indices": {"bufferView": idx, "componentType": U32},
                   "values": {"bufferView": val}},
    }));
    let tri = d.indices(&[0, 1, 2]);
    let mesh = d.mesh(json!({"POSITION": 0}), Some(tri), None);
    let node = d.node(json!({"mesh": mesh}));
    d.roots.push(node);
    d
}

#[test]
fn a_sparse_accessor_without_a_buffer_view_cannot_ask_for_gigabytes() {
    // A few hundred bytes asking for 10^8 positions (1.2 GB as floats).
    let hostile = sparse_only_triangle(100_000_000, 1).gltf_embedded();
    assert!(hostile.len() < 2048);
    for bytes in [hostile, sparse_only_triangle(100_000_000, 1).glb()] {
        let e = gltf::from_slice(&bytes, "s", None, &LoadLimits::default()).unwrap_err().to_string();
        assert!(e.contains("100000000 elements without a buffer view"), "{e}");
    }
    // Just over the stated cap is refused; a small one still loads as the zeros it implies.
    let over = sparse_only_triangle(MAX_SPARSE_ONLY_ELEMENTS + 1, 2).gltf_embedded();
    assert!(gltf::from_slice(&over, "s", None, &LoadLimits::default()).is_err());
    let s = gltf::from_slice(&sparse_only_triangle(3, 2).gltf_embedded(), "s", None, &LoadLimits::default())
        .unwrap()
        .scene;
    assert_eq!(s.triangle_count(), 1);
}

#[test]
fn an_index_count_beyond_the_triangle_limit_is_refused_before_reading() {
    let mut d = triangle();
    let many = d.indices(&[0, 1, 2, 0, 2, 1, 1, 0, 2]);
    d.meshes[0]["primitives"][0]["indices"] = json!(many);
    let limits = LoadLimits { max_triangles: 2, ..LoadLimits::default() };
    let e = gltf::from_slice(&d.gltf_embedded(), "t", None, &limits).unwrap_err().to_string();
    assert!(e.contains("more than 2 triangles"), "{e}");
    // The same file within the limit loads.
    assert!(gltf::from_slice(&d.gltf_embedded(), "t", None, &LoadLimits::default()).is_ok());
}
