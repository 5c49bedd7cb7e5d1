//! The OBJ loader on hand-written files: quads and n-gons, negative indices, the MTL
//! mapping, textures, missing normals and a missing MTL file.

mod common;

use common::*;
use glam::Vec3;
use renderlab_scene::load::{load, obj::from_slice, LoadLimits};

#[test]
fn quads_ngons_negative_indices_and_the_mtl_mapping() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cube.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.path().join("cube.mtl"), CUBE_MTL).unwrap();
    std::fs::write(dir.path().join("red.png"), png([[255, 128, 0, 255]; 4])).unwrap();
    let loaded = load(dir.path().join("cube.obj")).unwrap();
    let s = &loaded.scene;
    // Six quads → 12 triangles; a pentagon → 3.
    assert_eq!(s.instances.len(), 2);
    let count = |name: &str| {
        let i = s.instances.iter().find(|i| i.name == name).unwrap();
        (s.meshes[i.mesh as usize].triangles.len(), &s.materials[i.material as usize])
    };
    let (cube, red) = count("cube");
    let (pentagon, glass) = count("pentagon");
    assert_eq!((cube, pentagon), (12, 3));
    // The cube is closed and wound outward: its signed volume is +1.
    let i = s.instances.iter().find(|i| i.name == "cube").unwrap();
    let m = &s.meshes[i.mesh as usize];
    let vol: f32 = m
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| m.vertices[k as usize].position);
            a.dot(b.cross(c)) / 6.0
        })
        .sum();
    assert!((vol - 1.0).abs() < 1e-5, "volume {vol}");
    assert_eq!(red.base_color, Vec3::new(0.8, 0.1, 0.1));
    assert!((red.roughness - renderlab_scene::load::obj::roughness_from_shininess(100.0)).abs() < 1e-6);
    assert_eq!(red.emissive, Vec3::new(0.5, 0.25, 0.0));
    let tex = &s.textures[red.base_color_texture.unwrap() as usize].image;
    assert!((tex.get(1, 1).y - 0.2158605).abs() < 1e-4, "sRGB 128 decodes to 0.216");
    assert_eq!((glass.ior, glass.metallic), (1.45, 0.0));
    assert!((glass.transmission - 0.9).abs() < 1e-6);
    // OBJ has no lights or cameras. The red material emits (`Ke`), which lights the file:
    // no default light. The default camera is said aloud.
    assert!(s.lights.is_empty() && s.has_emitters());
    assert!(!loaded.warnings.iter().any(|w| w.contains("no lights")), "{:?}", loaded.warnings);
    assert!(loaded.warnings.iter().any(|w| w.contains("no camera")));
}

#[test]
fn a_missing_mtl_gives_the_default_material_and_a_warning() {
    let loaded = from_slice(CUBE_OBJ.as_bytes(), "c", None, &LoadLimits::default()).unwrap();
    assert!(loaded.warnings.iter().any(|w| w.contains("cube.mtl")), "{:?}", loaded.warnings);
    assert!(loaded.scene.materials.iter().all(|m| m.name == "default"));
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cube.obj"), CUBE_OBJ).unwrap();
    let loaded = load(dir.path().join("cube.obj")).unwrap();
    assert!(loaded.warnings.iter().any(|w| w.contains("cube.mtl")));
}

#[test]
fn missing_normals_are_computed_smooth_and_given_ones_are_kept() {
    let flat = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    let s = from_slice(flat.as_bytes(), "q", None, &LoadLimits::default()).unwrap().scene;
    assert_eq!(s.triangle_count(), 2);
    for v in &s.meshes[0].vertices {
        assert!((v.normal - Vec3::Z).length() < 1e-6);
    }
    let tilted = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1 1\nf 1//1 2//1 3//1\n";
    let s = from_slice(tilted.as_bytes(), "t", None, &LoadLimits::default()).unwrap().scene;
    let n = Vec3::new(0.0, 1.0, 1.0).normalize();
    assert!(s.meshes[0].vertices.iter().all(|v| (v.normal - n).length() < 1e-6));
}

#[test]
fn bad_obj_input_is_an_error_or_a_repair() {
    let l = LoadLimits::default();
    // An index past the end.
    assert!(from_slice(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "x", None, &l).is_err());
    // A NaN vertex.
    assert!(from_slice(b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "x", None, &l).is_err());
    // A texture the MTL names but that is missing is an error.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cube.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.path().join("cube.mtl"), CUBE_MTL).unwrap();
    let e = load(dir.path().join("cube.obj")).unwrap_err().to_string();
    assert!(e.contains("red.png"), "{e}");
    // Only degenerate faces: nothing to draw, but a valid (empty) scene.
    let loaded = from_slice(b"v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "x", None, &l).unwrap();
    assert_eq!(loaded.scene.triangle_count(), 0);
    assert!(loaded.warnings.iter().any(|w| w.contains("degenerate")));
}

#[test]
fn vertex_colours_after_positions_are_drawn() {
    // `v x y z r g b`, as MeshLab and tobj's own test files write them.
    let obj = "o tri\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
    let loaded = from_slice(obj.as_bytes(), "c", None, &LoadLimits::default()).unwrap();
    let s = &loaded.scene;
    let inst = &s.instances[0];
    let m = &s.materials[inst.material as usize];
    let tex = &s.textures[m.base_color_texture.expect("a baked vertex-colour texture") as usize];
    let mesh = &s.meshes[inst.mesh as usize];
    let mut centroid = glam::Vec2::ZERO;
    for v in &mesh.vertices {
        let want = if v.position == Vec3::ZERO {
            Vec3::X
        } else if v.position == Vec3::X {
            Vec3::Y
        } else {
            Vec3::Z
        };
        assert!((tex.sample(v.uv).truncate() - want).length() < 1e-5);
        centroid += v.uv / 3.0;
    }
    assert!((tex.sample(centroid).truncate() - Vec3::splat(1.0 / 3.0)).length() < 1e-5);
    // Smooth normals are kept: the triangle faces +Z.
    assert!(mesh.vertices.iter().all(|v| (v.normal - Vec3::Z).length() < 1e-6));
}

#[test]
fn texture_names_with_spaces_and_options_and_skipped_lines() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "mtllib m.mtl\no tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
               usemtl a\nf 1/1 2/2 3/3\nl 1 2\np 3\n";
    std::fs::write(dir.path().join("t.obj"), obj).unwrap();
    std::fs::write(
        dir.path().join("m.mtl"),
        "newmtl a\nKd 1 1 1\nmap_Kd -s 1 1 1 -clamp on my red map.png\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("my red map.png"), png([[255, 0, 0, 255]; 4])).unwrap();
    let loaded = load(dir.path().join("t.obj")).unwrap();
    let s = &loaded.scene;
    let m = &s.materials[s.instances[0].material as usize];
    let tex = &s.textures[m.base_color_texture.expect("the texture named with spaces") as usize].image;
    assert_eq!(tex.get(0, 0).truncate(), Vec3::X);
    assert!(loaded.warnings.iter().any(|w| w.contains("2 line and point elements")), "{:?}", loaded.warnings);

    // Only lines: loads, and says there is nothing to draw.
    let loaded = from_slice(b"v 0 0 0\nv 1 0 0\nl 1 2\n", "l", None, &LoadLimits::default()).unwrap();
    assert_eq!(loaded.scene.triangle_count(), 0);
    assert!(loaded.warnings.iter().any(|w| w.contains("nothing to draw")), "{:?}", loaded.warnings);
}

/// The default camera of a file without one looks from the side that shows the most front
/// faces: a closed cube from the front (+Z, every side shows as much), a room open toward −Z
/// (its walls facing inward, as a Cornell box is modelled) through its opening, not through
/// a wall that back-face culling would hide.
#[test]
fn the_default_camera_looks_into_an_open_room_through_its_opening() {
    let camera_z = |obj: &str| {
        let s = from_slice(obj.as_bytes(), "room", None, &LoadLimits::default()).unwrap().scene;
        assert_eq!(s.cameras.len(), 1);
        s.cameras[0].camera.position.z
    };
    // The room spans [0, 1]³; its walls face inward; the side at z = 0 is open.
    let room = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n\
                f 1 4 3 2\n\
                f 5 6 7 8\n\
                f 4 8 7 3\n\
                f 1 5 8 4\n\
                f 2 3 7 6\n";
    let z = camera_z(room);
    assert!(z < 0.0, "the camera is at z = {z}, behind the back wall (z = 1), not before the opening");
    // The same room with its opening toward +Z is seen from the front, +Z.
    let front = room.replace("f 4 8 7 3", "f 1 2 6 5");
    assert!(camera_z(&front) > 1.0);
    // A closed cube: the front.
    assert!(camera_z(CUBE_OBJ) > 0.0);
}

/// `Kd 0.5` (one number: a grey, as the MTL format allows) used to panic inside the parser;
/// it is a grey now, and a colour of two numbers is a warning and the default material.
#[test]
fn one_number_colours_are_greys_and_two_number_colours_do_not_panic() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cube.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.path().join("red.png"), png([[255, 128, 0, 255]; 4])).unwrap();
    let grey = CUBE_MTL.replace("Kd 1 1 1", "Kd 0.5");
    std::fs::write(dir.path().join("cube.mtl"), grey).unwrap();
    let s = load(dir.path().join("cube.obj")).unwrap().scene;
    let glass = s.materials.iter().find(|m| m.name == "glass").expect("the glass material");
    assert_eq!(glass.base_color, Vec3::splat(0.5));
    let two = CUBE_MTL.replace("Kd 1 1 1", "Kd 1 1");
    std::fs::write(dir.path().join("cube.mtl"), two).unwrap();
    let loaded = load(dir.path().join("cube.obj")).unwrap();
    assert!(
        loaded.warnings.iter().any(|w| w.contains("line 7: Kd needs one or three numbers")),
        "{:?}",
        loaded.warnings
    );
}
