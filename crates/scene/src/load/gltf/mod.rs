//! glTF 2.0 (`.gltf` and `.glb`) into a [`HybridScene`].
//!
//! What is read: the default scene's node tree (flattened: every mesh primitive under a
//! node becomes one [`Instance`] with the node's world transform), triangle primitives
//! (positions, normals — flat ones computed when missing, as the specification asks —,
//! the first UV set, tangents — computed when missing —, indexed or not, sparse accessors
//! included; COLOR_0 vertex colours, drawn through a texture baked for the primitive when
//! its material has no texture of its own), metal–roughness materials with their
//! base-colour (decoded from sRGB), metal–roughness and normal textures, emissive colour
//! (emitted from the back face only where the material is `doubleSided`),
//! `KHR_texture_transform` (applied to the primitive's UVs: the scene's material has one UV
//! map, so the base colour's transform serves all its textures, with a warning when they
//! differ), `KHR_materials_transmission` and `KHR_materials_ior`, `KHR_lights_punctual` lights
//! (pointing down their node's −Z) and perspective cameras (aspect from the file, else 16:9, at 1920 pixels wide). Animations,
//! skins and morph targets are not read (the scene is drawn at rest); an `animations` array
//! that does not parse is dropped with a warning.
//!
//! Units: light intensities are carried over as numbers (candela → the lab's radiant
//! intensity, lux → irradiance), so a file's relative lighting is kept; the lab's
//! renderers expose the image, not absolute photometry.
//!
//! Buffers and images are resolved here rather than by the `gltf` crate's importer, so that
//! data URIs are decoded with `base64`, images with the workspace's `image` codecs, and
//! every size is checked before anything is allocated. Each accessor is checked against its
//! buffer before it is read, so that no count can ask for more than the file holds; an
//! accessor without a buffer view (zeros but for its sparse elements) holds at most
//! [`MAX_SPARSE_ONLY_ELEMENTS`].

use super::common::{finish, read_limited, resolve, LoadLimits, LoadedScene, Problem};
use super::geometry::{clean, NormalRule, RawMesh};
use super::textures::vertex_colors;
use crate::light::{Light, LightKind};
use crate::scene::{HybridScene, Instance, SceneCamera};
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::khr_lights_punctual::Kind;
use ::gltf::{buffer, camera::Projection, Accessor, Document, Gltf, Semantic};
use assembly::{assemble, assembled_count};
use base64::Engine;
use glam::{Affine3A, Mat4, Vec2, Vec3, Vec4};
use renderlab_core::Camera;
use std::collections::HashMap;
use std::path::Path;

mod assembly;
mod material;

/// Deepest node nesting followed; deeper trees (or cycles) are refused.
const MAX_DEPTH: usize = 256;

/// Most elements of an accessor without a buffer view. Such an accessor is all zeros but
/// for its sparse elements, so its `count` is bounded by nothing in the file: a few bytes of
/// JSON could otherwise ask for gigabytes. 2^20 elements are 16 MiB as `VEC4` floats, more
/// than any zero-filled attribute of a real model needs (sparse data is used for morph
/// targets, which are not read; an attribute of a drawn mesh normally has a buffer view).
pub const MAX_SPARSE_ONLY_ELEMENTS: usize = 1 << 20;

/// Loads a glTF document from memory. `base` is the folder that relative URIs are
/// resolved against (`None`: only embedded data is allowed).
pub fn from_slice(
    bytes: &[u8],
    name: &str,
    base: Option<&Path>,
    limits: &LoadLimits,
) -> Result<LoadedScene, Problem> {
    let (Gltf { document, blob }, parse_note) = parse(bytes)?;
    let buffers = load_buffers(&document, blob, base, limits)?;
    let mut loader = Loader {
        document: &document,
        buffers: &buffers,
        base,
        limits,
        scene: HybridScene::empty(name, Vec3::ZERO),
        warnings: parse_note.into_iter().collect(),
        textures: HashMap::new(),
        materials: HashMap::new(),
        primitives: HashMap::new(),
        triangles: 0,
        dropped: 0,
    };
    let root = document.default_scene().or_else(|| document.scenes().next());
    match root {
        Some(scene) => {
            // Depth first in document order (children pushed reversed onto the stack).
            let mut stack: Vec<(::gltf::Node, Affine3A, usize)> =
                scene.nodes().map(|n| (n, Affine3A::IDENTITY, 0)).collect();
            stack.reverse();
            let mut visits = 0usize;
            while let Some((node, parent, depth)) = stack.pop() {
                visits += 1;
                if depth > MAX_DEPTH || visits > document.nodes().len().saturating_mul(64).max(1024) {
                    return Err(Problem::Invalid("the node hierarchy is too deep or has a cycle".into()));
                }
                let local = Affine3A::from_mat4(Mat4::from_cols_array_2d(&node.transform().matrix()));
                let world = parent * local;
                loader.node(&node, world)?;
                let first = stack.len();
                stack.extend(node.children().map(|c| (c, world, depth + 1)));
                stack[first..].reverse();
            }
        }
        None => loader.warnings.push("the file has no scene: nothing to draw".into()),
    }
    let mut warnings = loader.warnings;
    if loader.dropped > 0 {
        warnings.push(format!("dropped {} degenerate triangles", loader.dropped));
    }
    let scene = finish(loader.scene, &mut warnings)?;
    Ok(LoadedScene { scene, warnings })
}

/// Parses and validates the document; the second value is a warning when the document's
/// `animations` had to be dropped to read it.
///
/// Animations are not read (the scene is drawn at rest), so an `animations` array that the
/// parser refuses (older exporters wrote `"id"` for a channel's `"node"`) or that fails
/// validation is dropped, with a warning, rather than refusing the whole file.
///
/// The `gltf` crate's validation indexes the accessor list with a primitive's POSITION
/// index before checking it, so that index is checked here first; any other panic inside
/// the parser (none known) is caught and reported as a malformed file rather than taking
/// the program down.
fn parse(bytes: &[u8]) -> Result<(Gltf, Option<String>), Problem> {
    let parsed = std::panic::catch_unwind(|| {
        let (json, blob) = if bytes.starts_with(b"glTF") {
            let glb = ::gltf::binary::Glb::from_slice(bytes).map_err(|e| Problem::Gltf(e.to_string()))?;
            (glb.json.into_owned(), glb.bin.map(|b| b.into_owned()))
        } else {
            (bytes.to_vec(), None)
        };
        let mut value: ::gltf::json::Value =
            ::gltf::json::deserialize::from_slice(&json).map_err(|e| Problem::Gltf(e.to_string()))?;
        let document = match document_of(value.clone()) {
            Ok(document) => (document, None),
            Err(first) => {
                let dropped = value.as_object_mut().and_then(|root| root.remove("animations")).is_some();
                match document_of(value) {
                    Ok(document) if dropped => {
                        (document, Some(format!("animations ignored: they do not parse ({first})")))
                    }
                    _ => return Err(first),
                }
            }
        };
        Ok((Gltf { document: document.0, blob }, document.1))
    });
    parsed.unwrap_or_else(|_| Err(Problem::Gltf("the parser failed on malformed input".into())))
}

/// The validated document of a parsed JSON tree.
fn document_of(value: ::gltf::json::Value) -> Result<Document, Problem> {
    let root: ::gltf::json::Root =
        ::gltf::json::deserialize::from_value(value).map_err(|e| Problem::Gltf(e.to_string()))?;
    for (m, mesh) in root.meshes.iter().enumerate() {
        for prim in &mesh.primitives {
            let accessors =
                prim.attributes.values().map(|a| a.value()).chain(prim.indices.as_ref().map(|i| i.value()));
            if let Some(bad) = accessors.into_iter().find(|&a| a >= root.accessors.len()) {
                return Err(Problem::Gltf(format!(
                    "mesh {m} refers to accessor {bad}, which does not exist"
                )));
            }
        }
    }
    Document::from_json(root).map_err(|e| Problem::Gltf(e.to_string()))
}

/// Every buffer's bytes: the GLB binary chunk, a data URI or an external file.
fn load_buffers(
    document: &Document,
    blob: Option<Vec<u8>>,
    base: Option<&Path>,
    limits: &LoadLimits,
) -> Result<Vec<Vec<u8>>, Problem> {
    let mut blob = blob;
    let mut out = Vec::new();
    for b in document.buffers() {
        let data = match b.source() {
            buffer::Source::Bin => blob.take().ok_or_else(|| {
                Problem::Invalid(format!("buffer {} refers to a missing GLB binary chunk", b.index()))
            })?,
            buffer::Source::Uri(uri) => uri_bytes(uri, base, limits)?,
        };
        if data.len() < b.length() {
            return Err(Problem::Invalid(format!(
                "buffer {} has {} bytes, but the file declares {}",
                b.index(),
                data.len(),
                b.length()
            )));
        }
        out.push(data);
    }
    Ok(out)
}

/// The bytes a URI names: `data:…;base64,…` or a file relative to `base`.
fn uri_bytes(uri: &str, base: Option<&Path>, limits: &LoadLimits) -> Result<Vec<u8>, Problem> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or_else(|| Problem::Invalid("a data URI is not base64-encoded".into()))?;
        if payload.len() as u64 / 4 * 3 > limits.max_file_bytes {
            return Err(Problem::TooLarge {
                size: payload.len() as u64 / 4 * 3,
                limit: limits.max_file_bytes,
            });
        }
        return base64::engine::general_purpose::STANDARD
            .decode(payload.trim_end())
            .map_err(|e| Problem::Invalid(format!("a data URI does not decode: {e}")));
    }
    let path = resolve(base, &percent_decode(uri))?;
    read_limited(&path, limits)
}

/// Undoes URI percent-encoding (`%20` → space); malformed escapes are kept as written.
fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The state of one load: the document, its buffers, what has been converted so far.
struct Loader<'a> {
    document: &'a Document,
    buffers: &'a [Vec<u8>],
    base: Option<&'a Path>,
    limits: &'a LoadLimits,
    scene: HybridScene,
    warnings: Vec<String>,
    /// (image index, sRGB) → scene texture.
    textures: HashMap<(usize, bool), u32>,
    /// glTF material index (`None`: the default material) → scene material.
    materials: HashMap<Option<usize>, u32>,
    /// (mesh, primitive) → (scene mesh, scene material), `None` when it has no triangles.
    primitives: HashMap<(usize, usize), Option<(u32, u32)>>,
    triangles: usize,
    dropped: usize,
}

impl Loader<'_> {
    /// Converts what a node carries (mesh, light, camera) under its world transform.
    fn node(&mut self, node: &::gltf::Node, world: Affine3A) -> Result<(), Problem> {
        let name = node.name().map_or_else(|| format!("node {}", node.index()), str::to_string);
        if let Some(mesh) = node.mesh() {
            if !world.is_finite() || world.matrix3.determinant().abs() < 1e-30 {
                self.warnings.push(format!("{name}: singular or non-finite transform, mesh skipped"));
            } else {
                for prim in mesh.primitives() {
                    if let Some((m, mat)) = self.primitive(&mesh, &prim)? {
                        self.scene.instances.push(Instance {
                            name: name.clone(),
                            mesh: m,
                            material: mat,
                            transform: world,
                        });
                    }
                }
            }
        }
        let position = world.translation.into();
        let axis = |v: Vec3| world.transform_vector3(v).try_normalize();
        if let Some(light) = node.light() {
            let Some(direction) = axis(Vec3::NEG_Z) else {
                self.warnings.push(format!("{name}: light with a degenerate transform skipped"));
                return Ok(());
            };
            let kind = match light.kind() {
                Kind::Directional => LightKind::Directional,
                Kind::Point => LightKind::Point,
                Kind::Spot { inner_cone_angle, outer_cone_angle } => {
                    let outer = finite_or(outer_cone_angle, std::f32::consts::FRAC_PI_4)
                        .clamp(1e-3, std::f32::consts::FRAC_PI_2);
                    let inner = finite_or(inner_cone_angle, 0.0).clamp(0.0, outer - 1e-3 * outer);
                    LightKind::Spot { inner_cone: inner, outer_cone: outer }
                }
            };
            let color = Vec3::from(light.color());
            let intensity = light.intensity();
            if !(color.is_finite() && intensity.is_finite() && intensity >= 0.0) {
                return Err(Problem::Invalid(format!(
                    "{name}: light colour or intensity is not a finite, non-negative number"
                )));
            }
            self.scene.lights.push(Light {
                name: light.name().map_or_else(|| name.clone(), str::to_string),
                kind,
                position,
                direction,
                color,
                intensity,
                range: light.range().filter(|r| r.is_finite() && *r > 0.0),
            });
        }
        if let Some(camera) = node.camera() {
            match camera.projection() {
                Projection::Perspective(p) => {
                    let (Some(forward), Some(up)) = (axis(Vec3::NEG_Z), axis(Vec3::Y)) else {
                        self.warnings.push(format!("{name}: camera with a degenerate transform skipped"));
                        return Ok(());
                    };
                    let aspect = p
                        .aspect_ratio()
                        .filter(|a| a.is_finite() && (0.1..=10.0).contains(a))
                        .unwrap_or(16.0 / 9.0);
                    let fov = p.yfov().to_degrees();
                    let near = p.znear();
                    let far = p.zfar().unwrap_or(near * 1e5);
                    if !(fov.is_finite()
                        && fov > 0.0
                        && fov < 180.0
                        && near.is_finite()
                        && near > 0.0
                        && far.is_finite()
                        && far > near)
                    {
                        return Err(Problem::Invalid(format!(
                            "{name}: camera field of view or clipping distances out of range"
                        )));
                    }
                    let width = 1920u32;
                    let height = ((width as f32 / aspect).round() as u32).max(1);
                    let camera = Camera { position, forward, up, fov_y_deg: fov, width, height, near, far };
                    let cam_name = node.camera().and_then(|c| c.name().map(str::to_string)).unwrap_or(name);
                    self.scene.cameras.push(SceneCamera { name: cam_name, camera });
                }
                Projection::Orthographic(_) => {
                    self.warnings.push(format!("{name}: orthographic camera ignored"))
                }
            }
        }
        Ok(())
    }

    /// The scene mesh and material of a primitive, converted once however many nodes use it.
    fn primitive(
        &mut self,
        mesh: &::gltf::Mesh,
        prim: &::gltf::Primitive,
    ) -> Result<Option<(u32, u32)>, Problem> {
        let key = (mesh.index(), prim.index());
        if let Some(&done) = self.primitives.get(&key) {
            return Ok(done);
        }
        let result = self.convert_primitive(mesh, prim)?;
        self.primitives.insert(key, result);
        Ok(result)
    }

    fn convert_primitive(
        &mut self,
        mesh: &::gltf::Mesh,
        prim: &::gltf::Primitive,
    ) -> Result<Option<(u32, u32)>, Problem> {
        let label = format!(
            "{} primitive {}",
            mesh.name().map_or_else(|| format!("mesh {}", mesh.index()), str::to_string),
            prim.index()
        );
        use ::gltf::mesh::Mode;
        let mode = prim.mode();
        if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            self.warnings.push(format!("{label}: mode {mode:?} draws no triangles, skipped"));
            return Ok(None);
        }
        let Some(pos_acc) = prim.get(&Semantic::Positions) else {
            self.warnings.push(format!("{label}: no positions, skipped"));
            return Ok(None);
        };
        check(&pos_acc, &[DataType::F32], Dimensions::Vec3, self.buffers, &label)?;
        if prim.indices().is_none() && assembled_count(mode, pos_acc.count()) > self.limits.max_triangles {
            return Err(Problem::Invalid(format!(
                "{label}: more than {} triangles",
                self.limits.max_triangles
            )));
        }
        let buffers = self.buffers;
        let reader = prim.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let unreadable =
            |what: &str| Problem::Invalid(format!("{label}: the {what} accessor does not fit its buffer"));
        let positions: Vec<Vec3> =
            reader.read_positions().ok_or_else(|| unreadable("position"))?.map(Vec3::from).collect();
        let normals = match prim.get(&Semantic::Normals) {
            Some(a) => {
                check(&a, &[DataType::F32], Dimensions::Vec3, buffers, &label)?;
                Some(reader.read_normals().ok_or_else(|| unreadable("normal"))?.map(Vec3::from).collect())
            }
            None => None,
        };
        let tangents = match prim.get(&Semantic::Tangents) {
            Some(a) => {
                check(&a, &[DataType::F32], Dimensions::Vec4, buffers, &label)?;
                Some(reader.read_tangents().ok_or_else(|| unreadable("tangent"))?.map(Vec4::from).collect())
            }
            None => None,
        };
        let uvs: Option<Vec<Vec2>> = match prim.get(&Semantic::TexCoords(0)) {
            Some(a) => {
                check(&a, &[DataType::F32, DataType::U8, DataType::U16], Dimensions::Vec2, buffers, &label)?;
                Some(
                    reader
                        .read_tex_coords(0)
                        .ok_or_else(|| unreadable("texture coordinate"))?
                        .into_f32()
                        .map(Vec2::from)
                        .collect(),
                )
            }
            None => None,
        };
        let uvs = match (uvs, self.uv_transform(&prim.material(), &label)) {
            (Some(uvs), Some(t)) => Some(uvs.into_iter().map(|p| t.apply(p)).collect()),
            (uvs, _) => uvs,
        };
        let colors = match prim.get(&Semantic::Colors(0)) {
            Some(a) => {
                let dims =
                    if a.dimensions() == Dimensions::Vec3 { Dimensions::Vec3 } else { Dimensions::Vec4 };
                check(&a, &[DataType::F32, DataType::U8, DataType::U16], dims, buffers, &label)?;
                Some(
                    reader
                        .read_colors(0)
                        .ok_or_else(|| unreadable("colour"))?
                        .into_rgba_f32()
                        .map(Vec4::from)
                        .collect(),
                )
            }
            None => None,
        };
        let triangles = match prim.indices() {
            Some(a) => {
                check(
                    &a,
                    &[DataType::U8, DataType::U16, DataType::U32],
                    Dimensions::Scalar,
                    buffers,
                    &label,
                )?;
                // Refused before the indices are read and assembled, not after.
                if assembled_count(mode, a.count()) > self.limits.max_triangles {
                    return Err(Problem::Invalid(format!(
                        "{label}: more than {} triangles",
                        self.limits.max_triangles
                    )));
                }
                let idx: Vec<u32> =
                    reader.read_indices().ok_or_else(|| unreadable("index"))?.into_u32().collect();
                assemble(mode, &idx)
            }
            None => {
                let idx: Vec<u32> = (0..positions.len() as u32).collect();
                assemble(mode, &idx)
            }
        };
        let raw = RawMesh { name: label.clone(), positions, normals, uvs, tangents, colors, triangles };
        let mut cleaned = clean(raw, NormalRule::Flat)?;
        self.dropped += cleaned.dropped;
        self.warnings.extend(cleaned.notes);
        if cleaned.mesh.triangles.is_empty() {
            self.warnings.push(format!("{label}: no drawable triangles, skipped"));
            return Ok(None);
        }
        self.triangles += cleaned.mesh.triangles.len();
        if self.triangles > self.limits.max_triangles {
            return Err(Problem::Invalid(format!("more than {} triangles", self.limits.max_triangles)));
        }
        let mut material = self.material(prim.material())?;
        if let Some(colors) = cleaned.colors.take() {
            material =
                vertex_colors(&mut self.scene, &mut cleaned.mesh, &colors, material, self.limits, &label)
                    .unwrap_or_else(|why| {
                        self.warnings.push(why);
                        material
                    });
        }
        self.scene.meshes.push(cleaned.mesh);
        Ok(Some(((self.scene.meshes.len() - 1) as u32, material)))
    }
}

/// Checks an accessor before the `gltf` crate's reader touches it: the component type and
/// shape the attribute needs, a stride no smaller than an element, and every element
/// (including a sparse accessor's indices and values) inside its buffer.
fn check(
    a: &Accessor,
    types: &[DataType],
    dims: Dimensions,
    buffers: &[Vec<u8>],
    label: &str,
) -> Result<(), Problem> {
    let bad = |why: String| Err(Problem::Invalid(format!("{label}: accessor {}: {why}", a.index())));
    if !types.contains(&a.data_type()) || a.dimensions() != dims {
        return bad(format!(
            "{:?} {:?} where {dims:?} of {types:?} is needed",
            a.dimensions(),
            a.data_type()
        ));
    }
    if a.count() == 0 {
        return bad("it has no elements".into());
    }
    let elem = a.size();
    let fits = |view: &::gltf::buffer::View, offset: usize, count: usize, size: usize| -> bool {
        let stride = view.stride().unwrap_or(size);
        let Some(data) = buffers.get(view.buffer().index()) else { return false };
        let span = stride
            .checked_mul(count - 1)
            .and_then(|s| s.checked_add(size))
            .and_then(|s| s.checked_add(offset));
        let view_end = view.offset().checked_add(view.length());
        stride >= size
            && span.is_some_and(|s| s <= view.length())
            && view_end.is_some_and(|e| e <= data.len())
    };
    match a.view() {
        Some(view) if !fits(&view, a.offset(), a.count(), elem) => {
            return bad("its elements lie outside the buffer".into())
        }
        None if a.sparse().is_none() => return bad("it has neither a buffer view nor sparse data".into()),
        None if a.count() > MAX_SPARSE_ONLY_ELEMENTS => {
            return bad(format!(
                "{} elements without a buffer view (at most {MAX_SPARSE_ONLY_ELEMENTS} are read)",
                a.count()
            ))
        }
        _ => {}
    }
    if let Some(sparse) = a.sparse() {
        let n = sparse.count();
        let idx = sparse.indices();
        let vals = sparse.values();
        if n == 0
            || n > a.count()
            || !fits(&idx.view(), idx.offset(), n, idx.index_type().size())
            || !fits(&vals.view(), vals.offset(), n, elem)
        {
            return bad("its sparse indices or values lie outside the buffer".into());
        }
        // Every sparse index must address an element; the reader assumes they increase.
        let data = &buffers[idx.view().buffer().index()];
        let stride = idx.view().stride().unwrap_or(idx.index_type().size());
        let mut last: Option<u64> = None;
        for k in 0..n {
            let at = idx.view().offset() + idx.offset() + k * stride;
            let v = match idx.index_type() {
                ::gltf::accessor::sparse::IndexType::U8 => u64::from(data[at]),
                ::gltf::accessor::sparse::IndexType::U16 => {
                    u64::from(u16::from_le_bytes([data[at], data[at + 1]]))
                }
                ::gltf::accessor::sparse::IndexType::U32 => {
                    u64::from(u32::from_le_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]]))
                }
            };
            if v >= a.count() as u64 || last.is_some_and(|l| v <= l) {
                return bad("its sparse indices are out of range or not increasing".into());
            }
            last = Some(v);
        }
    }
    Ok(())
}

fn finite_or(x: f32, default: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        default
    }
}
