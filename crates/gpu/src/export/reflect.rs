//! A module's inputs and outputs from naga's reflection: its bound global variables (uniform
//! blocks, textures, samplers, storage buffers and storage textures, with the entry points
//! that use each), the members of its uniform blocks (with their byte offsets), and the
//! arguments and results of its entry points (vertex attributes, varyings, built-ins,
//! fragment outputs, compute built-ins).
//!
//! Each item carries a **key**, the name the description table is indexed by: the variable's
//! name for a global (`albedo_map`), `Struct.member` for a struct member (`Frame.eye`,
//! `VertexIn.uv`, `DebugOut.layers`), `entry.argument` for an entry point's plain argument
//! (`fs_main.position`) and `entry.result` for its plain result.

use super::backends::{resource_class, ResourceClass};
use super::source::Parsed;
use naga::common::wgsl::TypeContext;
use naga::{Binding, ShaderStage, TypeInner};

/// What kind of input or output an item is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ItemKind {
    /// A uniform block.
    Uniform,
    /// A member of a uniform block.
    UniformMember,
    /// A sampled texture.
    Texture,
    /// A sampler.
    Sampler,
    /// A storage buffer; `writable` when declared `read_write`.
    StorageBuffer {
        /// Whether the shader may write it.
        writable: bool,
    },
    /// A storage texture, written texel by texel.
    StorageTexture,
    /// A compute entry point's built-in input (its invocation's place in the dispatch).
    ComputeInput,
    /// A vertex stage input (attribute or built-in).
    VertexInput,
    /// A value from the vertex stage to the fragment stage, or a fragment built-in input.
    Varying,
    /// A fragment stage output.
    FragmentOutput,
}

impl ItemKind {
    /// Its name in the README.
    pub fn label(self) -> &'static str {
        match self {
            ItemKind::Uniform => "uniform block",
            ItemKind::UniformMember => "uniform member",
            ItemKind::Texture => "texture",
            ItemKind::Sampler => "sampler",
            ItemKind::StorageBuffer { writable: false } => "storage buffer (read-only)",
            ItemKind::StorageBuffer { writable: true } => "storage buffer (read-write)",
            ItemKind::StorageTexture => "storage texture",
            ItemKind::ComputeInput => "compute input",
            ItemKind::VertexInput => "vertex input",
            ItemKind::Varying => "varying",
            ItemKind::FragmentOutput => "fragment output",
        }
    }

    /// Whether it is a resource the shader writes (a storage texture or a read-write storage
    /// buffer).
    pub fn is_output(self) -> bool {
        matches!(self, ItemKind::StorageTexture | ItemKind::StorageBuffer { writable: true })
    }

    /// Whether it is a bound resource (a uniform block, texture, sampler, storage buffer or
    /// storage texture) rather than a uniform member or a stage input or output.
    pub fn is_resource(self) -> bool {
        matches!(
            self,
            ItemKind::Uniform
                | ItemKind::Texture
                | ItemKind::Sampler
                | ItemKind::StorageBuffer { .. }
                | ItemKind::StorageTexture
        )
    }
}

/// One input or output of a module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Item {
    /// The description table's key (see the module docs).
    pub key: String,
    /// What it is.
    pub kind: ItemKind,
    /// Its WGSL type.
    pub ty: String,
    /// Where it sits: `@group(1) @binding(3)`, `offset 64`, `@location(0)`, `@builtin(position)`.
    pub place: String,
    /// The entry points that read or write it.
    pub entry_points: Vec<String>,
}

/// Every input and output of `parsed`: the bound globals in (group, binding) order, each
/// uniform block followed by its members, then the entry points' inputs and outputs in
/// entry-point order, each key once.
pub fn items(parsed: &Parsed) -> Vec<Item> {
    let module = &parsed.module;
    let types = &module.types;
    let mut out: Vec<Item> = Vec::new();
    let mut globals: Vec<_> = module.global_variables.iter().filter(|(_, g)| g.binding.is_some()).collect();
    globals.sort_by_key(|(_, g)| g.binding.as_ref().map(|b| (b.group, b.binding)));
    for (handle, g) in globals {
        let Some(rb) = g.binding.as_ref() else { continue };
        let users: Vec<String> = module
            .entry_points
            .iter()
            .enumerate()
            .filter(|(i, _)| !parsed.info.get_entry_point(*i)[handle].is_empty())
            .map(|(_, ep)| ep.name.clone())
            .collect();
        let inner = &types[g.ty].inner;
        let kind = match resource_class(module, g) {
            Some(ResourceClass::Sampler) => ItemKind::Sampler,
            Some(ResourceClass::Texture) => ItemKind::Texture,
            Some(ResourceClass::Uniform) => ItemKind::Uniform,
            Some(ResourceClass::StorageBuffer { writable }) => ItemKind::StorageBuffer { writable },
            Some(ResourceClass::StorageTexture) => ItemKind::StorageTexture,
            None => continue,
        };
        out.push(Item {
            key: g.name.clone().unwrap_or_default(),
            kind,
            ty: types.type_to_string(g.ty),
            place: format!("@group({}) @binding({})", rb.group, rb.binding),
            entry_points: users.clone(),
        });
        if let (ItemKind::Uniform, TypeInner::Struct { members, .. }) = (kind, inner) {
            let struct_name = types[g.ty].name.clone().unwrap_or_default();
            for m in members.iter().filter(|m| !is_padding(m.name.as_deref())) {
                out.push(Item {
                    key: format!("{struct_name}.{}", m.name.as_deref().unwrap_or_default()),
                    kind: ItemKind::UniformMember,
                    ty: types.type_to_string(m.ty),
                    place: format!("offset {}", m.offset),
                    entry_points: users.clone(),
                });
            }
        }
    }
    for ep in &module.entry_points {
        let (input_kind, output_kind) = match ep.stage {
            ShaderStage::Vertex => (ItemKind::VertexInput, ItemKind::Varying),
            // A compute entry point has no result; it writes storage resources.
            ShaderStage::Compute => (ItemKind::ComputeInput, ItemKind::ComputeInput),
            _ => (ItemKind::Varying, ItemKind::FragmentOutput),
        };
        let f = &ep.function;
        for arg in &f.arguments {
            let plain = format!("{}.{}", ep.name, arg.name.as_deref().unwrap_or("argument"));
            io(module, arg.ty, arg.binding.as_ref(), plain, input_kind, &ep.name, &mut out);
        }
        if let Some(r) = &f.result {
            io(
                module,
                r.ty,
                r.binding.as_ref(),
                format!("{}.result", ep.name),
                output_kind,
                &ep.name,
                &mut out,
            );
        }
    }
    out
}

/// Padding members (`_pad`, `_pad0`, …) are layout, not inputs.
fn is_padding(name: Option<&str>) -> bool {
    name.is_some_and(|n| n.starts_with("_pad"))
}

/// Adds one entry-point argument or result: a struct's members, or the plain value.
fn io(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
    binding: Option<&Binding>,
    plain_key: String,
    kind: ItemKind,
    entry: &str,
    out: &mut Vec<Item>,
) {
    let types = &module.types;
    let mut add = |key: String, ty: naga::Handle<naga::Type>, binding: Option<&Binding>| {
        if let Some(existing) = out.iter_mut().find(|i| i.key == key) {
            existing.entry_points.push(entry.to_string());
            return;
        }
        out.push(Item {
            key,
            kind,
            ty: types.type_to_string(ty),
            place: binding.map(place).unwrap_or_default(),
            entry_points: vec![entry.to_string()],
        });
    };
    match &types[ty].inner {
        TypeInner::Struct { members, .. } if binding.is_none() => {
            let struct_name = types[ty].name.clone().unwrap_or_default();
            for m in members {
                add(
                    format!("{struct_name}.{}", m.name.as_deref().unwrap_or_default()),
                    m.ty,
                    m.binding.as_ref(),
                );
            }
        }
        _ => add(plain_key, ty, binding),
    }
}

/// `@location(n)` or `@builtin(name)`.
fn place(b: &Binding) -> String {
    match b {
        Binding::Location { location, .. } => format!("@location({location})"),
        Binding::BuiltIn(builtin) => {
            let name = format!("{builtin:?}");
            let snake: String = name
                .split('{')
                .next()
                .unwrap_or_default()
                .trim()
                .chars()
                .enumerate()
                .flat_map(|(i, c)| {
                    let lower = c.to_ascii_lowercase();
                    if c.is_ascii_uppercase() && i > 0 {
                        vec!['_', lower]
                    } else {
                        vec![lower]
                    }
                })
                .collect();
            format!("@builtin({snake})")
        }
    }
}
