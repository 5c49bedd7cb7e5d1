//! The glTF loader on hand-written files: embedded and external buffers, GLB, node
//! hierarchies, sparse and non-indexed accessors, materials, lights, cameras, textures,
//! and the malformed cases that must be refused with one error.

mod common;

use common::*;
use glam::{Vec2, Vec3};
use renderlab_scene::load::{gltf::from_slice, load, load_with, LoadLimits, Problem};
use renderlab_scene::LightKind;
use serde_json::json;

fn limits() -> LoadLimits {
    LoadLimits::default()
}

#[test]
fn a_minimal_embedded_triangle_loads_with_flat_normals_and_defaults() {
    let loaded = from_slice(&triangle().gltf_embedded(), "t", None, &limits()).unwrap();
    let s = &loaded.scene;
    assert_eq!(s.triangle_count(), 1);
    for v in &s.meshes[0].vertices {
        assert!((v.normal - Vec3::Z).length() < 1e-6);
        assert!(v.tangent.truncate().dot(v.normal).abs() < 1e-6);
    }
    assert_eq!(s.lights.len(), 1, "a default light");
    assert_eq!(s.cameras.len(), 1, "a default camera");
    assert!(loaded.warnings.iter().any(|w| w.contains("no lights")), "{:?}", loaded.warnings);
    assert!(loaded.warnings.iter().any(|w| w.contains("no camera")), "{:?}", loaded.warnings);
}

#[test]
fn a_glb_with_materials_lights_and_camera() {
    let mut d = triangle();
    d.materials.push(json!({
        "name": "glass",
        "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.1},
        "emissiveFactor": [0.5, 0.0, 0.0],
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.33}}
    }));
    d.meshes[0]["primitives"][0]["material"] = json!(0);
    d.lights.push(json!({"type": "spot", "color": [1.0, 0.5, 0.25], "intensity": 20.0, "range": 10.0,
        "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}));
    d.lights.push(json!({"type": "directional", "intensity": 3.0}));
    // Rotated −90° about X, the node's −Z points down (−Y).
    let q = (-std::f32::consts::FRAC_PI_4).sin_cos();
    let spot = d.node(json!({"translation": [0.0, 5.0, 0.0], "rotation": [q.0, 0.0, 0.0, q.1],
        "extensions": {"KHR_lights_punctual": {"light": 0}}}));
    let sun = d.node(json!({"extensions": {"KHR_lights_punctual": {"light": 1}}}));
    d.cameras.push(json!({"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100.0, "aspectRatio": 2.0}}));
    let cam = d.node(json!({"camera": 0, "translation": [0.0, 1.0, 4.0]}));
    d.roots.extend([spot, sun, cam]);
    let loaded = from_slice(&d.glb(), "g", None, &limits()).unwrap();
    let s = &loaded.scene;
    let m = &s.materials[s.instances[0].material as usize];
    assert_eq!((m.transmission, m.ior, m.roughness), (1.0, 1.33, 0.1));
    assert!((m.base_color - Vec3::new(0.9, 0.8, 0.7)).length() < 1e-6);
    assert_eq!(m.emissive, Vec3::new(0.5, 0.0, 0.0));
    assert_eq!(s.lights.len(), 2);
    let l = &s.lights[0];
    assert!(
        matches!(l.kind, LightKind::Spot { inner_cone, outer_cone } if inner_cone == 0.2 && outer_cone == 0.5)
    );
    assert!((l.direction - Vec3::NEG_Y).length() < 1e-5, "{}", l.direction);
    assert!((l.position - Vec3::new(0.0, 5.0, 0.0)).length() < 1e-6);
    assert_eq!(l.range, Some(10.0));
    assert_eq!(s.lights[1].kind, LightKind::Directional);
    assert!((s.lights[1].direction - Vec3::NEG_Z).length() < 1e-6);
    let c = &s.cameras[0].camera;
    assert_eq!((c.width, c.height), (1920, 960));
    assert!((c.fov_y_deg - 0.8f32.to_degrees()).abs() < 1e-4);
    assert!(
        (c.forward - Vec3::NEG_Z).length() < 1e-6 && (c.position - Vec3::new(0.0, 1.0, 4.0)).length() < 1e-6
    );
    assert!(!loaded.warnings.iter().any(|w| w.contains("no lights")));
}

#[test]
fn a_node_hierarchy_composes_translation_scale_and_rotation() {
    let mut d = triangle();
    d.roots.clear();
    let q = std::f32::consts::FRAC_PI_4.sin_cos(); // 90° about Y
    let child = d.node(json!({"mesh": 0, "rotation": [0.0, q.0, 0.0, q.1]}));
    let parent =
        d.node(json!({"translation": [1.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "children": [child]}));
    d.roots.push(parent);
    let s = from_slice(&d.gltf_embedded(), "h", None, &limits()).unwrap().scene;
    assert_eq!(s.instances.len(), 1);
    let world = s.world_mesh(&s.instances[0]);
    // Vertex (1, 0, 0): rotated to (0, 0, −1), scaled to (0, 0, −2), moved to (1, 0, −2).
    let p = world.vertices.iter().map(|v| v.position).collect::<Vec<_>>();
    assert!(p.iter().any(|q| (*q - Vec3::new(1.0, 0.0, -2.0)).length() < 1e-5), "{p:?}");
    assert!(p.iter().any(|q| (*q - Vec3::new(1.0, 2.0, 0.0)).length() < 1e-5), "{p:?}");
    // The mesh's front (+Z) turned to +X.
    assert!((world.vertices[0].normal - Vec3::X).length() < 1e-5);
}

#[test]
fn a_sparse_accessor_overrides_its_base() {
    let mut d = triangle();
    let idx = d.view(&1u32.to_le_bytes());
    let val: Vec<u8> = [5.0f32, 0.0, 0.0].iter().flat_map(|x| x.to_le_bytes()).collect();
    let val = d.view(&val);
    d.accessors[0]["sparse"] = json!({"count": 1, "indices": {"bufferView": idx, "componentType": U32}, "values": {"bufferView": val}});
    d.accessors[0]["max"] = json!([5.0, 1.0, 0.0]);
    let s = from_slice(&d.gltf_embedded(), "s", None, &limits()).unwrap().scene;
    assert!(s.meshes[0].vertices.iter().any(|v| v.position == Vec3::new(5.0, 0.0, 0.0)));
}

#[test]
fn a_non_indexed_mesh_with_uvs_and_a_degenerate_triangle() {
    let mut d = Doc::default();
    let pos = d.vec3(&[
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
        [2.0, 2.0, 2.0], // collinear
    ]);
    let uv = d.vec2(&[
        [0.0, 1.0],
        [1.0, 1.0],
        [0.0, 0.0],
        [1.0, 1.0],
        [1.0, 0.0],
        [0.0, 0.0],
        [0.0; 2],
        [0.0; 2],
        [0.0; 2],
    ]);
    let mesh = d.mesh(json!({"POSITION": pos, "TEXCOORD_0": uv}), None, None);
    let node = d.node(json!({"mesh": mesh}));
    d.roots.push(node);
    let loaded = from_slice(&d.gltf_embedded(), "n", None, &limits()).unwrap();
    assert_eq!(loaded.scene.triangle_count(), 2);
    assert!(loaded.warnings.iter().any(|w| w == "dropped 1 degenerate triangles"), "{:?}", loaded.warnings);
    // u grows along +X: tangents follow it.
    for v in &loaded.scene.meshes[0].vertices {
        assert!((v.tangent.truncate() - Vec3::X).length() < 1e-5);
        assert!(v.uv.x >= 0.0 && v.uv.y >= 0.0);
    }
}

#[test]
fn an_embedded_png_base_colour_is_decoded_from_srgb() {
    let mut d = triangle();
    let png = png([[128, 0, 255, 255], [0, 0, 0, 255], [255, 255, 255, 255], [64, 64, 64, 255]]);
    let view = d.view(&png);
    d.images.push(json!({"bufferView": view, "mimeType": "image/png"}));
    d.textures.push(json!({"source": 0}));
    d.materials.push(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 0}}}));
    d.meshes[0]["primitives"][0]["material"] = json!(0);
    let s = from_slice(&d.glb(), "p", None, &limits()).unwrap().scene;
    assert_eq!(s.textures.len(), 2, "one image, decoded once as colour and once as data");
    let m = &s.materials[0];
    let colour = &s.textures[m.base_color_texture.unwrap() as usize].image;
    let data = &s.textures[m.metallic_roughness_texture.unwrap() as usize].image;
    assert!((colour.get(0, 0).x - 0.2158605).abs() < 1e-4, "{}", colour.get(0, 0));
    assert!((data.get(0, 0).x - 128.0 / 255.0).abs() < 1e-6);
    assert_eq!(colour.get(0, 0).z, 1.0);
}

#[test]
fn external_buffers_load_from_beside_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = triangle();
    std::fs::write(dir.path().join("tri data.bin"), &d.bin).unwrap();
    let json = d.json(Some("tri%20data.bin".into())).to_string();
    let path = dir.path().join("scene.GLTF");
    std::fs::write(&path, json).unwrap();
    let loaded = load(&path).unwrap();
    assert_eq!(loaded.scene.triangle_count(), 1);
    assert_eq!(loaded.scene.name, "scene");

    std::fs::remove_file(dir.path().join("tri data.bin")).unwrap();
    let err = load(&path).unwrap_err().to_string();
    assert!(err.contains("scene.GLTF") && err.contains("tri data.bin"), "{err}");
}

#[test]
fn malformed_files_are_refused_with_one_line() {
    let bad = |d: &Doc| {
        let e = from_slice(&d.gltf_embedded(), "b", None, &limits()).unwrap_err();
        let text = e.to_string();
        assert!(!text.contains('\n') && !text.is_empty());
        e
    };
    let mut d = triangle();
    d.bin[12 * 3..12 * 3 + 4].copy_from_slice(&7u32.to_le_bytes()); // index 7 of 3 vertices
    assert!(bad(&d).to_string().contains("vertex 7"));

    let mut d = triangle();
    d.bin[4..8].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(bad(&d).to_string().contains("non-finite"));

    let mut d = triangle();
    d.accessors[0]["byteOffset"] = json!(64); // past the view
    assert!(matches!(bad(&d), Problem::Invalid(_)));

    let mut d = triangle();
    d.accessors[0]["type"] = json!("VEC2");
    assert!(matches!(bad(&d), Problem::Invalid(_)));

    let mut d = triangle();
    d.images.push(json!({"uri": "missing.png"}));
    d.textures.push(json!({"source": 0}));
    d.materials.push(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}));
    d.meshes[0]["primitives"][0]["material"] = json!(0);
    assert!(matches!(bad(&d), Problem::Image(_)));

    let mut d = triangle();
    d.views[0]["byteLength"] = json!(4096); // the buffer is shorter
    assert!(from_slice(&d.gltf_embedded(), "b", None, &limits()).is_err());

    assert!(matches!(from_slice(b"{not json", "b", None, &limits()), Err(Problem::Gltf(_))));
}

#[test]
fn size_limits_and_unknown_formats_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.glb");
    std::fs::write(&path, triangle().glb()).unwrap();
    let small = LoadLimits { max_file_bytes: 64, ..LoadLimits::default() };
    let e = load_with(&path, &small).unwrap_err();
    assert!(matches!(&e.problem, Problem::Io(io) if io.kind() == std::io::ErrorKind::FileTooLarge), "{e}");
    assert!(e.to_string().contains("larger than 64 bytes"), "{e}");
    let few = LoadLimits { max_triangles: 0, ..LoadLimits::default() };
    assert!(load_with(&path, &few).is_err());
    assert!(load(&path).is_ok());
    let e = load(dir.path().join("scene.fbx")).unwrap_err();
    assert!(matches!(e.problem, Problem::UnknownFormat(_)));
    assert!(load(dir.path().join("absent.obj")).is_err());
    let _ = Vec2::ZERO;
}

/// Strips and fans (modes 5 and 6, which some exporters write) load as the triangles the
/// specification assembles, every one wound like the first; points and lines are
/// skipped with a warning, not an error.
#[test]
fn triangle_strips_and_fans_load_with_one_winding() {
    let grid: Vec<[f32; 3]> = (0..6).map(|i| [(i / 2) as f32, (i % 2) as f32, 0.0]).collect();
    for (mode, expected) in [(5, 4), (6, 4)] {
        let mut d = Doc::default();
        let pos = if mode == 5 {
            d.vec3(&grid)
        } else {
            // A fan around the centre of a hexagon, counter-clockwise seen from +Z.
            let mut fan = vec![[0.0, 0.0, 0.0]];
            fan.extend((0..5).map(|k| {
                let a = k as f32 * 0.9;
                [a.cos(), a.sin(), 0.0]
            }));
            d.vec3(&fan)
        };
        let idx = d.indices(&[0, 1, 2, 3, 4, 5]);
        let mesh = d.mesh(json!({"POSITION": pos}), Some(idx), None);
        d.meshes[mesh]["primitives"][0]["mode"] = json!(mode);
        let node = d.node(json!({"mesh": mesh}));
        d.roots.push(node);
        let loaded = from_slice(&d.gltf_embedded(), "s", None, &limits()).unwrap();
        assert_eq!(loaded.scene.triangle_count(), expected, "mode {mode}");
        let m = &loaded.scene.meshes[0];
        let normal_z = |t: &[u32; 3]| {
            let [a, b, c] = t.map(|i| m.vertices[i as usize].position);
            (b - a).cross(c - a).z
        };
        let first = normal_z(&m.triangles[0]);
        assert!(first != 0.0, "mode {mode}: degenerate first triangle");
        for t in &m.triangles {
            assert!(normal_z(t) * first > 0.0, "mode {mode}: {t:?} winds the other way");
        }
    }
    let mut d = Doc::default();
    let pos = d.vec3(&grid);
    let mesh = d.mesh(json!({"POSITION": pos}), None, None);
    d.meshes[mesh]["primitives"][0]["mode"] = json!(1);
    let node = d.node(json!({"mesh": mesh}));
    d.roots.push(node);
    match from_slice(&d.gltf_embedded(), "l", None, &limits()) {
        Ok(l) => assert!(l.warnings.iter().any(|w| w.contains("draws no triangles")), "{:?}", l.warnings),
        Err(e) => assert!(e.to_string().contains("triangle") || e.to_string().contains("mesh"), "{e}"),
    }
}

/// An interleaved vertex buffer (one view with `byteStride` 24: position, then a
/// normalized u16 UV pair and padding, as exporters pack them) and u8 indices load like
/// separate arrays.
#[test]
fn interleaved_vertices_and_byte_indices_load() {
    let mut d = Doc::default();
    let verts: [([f32; 3], [u16; 2]); 3] =
        [([0.0, 0.0, 0.0], [0, 65535]), ([1.0, 0.0, 0.0], [65535, 65535]), ([0.0, 1.0, 0.0], [0, 0])];
    let mut bytes = Vec::new();
    for (p, uv) in verts {
        bytes.extend(p.iter().flat_map(|x| x.to_le_bytes()));
        bytes.extend(uv.iter().flat_map(|x| x.to_le_bytes()));
        bytes.extend([0u8; 8]);
    }
    let view = d.view(&bytes);
    d.views[view]["byteStride"] = json!(24);
    d.accessors.push(json!({"bufferView": view, "componentType": 5126, "type": "VEC3", "count": 3,
        "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]}));
    let pos = d.accessors.len() - 1;
    d.accessors.push(json!({"bufferView": view, "byteOffset": 12, "componentType": 5123,
        "normalized": true, "type": "VEC2", "count": 3}));
    let uv = d.accessors.len() - 1;
    let idx = d.accessor(&[0u8, 1, 2, 0], 5121, "SCALAR", 3);
    let mesh = d.mesh(json!({"POSITION": pos, "TEXCOORD_0": uv}), Some(idx), None);
    let node = d.node(json!({"mesh": mesh}));
    d.roots.push(node);
    let loaded = from_slice(&d.gltf_embedded(), "i", None, &limits()).unwrap();
    assert_eq!(loaded.scene.triangle_count(), 1);
    let m = &loaded.scene.meshes[0];
    let mut got: Vec<(Vec3, glam::Vec2)> = m.vertices.iter().map(|v| (v.position, v.uv)).collect();
    got.sort_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.0.y.total_cmp(&b.0.y)));
    let expect = [
        (Vec3::new(0.0, 0.0, 0.0), glam::Vec2::new(0.0, 1.0)),
        (Vec3::new(0.0, 1.0, 0.0), glam::Vec2::new(0.0, 0.0)),
        (Vec3::new(1.0, 0.0, 0.0), glam::Vec2::new(1.0, 1.0)),
    ];
    for ((p, t), (ep, et)) in got.iter().zip(expect) {
        assert!((*p - ep).length() < 1e-6 && (*t - et).length() < 1e-4, "{p} {t} vs {ep} {et}");
    }
}

/// A unit quad of four shared vertices (two indexed triangles) with a COLOR_0 accessor.
fn coloured_quad(colours: Option<usize>, d: &mut Doc) -> usize {
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = d.indices(&[0, 1, 2, 0, 2, 3]);
    let mut attributes = json!({"POSITION": pos});
    if let Some(c) = colours {
        attributes["COLOR_0"] = json!(c);
    }
    let mesh = d.mesh(attributes, Some(idx), Some(0));
    let node = d.node(json!({"mesh": mesh}));
    d.roots.push(node);
    mesh
}

/// Checks that the instance's base-colour texture, read at its vertices' UVs and at each
/// triangle's centroid, gives the vertex colours and their mean.
fn assert_colours_drawn(s: &renderlab_scene::HybridScene, expected: &[[f32; 3]; 4]) {
    let inst = &s.instances[0];
    let m = &s.materials[inst.material as usize];
    let tex = &s.textures[m.base_color_texture.expect("a baked vertex-colour texture") as usize];
    let mesh = &s.meshes[inst.mesh as usize];
    assert_eq!(mesh.triangles.len(), 2);
    let colour_at = |p: Vec3| {
        // The quad's corners are its positions; find which one `p` is.
        let k = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]
            .iter()
            .position(|c| (*c - p).length() < 1e-6)
            .unwrap();
        Vec3::from(expected[k])
    };
    for t in &mesh.triangles {
        let vs = t.map(|i| mesh.vertices[i as usize]);
        for v in &vs {
            let got = tex.sample(v.uv).truncate();
            assert!((got - colour_at(v.position)).length() < 1e-5, "{got} at {}", v.position);
        }
        let centroid = (vs[0].uv + vs[1].uv + vs[2].uv) / 3.0;
        let mean = vs.iter().map(|v| colour_at(v.position)).sum::<Vec3>() / 3.0;
        let got = tex.sample(centroid).truncate();
        assert!((got - mean).length() < 1e-5, "centroid {got}, expected {mean}");
    }
}

#[test]
fn vertex_colours_are_drawn_through_a_baked_texture() {
    // Float RGBA colours, four shared vertices, a base colour factor that multiplies them.
    let colours = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
    let mut d = Doc::default();
    let rgba: Vec<u8> =
        colours.iter().flat_map(|c| [c[0], c[1], c[2], 1.0]).flat_map(|x: f32| x.to_le_bytes()).collect();
    let c = d.accessor(&rgba, FLOAT, "VEC4", 4);
    d.materials.push(json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 1.0, 1.0, 1.0]}}));
    coloured_quad(Some(c), &mut d);
    let loaded = from_slice(&d.gltf_embedded(), "c", None, &limits()).unwrap();
    let s = &loaded.scene;
    assert_colours_drawn(s, &colours);
    let m = &s.materials[s.instances[0].material as usize];
    assert_eq!(m.base_color, Vec3::new(0.5, 1.0, 1.0), "the factor still multiplies the colours");

    // Normalised unsigned-byte RGB colours in a GLB.
    let bytes = [[255u8, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0]];
    let mut d = Doc::default();
    let c = d.accessor(&bytes.concat(), U8, "VEC3", 4);
    d.accessors[c]["normalized"] = json!(true);
    d.materials.push(json!({}));
    coloured_quad(Some(c), &mut d);
    let loaded = from_slice(&d.glb(), "c", None, &limits()).unwrap();
    assert_colours_drawn(&loaded.scene, &colours);

    // A material with its own base-colour texture keeps it; the colours are reported ignored.
    let mut d = Doc::default();
    let c = d.accessor(&rgba, FLOAT, "VEC4", 4);
    let png_view = d.view(&png([[255, 255, 255, 255]; 4]));
    d.images.push(json!({"bufferView": png_view, "mimeType": "image/png"}));
    d.textures.push(json!({"source": 0}));
    d.materials.push(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}));
    coloured_quad(Some(c), &mut d);
    let loaded = from_slice(&d.gltf_embedded(), "c", None, &limits()).unwrap();
    assert_eq!(loaded.scene.textures.len(), 1);
    assert!(loaded.warnings.iter().any(|w| w.contains("vertex colours ignored")), "{:?}", loaded.warnings);
}

#[test]
fn a_malformed_animation_is_dropped_with_a_warning() {
    // Older exporters wrote a channel's target node as "id": the parser refuses it.
    let animation = json!([{
        "samplers": [{"input": 0, "output": 0, "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"id": 0, "path": "rotation"}}]
    }]);
    for glb in [false, true] {
        let mut d = triangle();
        d.extra.push(("animations", animation.clone()));
        let bytes = if glb { d.glb() } else { d.gltf_embedded() };
        let loaded = from_slice(&bytes, "a", None, &limits()).unwrap();
        assert_eq!(loaded.scene.triangle_count(), 1);
        assert!(loaded.warnings.iter().any(|w| w.contains("animations ignored")), "{:?}", loaded.warnings);
    }
    // An animation that parses but points at a node that does not exist: the scene loads
    // (whether or not the parser's validation notices, animations are never read).
    let mut d = triangle();
    d.extra.push((
        "animations",
        json!([{"samplers": [{"input": 0, "output": 0}], "channels": [{"sampler": 0, "target": {"node": 9, "path": "rotation"}}]}]),
    ));
    let loaded = from_slice(&d.gltf_embedded(), "a", None, &limits()).unwrap();
    assert_eq!(loaded.scene.triangle_count(), 1);
    // A fault elsewhere is still an error, with the animations present or not.
    let mut d = triangle();
    d.extra.push(("animations", animation));
    d.meshes[0]["primitives"][0]["indices"] = json!(7);
    let err = from_slice(&d.gltf_embedded(), "a", None, &limits()).unwrap_err();
    assert!(matches!(err, Problem::Gltf(_)), "{err}");
}

/// `KHR_texture_transform` on a material's textures moves its primitives' UVs as the
/// extension defines: scale, then rotation, then offset. The extension's own example (a
/// quarter turn, scale ½, offset (0, 1)) takes the unit square to the image's lower-left
/// quadrant; textures that disagree are warned about and the base colour's is used.
#[test]
fn khr_texture_transform_moves_the_uvs() {
    let with_transform = |transforms: &[serde_json::Value]| {
        let mut d = triangle();
        let uv = d.vec2(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        d.meshes[0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(uv);
        let view = d.view(&png([[255, 255, 255, 255]; 4]));
        d.images.push(json!({"bufferView": view, "mimeType": "image/png"}));
        d.textures.push(json!({"source": 0}));
        let info = |t: &serde_json::Value| json!({"index": 0, "extensions": {"KHR_texture_transform": t}});
        let mut pbr = json!({"baseColorTexture": info(&transforms[0])});
        if let Some(t) = transforms.get(1) {
            pbr["metallicRoughnessTexture"] = info(t);
        }
        d.materials.push(json!({"pbrMetallicRoughness": pbr}));
        d.meshes[0]["primitives"][0]["material"] = json!(0);
        let loaded = from_slice(&d.glb(), "t", None, &limits()).unwrap();
        let m = &loaded.scene.meshes[0];
        // The UV of the corner at each position.
        let at = |p: [f32; 3]| m.vertices.iter().find(|v| v.position == Vec3::from(p)).expect("corner").uv;
        ([at([0.0, 0.0, 0.0]), at([1.0, 0.0, 0.0]), at([0.0, 1.0, 0.0])], loaded.warnings)
    };
    let close = |a: Vec2, b: [f32; 2]| (a - Vec2::from(b)).abs().max_element() < 1e-6;
    let quarter = json!({"offset": [0.0, 1.0], "rotation": std::f32::consts::FRAC_PI_2, "scale": [0.5, 0.5]});
    let (uv, warnings) = with_transform(std::slice::from_ref(&quarter));
    for (got, want) in uv.iter().zip([[0.0, 1.0], [0.0, 0.5], [0.5, 1.0]]) {
        assert!(close(*got, want), "{uv:?}");
    }
    assert!(warnings.iter().all(|w| !w.contains("KHR_texture_transform")), "{warnings:?}");
    let (uv, _) = with_transform(&[json!({"offset": [0.25, 0.5], "scale": [2.0, 3.0]})]);
    for (got, want) in uv.iter().zip([[0.25, 0.5], [2.25, 0.5], [0.25, 3.5]]) {
        assert!(close(*got, want), "{uv:?}");
    }
    let (uv, warnings) = with_transform(&[quarter, json!({"scale": [4.0, 4.0]})]);
    assert!(close(uv[1], [0.0, 0.5]), "the base colour's transform: {uv:?}");
    assert!(warnings.iter().any(|w| w.contains("different KHR_texture_transforms")), "{warnings:?}");
}
