//! Hand-written glTF and OBJ files for the loader tests: a small builder that lays vertex
//! data into one binary buffer with a view and an accessor per stream, and writes the
//! document as `.gltf` (buffer as a data URI or an external file) or as `.glb`.

#![allow(dead_code)]

use base64::Engine;
use serde_json::{json, Value};

/// glTF component types.
pub const FLOAT: u32 = 5126;
/// Unsigned 8-bit.
pub const U8: u32 = 5121;
/// Unsigned 16-bit.
pub const U16: u32 = 5123;
/// Unsigned 32-bit.
pub const U32: u32 = 5125;

/// A glTF document under construction.
#[derive(Default)]
pub struct Doc {
    pub bin: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
    pub meshes: Vec<Value>,
    pub nodes: Vec<Value>,
    pub materials: Vec<Value>,
    pub lights: Vec<Value>,
    pub cameras: Vec<Value>,
    pub images: Vec<Value>,
    pub textures: Vec<Value>,
    pub roots: Vec<usize>,
    /// Further top-level properties (`animations` …), written as given.
    pub extra: Vec<(&'static str, Value)>,
}

impl Doc {
    /// Appends raw bytes as a buffer view (4-byte aligned) and returns its index.
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.views.push(json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()}));
        self.bin.extend_from_slice(bytes);
        self.views.len() - 1
    }

    /// An accessor of `count` elements of `ty` over a new view of `bytes`.
    pub fn accessor(&mut self, bytes: &[u8], component: u32, ty: &str, count: usize) -> usize {
        let view = self.view(bytes);
        self.accessors
            .push(json!({"bufferView": view, "componentType": component, "type": ty, "count": count}));
        self.accessors.len() - 1
    }

    /// A VEC3 float accessor (with the min/max glTF requires for positions).
    pub fn vec3(&mut self, v: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = v.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        let a = self.accessor(&bytes, FLOAT, "VEC3", v.len());
        let lo = (0..3).map(|k| v.iter().map(|p| p[k]).fold(f32::INFINITY, f32::min)).collect::<Vec<_>>();
        let hi = (0..3).map(|k| v.iter().map(|p| p[k]).fold(f32::NEG_INFINITY, f32::max)).collect::<Vec<_>>();
        self.accessors[a]["min"] = json!(lo);
        self.accessors[a]["max"] = json!(hi);
        a
    }

    /// A VEC2 float accessor.
    pub fn vec2(&mut self, v: &[[f32; 2]]) -> usize {
        let bytes: Vec<u8> = v.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        self.accessor(&bytes, FLOAT, "VEC2", v.len())
    }

    /// A u32 index accessor.
    pub fn indices(&mut self, i: &[u32]) -> usize {
        let bytes: Vec<u8> = i.iter().flat_map(|x| x.to_le_bytes()).collect();
        self.accessor(&bytes, U32, "SCALAR", i.len())
    }

    /// A mesh of one primitive; returns the mesh index.
    pub fn mesh(&mut self, attributes: Value, indices: Option<usize>, material: Option<usize>) -> usize {
        let mut prim = json!({"attributes": attributes});
        if let Some(i) = indices {
            prim["indices"] = json!(i);
        }
        if let Some(m) = material {
            prim["material"] = json!(m);
        }
        self.meshes.push(json!({"primitives": [prim]}));
        self.meshes.len() - 1
    }

    /// A node; returns its index.
    pub fn node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// The JSON document with the buffer given by `buffer` (a URI or none for GLB).
    pub fn json(&self, uri: Option<String>) -> Value {
        let mut buffer = json!({"byteLength": self.bin.len()});
        if let Some(u) = uri {
            buffer["uri"] = json!(u);
        }
        let mut doc = json!({
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": self.roots}],
            "nodes": self.nodes,
            "meshes": self.meshes,
            "accessors": self.accessors,
            "bufferViews": self.views,
            "buffers": [buffer],
        });
        let mut used = Vec::new();
        for (key, list) in [
            ("materials", &self.materials),
            ("cameras", &self.cameras),
            ("images", &self.images),
            ("textures", &self.textures),
        ] {
            if !list.is_empty() {
                doc[key] = json!(list);
            }
        }
        for (key, value) in &self.extra {
            doc[*key] = value.clone();
        }
        if !self.lights.is_empty() {
            doc["extensions"] = json!({"KHR_lights_punctual": {"lights": self.lights}});
            used.push("KHR_lights_punctual");
        }
        let text = doc.to_string();
        for ext in ["KHR_materials_transmission", "KHR_materials_ior"] {
            if text.contains(ext) {
                used.push(ext);
            }
        }
        if !used.is_empty() {
            doc["extensionsUsed"] = json!(used);
        }
        doc
    }

    /// `.gltf` text with the buffer embedded as a base64 data URI.
    pub fn gltf_embedded(&self) -> Vec<u8> {
        let b64 = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        self.json(Some(format!("data:application/octet-stream;base64,{b64}"))).to_string().into_bytes()
    }

    /// `.glb` bytes: header, JSON chunk (space-padded), BIN chunk (zero-padded).
    pub fn glb(&self) -> Vec<u8> {
        let mut json = self.json(None).to_string().into_bytes();
        json.resize(json.len().next_multiple_of(4), b' ');
        let mut bin = self.bin.clone();
        bin.resize(bin.len().next_multiple_of(4), 0);
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        out
    }
}

/// One triangle in the z = 0 plane facing +Z (no normals), as a one-node document.
pub fn triangle() -> Doc {
    let mut d = Doc::default();
    let pos = d.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = d.indices(&[0, 1, 2]);
    let mesh = d.mesh(json!({"POSITION": pos}), Some(idx), None);
    let node = d.node(json!({"mesh": mesh}));
    d.roots.push(node);
    d
}

/// A 2×2 RGBA PNG with the given texels.
pub fn png(texels: [[u8; 4]; 4]) -> Vec<u8> {
    let img = image::RgbaImage::from_fn(2, 2, |x, y| image::Rgba(texels[(y * 2 + x) as usize]));
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).expect("encode png");
    out.into_inner()
}

/// A unit cube as an OBJ with quads, negative indices on two faces and a material library.
pub const CUBE_OBJ: &str = "\
mtllib cube.mtl
o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl red
f 1/1 4/4 3/3 2/2
f 5/1 6/2 7/3 8/4
f 1/1 2/2 6/3 5/4
f 2/1 3/2 7/3 6/4
f -5/1 -1/2 -2/3 -6/4
f -8/1 -4/2 -1/3 -5/4
o pentagon
v 3 0 0
v 4 0 0
v 4.3 1 0
v 3.5 1.6 0
v 2.7 1 0
usemtl glass
f -5 -4 -3 -2 -1
";

/// The cube's materials.
pub const CUBE_MTL: &str = "\
newmtl red
Kd 0.8 0.1 0.1
Ns 100
Ke 0.5 0.25 0
map_Kd red.png
newmtl glass
Kd 1 1 1
Ni 1.45
d 0.1
Pm 0.0
";
