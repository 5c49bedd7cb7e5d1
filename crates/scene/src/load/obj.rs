//! Wavefront OBJ with MTL materials into a [`HybridScene`] (through the `tobj` parser).
//!
//! Faces of any size are fan-triangulated, negative (relative) indices resolve as the
//! format defines them, missing normals are computed smooth (area-weighted over shared
//! vertices, what OBJ exporters assume), missing UVs are zero, tangents always come from
//! the UVs. V is flipped (OBJ counts it upward, the lab's textures downward). Vertex
//! colours (`v x y z r g b`) multiply the material's `Kd`, through a texture baked for the
//! mesh, when the material has no texture of its own.
//!
//! MTL → [`PbrMaterial`]:
//! - `Kd` → base colour; `map_Kd` → base-colour texture (decoded from sRGB); `norm` /
//!   `map_Bump` → normal texture (read as a tangent-space normal map);
//! - `Ns` (Blinn–Phong exponent n) → roughness through the usual equivalence of a
//!   Blinn–Phong lobe and a microfacet one, α = √(2 / (n + 2)), perceptual roughness √α
//!   (n = 0 gives 1, n = 1000 gives 0.21); a `Pr` entry (the PBR extension) overrides it;
//! - `Pm` → metalness (0 without it);
//! - `Ni` → ior (values below 1, such as the common 1.0 placeholder's neighbours, give 1);
//! - `d` → transmission 1 − d, or `Tr` → transmission Tr;
//! - `Ke` → emitted radiance. MTL has no notion of a material's sides, so every material
//!   stays [`PbrMaterial::double_sided`]: an emitter shines from both faces.
//!
//! OBJ has no lights or cameras: the shared finishing step adds a framing camera, and a
//! default sun unless some material emits (`Ke`), with warnings. A missing MTL file gives the default material and a
//! warning; a missing texture is an error.

use super::common::{finish, read_limited, resolve, LoadLimits, LoadedScene, Problem};
use super::geometry::{clean, NormalRule, RawMesh};
use super::textures::{decode_image, vertex_colors};
use crate::material::{PbrMaterial, Texture};
use crate::scene::{HybridScene, Instance};
use glam::{Affine3A, Vec2, Vec3, Vec4};
use std::collections::HashMap;
use std::path::Path;

/// Loads an OBJ document from memory; `base` is the folder MTL files and textures are
/// resolved against (`None`: none can be loaded).
pub fn from_slice(
    bytes: &[u8],
    name: &str,
    base: Option<&Path>,
    limits: &LoadLimits,
) -> Result<LoadedScene, Problem> {
    let mut warnings = Vec::new();
    let options =
        tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let mtl_notes = std::cell::RefCell::new(Vec::new());
    // The parser indexes and unwraps on some malformed input (MTL colour statements are
    // checked first, see `normalize_mtl`): a panic inside it is a malformed file, not a crash.
    let parsed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, |p| {
            let loaded = p
                .to_str()
                .ok_or_else(|| Problem::Invalid("an MTL file name is not UTF-8".into()))
                .and_then(|n| resolve(base, n))
                .and_then(|path| read_limited(&path, limits));
            match loaded.map(|text| normalize_mtl(&text)) {
                Ok(Ok(text)) => tobj::load_mtl_buf(&mut std::io::Cursor::new(text)).inspect_err(|e| {
                    mtl_notes
                        .borrow_mut()
                        .push(format!("MTL file {}: {e}; default material used", p.display()));
                }),
                Ok(Err(why)) => {
                    mtl_notes
                        .borrow_mut()
                        .push(format!("MTL file {}: {why}; default material used", p.display()));
                    Err(tobj::LoadError::MaterialParseError)
                }
                Err(e) => {
                    mtl_notes
                        .borrow_mut()
                        .push(format!("MTL file {} not loaded ({e}); default material used", p.display()));
                    Err(tobj::LoadError::OpenFileFailed)
                }
            }
        })
    }))
    .map_err(|_| Problem::Obj("the parser failed on malformed input".into()))?;
    let (models, materials) = parsed.map_err(|e| match e {
        tobj::LoadError::FaceColorOutOfBounds | tobj::LoadError::ColorParseError => {
            Problem::Obj(vertex_colour_problem(bytes).unwrap_or_else(|| e.to_string()))
        }
        e => Problem::Obj(e.to_string()),
    })?;
    warnings.append(&mut mtl_notes.into_inner());
    let skipped = bytes
        .split(|&b| b == b'\n')
        .filter(|l| matches!(l.trim_ascii_start(), [b'l' | b'p', b' ' | b'\t', ..]))
        .count();
    if skipped > 0 {
        warnings.push(format!("{skipped} line and point elements (l, p) are not drawn"));
    }
    let materials = materials.unwrap_or_default();

    let mut scene = HybridScene::empty(name, Vec3::ZERO);
    let mut converted: HashMap<Option<usize>, u32> = HashMap::new();
    let mut textures: HashMap<(String, bool), u32> = HashMap::new();
    let (mut triangles, mut dropped) = (0usize, 0usize);
    for model in models {
        let m = &model.mesh;
        let n = m.positions.len() / 3;
        let positions: Vec<Vec3> = m.positions.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect();
        let normals = (m.normals.len() == 3 * n && n > 0)
            .then(|| m.normals.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect());
        let uvs = (m.texcoords.len() == 2 * n && n > 0)
            .then(|| m.texcoords.chunks_exact(2).map(|c| Vec2::new(c[0], 1.0 - c[1])).collect());
        let colors = (m.vertex_color.len() == 3 * n && n > 0)
            .then(|| m.vertex_color.chunks_exact(3).map(|c| Vec4::new(c[0], c[1], c[2], 1.0)).collect());
        let tris = m.indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let raw = RawMesh {
            name: model.name.clone(),
            positions,
            normals,
            uvs,
            tangents: None,
            colors,
            triangles: tris,
        };
        let mut cleaned = clean(raw, NormalRule::Smooth)?;
        dropped += cleaned.dropped;
        warnings.extend(cleaned.notes);
        if cleaned.mesh.triangles.is_empty() {
            continue;
        }
        triangles += cleaned.mesh.triangles.len();
        if triangles > limits.max_triangles {
            return Err(Problem::Invalid(format!("more than {} triangles", limits.max_triangles)));
        }
        let key = m.material_id.filter(|&i| i < materials.len());
        if m.material_id.is_some() && key.is_none() && !materials.is_empty() {
            warnings.push(format!("{}: unknown material, default used", model.name));
        }
        let material = match converted.get(&key) {
            Some(&done) => done,
            None => {
                let mat = match key {
                    Some(i) => convert(&materials[i], &mut scene, &mut textures, base, limits)?,
                    None => PbrMaterial::default(),
                };
                scene.materials.push(mat);
                let index = (scene.materials.len() - 1) as u32;
                converted.insert(key, index);
                index
            }
        };
        let material = match cleaned.colors.take() {
            Some(colors) => {
                vertex_colors(&mut scene, &mut cleaned.mesh, &colors, material, limits, &model.name)
                    .unwrap_or_else(|why| {
                        warnings.push(why);
                        material
                    })
            }
            None => material,
        };
        scene.meshes.push(cleaned.mesh);
        scene.instances.push(Instance {
            name: model.name,
            mesh: (scene.meshes.len() - 1) as u32,
            material,
            transform: Affine3A::IDENTITY,
        });
    }
    if dropped > 0 {
        warnings.push(format!("dropped {dropped} degenerate triangles"));
    }
    let scene = finish(scene, &mut warnings)?;
    Ok(LoadedScene { scene, warnings })
}

/// The PBR material of an MTL material (the mapping in the module documentation).
fn convert(
    m: &tobj::Material,
    scene: &mut HybridScene,
    textures: &mut HashMap<(String, bool), u32>,
    base: Option<&Path>,
    limits: &LoadLimits,
) -> Result<PbrMaterial, Problem> {
    let unit = |x: f32| if x.is_finite() { x.clamp(0.0, 1.0) } else { 0.0 };
    let param = |key: &str| {
        m.unknown_param.get(key).and_then(|v| v.trim().parse::<f32>().ok()).filter(|v| v.is_finite())
    };
    // MTL cannot say which faces a material shows: both, as before sidedness was read.
    let mut out = PbrMaterial { name: m.name.clone(), double_sided: true, ..PbrMaterial::default() };
    if let Some(kd) = m.diffuse {
        out.base_color = Vec3::from(kd.map(unit));
    }
    if let Some(ns) = m.shininess.filter(|n| n.is_finite()) {
        out.roughness = roughness_from_shininess(ns);
    }
    if let Some(pr) = param("Pr") {
        out.roughness = unit(pr);
    }
    out.metallic = param("Pm").map_or(0.0, unit);
    if let Some(ni) = m.optical_density.filter(|n| n.is_finite()) {
        out.ior = ni.max(1.0);
    }
    if let Some(d) = m.dissolve {
        out.transmission = unit(1.0 - d);
    } else if let Some(tr) = param("Tr") {
        out.transmission = unit(tr);
    }
    if let Some(ke) = m.emissive {
        let e = Vec3::from(ke);
        out.emissive = if e.is_finite() { e.max(Vec3::ZERO) } else { Vec3::ZERO };
    }
    let mut texture = |file: &str, srgb: bool| -> Result<u32, Problem> {
        if let Some(&done) = textures.get(&(file.to_string(), srgb)) {
            return Ok(done);
        }
        let file_name = texture_file_name(file);
        let bytes = resolve(base, file_name)
            .and_then(|p| read_limited(&p, limits))
            .map_err(|e| Problem::Image(format!("{file_name:?}: {e}")))?;
        let image =
            decode_image(&bytes, srgb, limits).map_err(|e| Problem::Image(format!("{file_name:?}: {e}")))?;
        scene.textures.push(Texture::new(image));
        let index = (scene.textures.len() - 1) as u32;
        textures.insert((file.to_string(), srgb), index);
        Ok(index)
    };
    if let Some(f) = &m.diffuse_texture {
        out.base_color_texture = Some(texture(f, true)?);
    }
    if let Some(f) = m.normal_texture.as_ref().or_else(|| m.unknown_param.get("norm")) {
        out.normal_texture = Some(texture(f, false)?);
    }
    Ok(out)
}

/// Checks an MTL file's colour statements (`Ka`, `Kd`, `Ks`, `Ke`) before the parser sees
/// them: the format allows one number for a grey (`Kd 0.5` means `Kd 0.5 0.5 0.5`), which is
/// written out as three, and the parser would panic on one or two; a statement with none or
/// two is refused with its line number. Other lines are passed on as they are.
pub fn normalize_mtl(text: &[u8]) -> Result<Vec<u8>, String> {
    let mut out = Vec::with_capacity(text.len() + 64);
    for (n, line) in text.split(|&b| b == b'\n').enumerate() {
        if n > 0 {
            out.push(b'\n');
        }
        let Ok(line_str) = std::str::from_utf8(line) else {
            out.extend_from_slice(line);
            continue;
        };
        let mut words = line_str.split_whitespace();
        match words.next() {
            Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) => {
                let values: Vec<&str> = words.collect();
                match values.as_slice() {
                    [v] => out.extend_from_slice(format!("{key} {v} {v} {v}").as_bytes()),
                    [_, _, _, ..] => out.extend_from_slice(line),
                    _ => return Err(format!("line {}: {key} needs one or three numbers", n + 1)),
                }
            }
            _ => out.extend_from_slice(line),
        }
    }
    Ok(out)
}

/// The file name of an MTL texture statement's argument: the options that may precede it
/// (`-bm 1.0`, `-o 0 0.5`, `-clamp on` …, each with its argument count) are skipped, and the
/// rest, spaces included, is the name (exporters write names such as `wood floor.png`).
pub fn texture_file_name(arg: &str) -> &str {
    let mut rest = arg.trim();
    while rest.starts_with('-') {
        let (option, after) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
        // (least, most) arguments; -o, -s and -t take one to three numbers.
        let (least, most) = match option {
            "-o" | "-s" | "-t" => (1, 3),
            "-mm" => (2, 2),
            "-blendu" | "-blendv" | "-boost" | "-texres" | "-clamp" | "-bm" | "-imfchan" | "-type"
            | "-cc" => (1, 1),
            _ => (0, 0),
        };
        rest = after.trim_start();
        for k in 0..most {
            let (word, after) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
            let numeric = word.parse::<f32>().is_ok();
            if word.is_empty() || (k >= least && !numeric) || after.trim().is_empty() {
                break;
            }
            rest = after.trim_start();
        }
    }
    rest
}

/// Perceptual GGX roughness equivalent to a Blinn–Phong exponent: α = √(2 / (n + 2)),
/// roughness = √α (clamped to [0, 1]; negative exponents count as 0).
pub fn roughness_from_shininess(ns: f32) -> f32 {
    let alpha = (2.0 / (ns.max(0.0) + 2.0)).sqrt();
    alpha.sqrt().clamp(0.0, 1.0)
}

/// What is wrong with the vertex colours (`v x y z r g b`) of an OBJ document that the
/// parser refused for them (it says only "face vertex color index out of bounds"): the first
/// vertex whose colour is not three numbers, or that lacks the colour its predecessors have
/// (or has one they lack), by line and vertex number.
fn vertex_colour_problem(bytes: &[u8]) -> Option<String> {
    let text = String::from_utf8_lossy(bytes);
    let mut first: Option<(usize, bool)> = None; // (line, has a colour) of the first vertex
    let mut vertex = 0usize;
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("v") {
            continue;
        }
        vertex += 1;
        let rest: Vec<&str> = words.collect();
        let at = format!("line {}, vertex {vertex}", n + 1);
        if rest.len() != 3 && rest.len() != 4 && rest.len() != 6 {
            return Some(format!("{at}: {} values (x y z, x y z w or x y z r g b)", rest.len()));
        }
        let coloured = rest.len() == 6;
        if coloured {
            if let Some(bad) = rest[3..].iter().find(|w| !w.parse::<f32>().is_ok_and(f32::is_finite)) {
                return Some(format!("{at}: vertex colour component '{bad}' is not a finite number"));
            }
        }
        match first {
            None => first = Some((n + 1, coloured)),
            Some((l, c)) if c != coloured => {
                let (this, that) = if coloured { ("a colour", "none") } else { ("no colour", "one") };
                return Some(format!(
                    "{at}: has {this} but vertex 1 (line {l}) has {that}; vertex colours must be given for every vertex or none"
                ));
            }
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_vertex_colour_is_named_by_line_and_vertex() {
        let limits = LoadLimits::default();
        let obj = |text: &str| match from_slice(text.as_bytes(), "t", None, &limits) {
            Err(e) => e.to_string(),
            Ok(_) => "loaded".into(),
        };
        let e = obj("v 0 0 0 1 1 1\nv 1 0 0 1 nan? 1\nv 0 1 0 1 1 1\nf 1 2 3\n");
        assert!(e.contains("line 2, vertex 2") && e.contains("'nan?'") && e.contains("finite"), "{e}");
        let e = obj("v 0 0 0 1 1 1\nv 1 0 0\nv 0 1 0 1 1 1\nf 1 2 3\n");
        assert!(e.contains("line 2, vertex 2") && e.contains("every vertex or none"), "{e}");
        assert!(!e.contains("out of bounds"), "{e}");
    }

    #[test]
    fn texture_names_keep_their_spaces_and_lose_their_options() {
        assert_eq!(texture_file_name("wood.png"), "wood.png");
        assert_eq!(texture_file_name("  this texture has spaces.jpg "), "this texture has spaces.jpg");
        assert_eq!(texture_file_name("-bm 0.5 bump map.png"), "bump map.png");
        assert_eq!(texture_file_name("-o 0.1 0.2 -s 2 -clamp on my file.png"), "my file.png");
        assert_eq!(texture_file_name("-mm 0 1 a.png"), "a.png");
        assert_eq!(texture_file_name("-bm 2.png"), "2.png", "a name is never eaten as an argument");
    }

    #[test]
    fn mtl_colours_of_one_number_are_greys_and_of_two_are_refused() {
        let text = b"newmtl a\nKd 0.5\r\nKs 1 0 0\nKa 0.25 \nmap_Kd x.png";
        let out = normalize_mtl(text).unwrap();
        assert_eq!(out, b"newmtl a\nKd 0.5 0.5 0.5\nKs 1 0 0\nKa 0.25 0.25 0.25\nmap_Kd x.png");
        let m = tobj::load_mtl_buf(&mut std::io::Cursor::new(out)).unwrap().0;
        assert_eq!(m[0].diffuse, Some([0.5; 3]));
        assert_eq!(
            normalize_mtl(b"newmtl a\nKe 1 2\n").unwrap_err(),
            "line 2: Ke needs one or three numbers"
        );
        assert!(normalize_mtl(b"Kd\n").is_err());
    }

    #[test]
    fn shininess_maps_to_roughness_monotonically() {
        assert!((roughness_from_shininess(0.0) - 1.0).abs() < 1e-6);
        let mut last = 1.0;
        for ns in [1.0, 10.0, 100.0, 1000.0] {
            let r = roughness_from_shininess(ns);
            assert!(r < last && r > 0.0, "Ns {ns} → {r}");
            last = r;
        }
        assert!((roughness_from_shininess(1000.0) - 0.2113).abs() < 1e-3);
    }
}
