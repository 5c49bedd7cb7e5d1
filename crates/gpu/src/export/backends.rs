//! The translations and their binding layouts.
//!
//! Each language is written by naga's own backend from the validated module. WGSL has
//! `@group`/`@binding` pairs; the other languages number their resources differently, so
//! each needs a map, and every map here is derived from the module's pairs in one order
//! (ascending group, then binding), which [`binding_layout`] reports for the README:
//!
//! - **GLSL 4.50 core.** Chosen because the frame needs fine derivatives (`dFdxFine`), core
//!   from 4.50 on and missing from every GLSL ES, and because 4.50 has `layout(binding = N)`
//!   and `glClipControl`. Uniform blocks take uniform-buffer binding points 0, 1, … and
//!   textures take texture units 0, 1, …, each in that order. GLSL has no separate sampler
//!   objects in its source: naga combines each texture with the sampler it is read through
//!   into one `sampler2D`, whose sampler state the engine sets on the texture unit. One file
//!   per entry point (naga's GLSL backend writes one stage per output). Written without
//!   naga's coordinate adjustment: clip space stays WebGPU's (y up, z in [0, 1]), which an
//!   OpenGL engine gets with `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`.
//! - **HLSL, shader model 6.0** (DXC, the compiler current Direct3D 12 engines use; register
//!   spaces need 5.1 or later). A uniform block is `register(b<binding>, space<group>)`, a
//!   texture `register(t<binding>, space<group>)`. A sampler is naga's Direct3D 12 form: an
//!   index into the sampler heap `nagaSamplerHeap` (`register(s0, space0)`), read from the
//!   group's `StructuredBuffer<uint> nagaGroup<G>SamplerIndexArray`
//!   (`register(t<group>, space255)`) at the sampler's binding number.
//! - **MSL 2.1** (Metal 2 on macOS 10.14 and iOS 12 and later; the frame needs nothing newer).
//!   Every entry point gets the same slots: uniform blocks `[[buffer(0)]]`, `[[buffer(1)]]`,
//!   …, textures `[[texture(0)]]`, …, samplers `[[sampler(0)]]`, … in that order. Vertex
//!   attributes come through `[[stage_in]]`; the engine's vertex buffers take buffer slots
//!   after the uniforms'.
//! - **SPIR-V 1.0** (Vulkan 1.0), binary, every entry point in one module: descriptor set =
//!   group, binding = binding, as in WGSL. Written with naga's coordinate adjustment (y
//!   negated in the vertex stage), so a Vulkan engine with an ordinary (positive-height)
//!   viewport draws the frame upright, as WebGPU does.

use super::source::{ExportShader, Lang, Parsed};
use crate::error::{GpuError, Result};
use naga::{AddressSpace, ResourceBinding, ShaderStage, TypeInner};
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
}

/// Where one resource of the module is bound, in every language.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BindingRow {
    /// The WGSL variable's name.
    pub name: String,
    /// Its `@group` and `@binding`.
    pub group: u32,
    /// Its `@binding`.
    pub binding: u32,
    /// What it is.
    pub class: ResourceClass,
    /// Its index among the resources of its class (uniform blocks, textures or samplers), in
    /// ascending (group, binding) order: GLSL's binding point or texture unit, MSL's slot.
    pub slot: u32,
}

impl BindingRow {
    /// Where GLSL binds it.
    pub fn glsl(&self) -> String {
        match self.class {
            ResourceClass::Uniform => format!("uniform block binding {}", self.slot),
            ResourceClass::Texture => format!("texture unit {}", self.slot),
            ResourceClass::Sampler => "state of the textures it samples".into(),
        }
    }

    /// Where HLSL binds it.
    pub fn hlsl(&self) -> String {
        match self.class {
            ResourceClass::Uniform => format!("b{}, space{}", self.binding, self.group),
            ResourceClass::Texture => format!("t{}, space{}", self.binding, self.group),
            ResourceClass::Sampler => {
                format!("heap index nagaGroup{}SamplerIndexArray[{}]", self.group, self.binding)
            }
        }
    }

    /// Where MSL binds it.
    pub fn msl(&self) -> String {
        match self.class {
            ResourceClass::Uniform => format!("buffer({})", self.slot),
            ResourceClass::Texture => format!("texture({})", self.slot),
            ResourceClass::Sampler => format!("sampler({})", self.slot),
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

/// Every bound resource of `module`, in ascending (group, binding) order, with its slot.
pub fn binding_layout(module: &naga::Module) -> Vec<BindingRow> {
    let mut rows: Vec<BindingRow> = module
        .global_variables
        .iter()
        .filter_map(|(_, g)| {
            let rb = g.binding.as_ref()?;
            let class = match (&module.types[g.ty].inner, g.space) {
                (TypeInner::Sampler { .. }, _) => ResourceClass::Sampler,
                (TypeInner::Image { .. }, _) => ResourceClass::Texture,
                (_, AddressSpace::Uniform) => ResourceClass::Uniform,
                // Nothing else occurs in renderlab's shaders; `translate` refuses it.
                _ => return None,
            };
            let name = g.name.clone().unwrap_or_default();
            Some(BindingRow { name, group: rb.group, binding: rb.binding, class, slot: 0 })
        })
        .collect();
    rows.sort_by_key(|r| (r.group, r.binding));
    let mut next: BTreeMap<u8, u32> = BTreeMap::new();
    for r in &mut rows {
        let n = next.entry(r.class as u8).or_insert(0);
        r.slot = *n;
        *n += 1;
    }
    rows
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
            "{}: a bound resource is neither a uniform buffer, a texture nor a sampler",
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

/// A GLSL file's name: `NAME.vert` / `NAME.frag` for the first entry point of each stage (in
/// module order), `NAME.ENTRY.frag` for the others (glslang reads the stage from the last
/// extension).
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
        writer_flags: glsl::WriterFlags::empty(),
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
        let slot = r.slot as u8;
        match r.class {
            ResourceClass::Uniform => target.buffer = Some(slot),
            ResourceClass::Texture => target.texture = Some(slot),
            ResourceClass::Sampler => target.sampler = Some(msl::BindSamplerTarget::Resource(slot)),
        }
        resources.insert(r.resource_binding(), target);
    }
    let per_entry = msl::EntryPointResources { resources, immediates_buffer: None, sizes_buffer: None };
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
