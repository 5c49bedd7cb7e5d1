//! The translations and their binding layouts.
//!
//! Each language is written by naga's own backend from the validated module. WGSL has
//! `@group`/`@binding` pairs; the other languages number their resources differently, so
//! each needs a map, and every map here is derived from the module's pairs in one order
//! (ascending group, then binding), which [`binding_layout`] reports for the README:
//!
//! - **GLSL 4.50 core.** Chosen because the frame needs fine derivatives (`dFdxFine`), core
//!   from 4.50 on and missing from every GLSL ES, and because 4.50 has `layout(binding = N)`
//!   and `glClipControl`. Uniform blocks take uniform-buffer binding points 0, 1, …,
//!   textures texture units 0, 1, …, storage buffers (`std430` buffer blocks, read-only and
//!   read-write together) shader-storage binding points 0, 1, … and storage textures
//!   (`image2D`/`uimage2D` with their formats) image units 0, 1, …, each in that order: four
//!   numberings, as OpenGL has four kinds of binding point. GLSL has no separate sampler
//!   objects in its source: naga combines each texture with the sampler it is read through
//!   into one `sampler2D`, whose sampler state the engine sets on the texture unit. One file
//!   per entry point (naga's GLSL backend writes one stage per output), named by stage
//!   (`.vert`, `.frag`, `.comp`; see [`glsl_file_name`]). Written without
//!   naga's coordinate adjustment: clip space stays WebGPU's (y up, z in [0, 1]), which an
//!   OpenGL engine gets with `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`.
//! - **HLSL, shader model 6.0** (DXC, the compiler current Direct3D 12 engines use; register
//!   spaces need 5.1 or later). A uniform block is `register(b<binding>, space<group>)`, a
//!   texture or read-only storage buffer (`ByteAddressBuffer`) `register(t<binding>,
//!   space<group>)`, a read-write storage buffer (`RWByteAddressBuffer`) or storage texture
//!   (`RWTexture2D`) `register(u<binding>, space<group>)`: one number per resource in every
//!   class, so the registers never collide. A sampler is naga's Direct3D 12 form: an
//!   index into the sampler heap `nagaSamplerHeap` (`register(s0, space0)`), read from the
//!   group's `StructuredBuffer<uint> nagaGroup<G>SamplerIndexArray`
//!   (`register(t<group>, space255)`) at the sampler's binding number.
//! - **MSL 2.1** (Metal 2 on macOS 10.14 and iOS 12 and later; the frame needs nothing newer).
//!   Every entry point gets the same slots: uniform blocks `[[buffer(0)]]`, `[[buffer(1)]]`,
//!   …, textures `[[texture(0)]]`, …, samplers `[[sampler(0)]]`, … in that order; storage
//!   buffers take the buffer slots after every uniform block's and storage textures the
//!   texture slots after every sampled texture's (so that the fragment entry points' slots
//!   are those of a module without storage resources), and a kernel over runtime-sized
//!   buffers reads their sizes at the slot after every buffer ([`msl_sizes_slot`]). Vertex
//!   attributes come through `[[stage_in]]`; the engine's vertex buffers take buffer slots
//!   after the uniforms'.
//! - **SPIR-V 1.0** (Vulkan 1.0), binary, every entry point (compute ones included) in one
//!   module: descriptor set = group, binding = binding, as in WGSL. Written with naga's coordinate adjustment (y
//!   negated in the vertex stage), so a Vulkan engine with an ordinary (positive-height)
//!   viewport draws the frame upright, as WebGPU does.

use super::source::{ExportShader, Lang, Parsed};
use crate::error::{GpuError, Result};
use naga::{AddressSpace, ImageClass, ResourceBinding, ShaderStage, StorageAccess, TypeInner};
use std::collections::BTreeMap;

/// One file to write: its name inside the output directory and its contents.
#[derive(Clone, Debug)]
pub struct OutputFile {
    /// File name (`pom.frag`, `pom.spv`).
    pub name: String,
    /// What the file holds.
    pub bytes: Vec<u8>,
    /// The shader it came from.
    pub shader: String,
    /// Its language.
    pub lang: Lang,
}

/// What a bound resource is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResourceClass {
    /// A uniform buffer (a struct in the `uniform` address space).
    Uniform,
    /// A sampled texture.
    Texture,
    /// A sampler.
    Sampler,
    /// A buffer in the `storage` address space; `writable` when declared `read_write`.
    StorageBuffer {
        /// Whether the shader may write it.
        writable: bool,
    },
    /// A storage texture (`texture_storage_2d`), which the shader writes texel by texel.
    StorageTexture,
}

/// The numbering a class shares in GLSL (binding points, texture units, image units) and in
/// MSL (buffer, texture and sampler slots).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Namespace {
    UniformBlock,
    TextureUnit,
    Sampler,
    StorageBlock,
    ImageUnit,
}

impl ResourceClass {
    /// GLSL's numbering of the class (read-only and read-write storage blocks share one).
    fn glsl_namespace(self) -> Namespace {
        match self {
            ResourceClass::Uniform => Namespace::UniformBlock,
            ResourceClass::Texture => Namespace::TextureUnit,
            ResourceClass::Sampler => Namespace::Sampler,
            ResourceClass::StorageBuffer { .. } => Namespace::StorageBlock,
            ResourceClass::StorageTexture => Namespace::ImageUnit,
        }
    }

    /// MSL's numbering of the class, and whether the class comes after the others of that
    /// numbering: buffers hold uniform blocks then storage buffers, textures hold sampled
    /// then storage textures.
    fn msl_namespace(self) -> (Namespace, bool) {
        match self {
            ResourceClass::Uniform => (Namespace::UniformBlock, false),
            ResourceClass::StorageBuffer { .. } => (Namespace::UniformBlock, true),
            ResourceClass::Texture => (Namespace::TextureUnit, false),
            ResourceClass::StorageTexture => (Namespace::TextureUnit, true),
            ResourceClass::Sampler => (Namespace::Sampler, false),
        }
    }
}

/// Where one resource of the module is bound, in every language.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BindingRow {
    /// The WGSL variable's name.
    pub name: String,
    /// Its `@group`.
    pub group: u32,
    /// Its `@binding`.
    pub binding: u32,
    /// What it is.
    pub class: ResourceClass,
    /// Its index in GLSL's numbering of its class, in ascending (group, binding) order: the
    /// uniform-block binding point, texture unit, shader-storage-block binding point (read-only
    /// and read-write blocks counted together) or image unit. For uniform blocks, textures
    /// and samplers also the MSL slot.
    pub slot: u32,
    /// Its MSL slot: uniform blocks `buffer(0)`, … then storage buffers after them; sampled
    /// textures `texture(0)`, … then storage textures after them; samplers `sampler(0)`, ….
    /// Each part in ascending (group, binding) order, so that the storage resources never move
    /// the others.
    pub msl_slot: u32,
}

impl BindingRow {
    /// Where GLSL binds it.
    pub fn glsl(&self) -> String {
        match self.class {
            ResourceClass::Uniform => format!("uniform block binding {}", self.slot),
            ResourceClass::Texture => format!("texture unit {}", self.slot),
            ResourceClass::Sampler => "state of the textures it samples".into(),
            ResourceClass::StorageBuffer { .. } => format!("std430 buffer block binding {}", self.slot),
            ResourceClass::StorageTexture => format!("image unit {}", self.slot),
        }
    }

    /// Where HLSL binds it.
    pub fn hlsl(&self) -> String {
        match self.class {
            ResourceClass::Uniform => format!("b{}, space{}", self.binding, self.group),
            ResourceClass::Texture | ResourceClass::StorageBuffer { writable: false } => {
                format!("t{}, space{}", self.binding, self.group)
            }
            ResourceClass::StorageBuffer { writable: true } | ResourceClass::StorageTexture => {
                format!("u{}, space{}", self.binding, self.group)
            }
            ResourceClass::Sampler => {
                format!("heap index nagaGroup{}SamplerIndexArray[{}]", self.group, self.binding)
            }
        }
    }

    /// Where MSL binds it.
    pub fn msl(&self) -> String {
        match self.class {
            ResourceClass::Uniform | ResourceClass::StorageBuffer { .. } => {
                format!("buffer({})", self.msl_slot)
            }
            ResourceClass::Texture | ResourceClass::StorageTexture => format!("texture({})", self.msl_slot),
            ResourceClass::Sampler => format!("sampler({})", self.msl_slot),
        }
    }

    /// Where SPIR-V binds it.
    pub fn spv(&self) -> String {
        format!("set {}, binding {}", self.group, self.binding)
    }

    fn resource_binding(&self) -> ResourceBinding {
        ResourceBinding { group: self.group, binding: self.binding }
    }
}

/// What a bound global variable is, or `None` for what no renderlab shader binds.
pub(crate) fn resource_class(module: &naga::Module, g: &naga::GlobalVariable) -> Option<ResourceClass> {
    Some(match (&module.types[g.ty].inner, g.space) {
        (TypeInner::Sampler { .. }, _) => ResourceClass::Sampler,
        (TypeInner::Image { class: ImageClass::Storage { .. }, .. }, _) => ResourceClass::StorageTexture,
        (TypeInner::Image { .. }, _) => ResourceClass::Texture,
        (_, AddressSpace::Uniform) => ResourceClass::Uniform,
        (_, AddressSpace::Storage { access }) => {
            ResourceClass::StorageBuffer { writable: access.contains(StorageAccess::STORE) }
        }
        _ => return None,
    })
}

/// Every bound resource of `module`, in ascending (group, binding) order, with its slots.
pub fn binding_layout(module: &naga::Module) -> Vec<BindingRow> {
    let mut rows: Vec<BindingRow> = module
        .global_variables
        .iter()
        .filter_map(|(_, g)| {
            let rb = g.binding.as_ref()?;
            // Nothing else occurs in renderlab's shaders; `translate` refuses it.
            let class = resource_class(module, g)?;
            let name = g.name.clone().unwrap_or_default();
            Some(BindingRow { name, group: rb.group, binding: rb.binding, class, slot: 0, msl_slot: 0 })
        })
        .collect();
    rows.sort_by_key(|r| (r.group, r.binding));
    let mut next: BTreeMap<Namespace, u32> = BTreeMap::new();
    for r in &mut rows {
        let n = next.entry(r.class.glsl_namespace()).or_insert(0);
        r.slot = *n;
        *n += 1;
    }
    // MSL: the first part of each numbering, then the part after it.
    let mut next: BTreeMap<Namespace, u32> = BTreeMap::new();
    for after in [false, true] {
        for r in rows.iter_mut().filter(|r| r.class.msl_namespace().1 == after) {
            let n = next.entry(r.class.msl_namespace().0).or_insert(0);
            r.msl_slot = *n;
            *n += 1;
        }
    }
    rows
}

/// The MSL buffer slot of the buffer sizes naga's Metal kernels read for their runtime-sized
/// storage arrays (`_buffer_sizes`, struct `_mslBufferSizes`): the slot after every buffer of
/// the layout.
pub fn msl_sizes_slot(rows: &[BindingRow]) -> u32 {
    rows.iter()
        .filter(|r| matches!(r.class, ResourceClass::Uniform | ResourceClass::StorageBuffer { .. }))
        .count() as u32
}

/// Translates `shader` (parsed as `parsed`) into `lang`: the files it becomes.
pub fn translate(shader: &ExportShader, parsed: &Parsed, lang: Lang) -> Result<Vec<OutputFile>> {
    let fail = |e: &dyn std::error::Error| {
        GpuError::Export(format!(
            "{}: naga cannot write {lang}: {}",
            shader.name,
            super::source::one_line_error(e)
        ))
    };
    let module = &parsed.module;
    let rows = binding_layout(module);
    let bound = module.global_variables.iter().filter(|(_, g)| g.binding.is_some()).count();
    if rows.len() != bound {
        return Err(GpuError::Export(format!(
            "{}: a bound resource is neither a uniform or storage buffer, a texture nor a sampler",
            shader.name
        )));
    }
    let file = |name: String, bytes: Vec<u8>| OutputFile { name, bytes, shader: shader.name.clone(), lang };
    let out = match lang {
        Lang::Wgsl => vec![file(format!("{}.wgsl", shader.name), shader.wgsl.clone().into_bytes())],
        Lang::Glsl => {
            let mut files = Vec::new();
            for ep in &module.entry_points {
                let text = glsl(parsed, &rows, ep.stage, &ep.name).map_err(|e| fail(&e))?;
                files.push(file(glsl_file_name(module, &shader.name, ep), text.into_bytes()));
            }
            files
        }
        Lang::Hlsl => vec![file(
            format!("{}.hlsl", shader.name),
            hlsl(parsed, &rows).map_err(|e| fail(&e))?.into_bytes(),
        )],
        Lang::Msl => vec![file(
            format!("{}.metal", shader.name),
            msl(parsed, &rows).map_err(|e| fail(&e))?.into_bytes(),
        )],
        Lang::Spv => {
            let words = spv(parsed, &rows).map_err(|e| fail(&e))?;
            vec![file(format!("{}.spv", shader.name), words.iter().flat_map(|w| w.to_le_bytes()).collect())]
        }
    };
    Ok(out)
}

/// A GLSL file's name: `NAME.vert` / `NAME.frag` / `NAME.comp` for the first entry point of
/// each stage (in module order), `NAME.ENTRY.frag` / `NAME.ENTRY.comp` for the others
/// (glslang reads the stage from the last extension).
pub fn glsl_file_name(module: &naga::Module, name: &str, ep: &naga::EntryPoint) -> String {
    let ext = match ep.stage {
        ShaderStage::Vertex => "vert",
        ShaderStage::Fragment => "frag",
        ShaderStage::Compute => "comp",
        _ => "glsl",
    };
    let first = module.entry_points.iter().find(|e| e.stage == ep.stage).is_some_and(|e| e.name == ep.name);
    if first {
        format!("{name}.{ext}")
    } else {
        format!("{name}.{}.{ext}", ep.name)
    }
}

fn glsl(
    parsed: &Parsed,
    rows: &[BindingRow],
    stage: ShaderStage,
    entry: &str,
) -> std::result::Result<String, naga::back::glsl::Error> {
    use naga::back::glsl;
    let mut binding_map = glsl::BindingMap::default();
    for r in rows.iter().filter(|r| r.class != ResourceClass::Sampler) {
        binding_map.insert(r.resource_binding(), r.slot as u8);
    }
    let options = glsl::Options {
        version: glsl::Version::Desktop(450),
        // The vertex stage reads the draw's instance index (the object, whose patch the
        // fragment stage reads): with draw parameters it is gl_InstanceIndex's GLSL twin
        // `gl_InstanceID + gl_BaseInstanceARB` (GL_ARB_shader_draw_parameters, core in 4.6)
        // rather than a uniform the engine would have to set per draw.
        writer_flags: glsl::WriterFlags::DRAW_PARAMETERS,
        binding_map,
        zero_initialize_workgroup_memory: true,
    };
    let pipeline =
        glsl::PipelineOptions { shader_stage: stage, entry_point: entry.to_string(), multiview: None };
    let mut text = String::new();
    let mut writer = glsl::Writer::new(
        &mut text,
        &parsed.module,
        &parsed.info,
        &options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )?;
    writer.write()?;
    Ok(text)
}

fn hlsl(parsed: &Parsed, rows: &[BindingRow]) -> std::result::Result<String, naga::back::hlsl::Error> {
    use naga::back::hlsl;
    let mut options = hlsl::Options {
        shader_model: hlsl::ShaderModel::V6_0,
        fake_missing_bindings: false,
        ..Default::default()
    };
    for r in rows {
        let target = hlsl::BindTarget {
            space: r.group as u8,
            register: r.binding,
            binding_array_size: None,
            dynamic_storage_buffer_offsets_index: None,
            restrict_indexing: false,
        };
        options.binding_map.insert(r.resource_binding(), target);
        if r.class == ResourceClass::Sampler {
            let index_buffer = hlsl::BindTarget { space: u8::MAX, register: r.group, ..target };
            options
                .sampler_buffer_binding_map
                .insert(hlsl::SamplerIndexBufferKey { group: r.group }, index_buffer);
        }
    }
    let pipeline = hlsl::PipelineOptions::default();
    let mut text = String::new();
    let mut writer = hlsl::Writer::new(&mut text, &options, &pipeline);
    writer.write(&parsed.module, &parsed.info, None)?;
    Ok(text)
}

fn msl(parsed: &Parsed, rows: &[BindingRow]) -> std::result::Result<String, naga::back::msl::Error> {
    use naga::back::msl;
    let mut resources = msl::BindingMap::default();
    for r in rows {
        let mut target = msl::BindTarget::default();
        let slot = r.msl_slot as u8;
        match r.class {
            ResourceClass::Uniform | ResourceClass::StorageBuffer { .. } => target.buffer = Some(slot),
            ResourceClass::Texture | ResourceClass::StorageTexture => target.texture = Some(slot),
            ResourceClass::Sampler => target.sampler = Some(msl::BindSamplerTarget::Resource(slot)),
        }
        resources.insert(r.resource_binding(), target);
    }
    // Only kernels over runtime-sized storage arrays read the sizes; naga declares the buffer
    // in no other entry point.
    let sizes_buffer = Some(msl_sizes_slot(rows) as u8);
    let per_entry = msl::EntryPointResources { resources, immediates_buffer: None, sizes_buffer };
    let options = msl::Options {
        lang_version: (2, 1),
        per_entry_point_map: parsed
            .module
            .entry_points
            .iter()
            .map(|ep| (ep.name.clone(), per_entry.clone()))
            .collect(),
        fake_missing_bindings: false,
        ..Default::default()
    };
    let (text, _) =
        msl::write_string(&parsed.module, &parsed.info, &options, &msl::PipelineOptions::default())?;
    Ok(text)
}

fn spv(parsed: &Parsed, rows: &[BindingRow]) -> std::result::Result<Vec<u32>, naga::back::spv::Error> {
    use naga::back::spv;
    let mut options = spv::Options {
        lang_version: (1, 0),
        // Debug names kept (engines' reflection reads them); the same in every build profile.
        flags: spv::WriterFlags::ADJUST_COORDINATE_SPACE
            | spv::WriterFlags::LABEL_VARYINGS
            | spv::WriterFlags::CLAMP_FRAG_DEPTH
            | spv::WriterFlags::DEBUG,
        fake_missing_bindings: false,
        ..Default::default()
    };
    for r in rows {
        let info = spv::BindingInfo { descriptor_set: r.group, binding: r.binding, binding_array_size: None };
        options.binding_map.insert(r.resource_binding(), info);
    }
    spv::write_vec(&parsed.module, &parsed.info, &options, None)
}

/// The SPIR-V magic number, the first word of every module.
pub const SPIRV_MAGIC: u32 = 0x0723_0203;
