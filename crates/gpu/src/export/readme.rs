//! The README written beside the exported shaders: the conventions they share, each
//! language's binding layout, and per shader its entry points, its files, its technique's
//! parameters and every input and output with its meaning and unit.
//!
//! Shaders whose inputs and outputs are the same (every relief technique shares the relief
//! frame) share one set of tables, so that the README stays readable; each shader's own
//! section then says which resources each of its entry points actually uses. Modules with
//! compute entry points get a section on dispatching them (`readme_compute.rs`).

use super::backends::OutputFile;
use super::backends::{binding_layout, BindingRow};
use super::descriptions::describe;
use super::readme_compute::compute_section;
use super::reflect::{items, Item, ItemKind};
use super::source::{ExportShader, Lang, Parsed, ShaderKind};
use renderlab_relief::render::shade::ShadowMode;
use renderlab_relief::Shading;
use std::fmt::Write;

/// The README's file name.
pub const README: &str = "README.md";

/// The README for `shaders` (parsed as `parsed`, in the same order), exported as `langs`
/// into `files`.
pub fn readme(shaders: &[ExportShader], parsed: &[Parsed], langs: &[Lang], files: &[OutputFile]) -> String {
    let mut s = String::new();
    let names: Vec<&str> = langs.iter().map(|l| l.name()).collect();
    let _ = writeln!(
        s,
        "# renderlab shaders\n\n\
         Written by `renderlab shaders export --lang {}` (renderlab {}): the shaders of renderlab's \
         GPU renderer, translated by naga from the WGSL that renderlab runs on wgpu and checks \
         against its CPU renderer.\n",
        names.join(","),
        env!("CARGO_PKG_VERSION"),
    );
    s.push_str(CONVENTIONS);
    s.push_str("\n## Languages and bindings\n\n");
    for l in langs {
        let _ = writeln!(s, "- {}", lang_note(*l));
    }
    compute_section(&mut s, shaders, parsed, langs);
    s.push_str("\n## Files\n\n| shader | files |\n|---|---|\n");
    for sh in shaders {
        let mine: Vec<String> =
            files.iter().filter(|f| f.shader == sh.name).map(|f| format!("`{}`", f.name)).collect();
        let _ = writeln!(s, "| {} | {} |", sh.name, mine.join(", "));
    }
    // Shaders with the same interface share one set of tables.
    let interfaces: Vec<Vec<Item>> = parsed.iter().map(items).collect();
    let mut done = vec![false; shaders.len()];
    for i in 0..shaders.len() {
        if done[i] {
            continue;
        }
        let group: Vec<usize> =
            (i..shaders.len()).filter(|&j| same_interface(&interfaces[i], &interfaces[j])).collect();
        for &j in &group {
            done[j] = true;
        }
        let members: Vec<&str> = group.iter().map(|&j| shaders[j].name.as_str()).collect();
        let _ = writeln!(s, "\n## Inputs and outputs of {}\n", members.join(", "));
        interface_tables(&mut s, &parsed[i], &interfaces[i], langs);
        for &j in &group {
            shader_section(&mut s, &shaders[j], &parsed[j], &interfaces[j]);
        }
    }
    s
}

/// What every exported shader assumes.
const CONVENTIONS: &str = "## Conventions\n\n\
- **Colour** is linear light throughout: textures hold linear values and the outputs are \
linear (tone-map and encode after).\n\
- **Texture space:** UV 1 = one tile of the maps (they repeat); depth 0 = the top of the \
relief, 1 = its deepest point; tangent space is (T, B, N) = (direction of increasing u, \
direction of increasing v, surface normal).\n\
- **Directions are vectors, not angles:** no input is an angle; the view direction comes from \
the eye position and the light's from a unit vector.\n\
- **Clip space** is WebGPU's (y up, z in [0, 1], pixel centres at +0.5); see each language \
for how it is adjusted.\n\
- **The relief frame** is one draw per material with depth test (less) and back faces culled \
(counter-clockwise front faces), or with the compute entry points one dispatch per material over \
the engine's visibility buffer (see below). The technique's parameters are uniforms (`Frame.params`), so \
one shader serves every setting of a technique.\n";

/// One line per language: the version and its binding layout.
fn lang_note(l: Lang) -> &'static str {
    match l {
        Lang::Wgsl => "**wgsl** (`NAME.wgsl`): the module renderlab runs, self-contained; bindings as declared.",
        Lang::Glsl => "**glsl** (`NAME.vert`, `NAME.frag`, `NAME.ENTRY.frag` for further fragment entry points, \
`NAME.comp` and `NAME.ENTRY.comp` for the compute entry points): \
GLSL 4.50 core, the first version with the fine derivatives (`dFdxFine`) the relief frame needs (GLSL ES has none). \
Uniform blocks take binding points 0, 1, … and textures texture units 0, 1, … in (group, binding) order; \
storage buffers are `std430` buffer blocks at shader-storage binding points 0, 1, … and storage textures \
`image2D`/`uimage2D` with their formats at image units 0, 1, …, each in the same order; \
GLSL has no separate samplers, so each texture is a `sampler2D` whose unit carries the sampler state \
listed for it. Clip space is left as WebGPU's: use `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`. \
Checked with `glslangValidator`.",
        Lang::Hlsl => "**hlsl** (`NAME.hlsl`, every entry point): shader model 6.0 (DXC). Uniform blocks at \
`b<binding>, space<group>`, textures at `t<binding>, space<group>`; samplers as naga writes them for \
Direct3D 12: an index into `nagaSamplerHeap` (`s0, space0`) read from the group's \
`StructuredBuffer<uint> nagaGroup<G>SamplerIndexArray` (`t<G>, space255`) at the sampler's binding. \
Read-only storage buffers are `ByteAddressBuffer` at `t<binding>, space<group>`; read-write storage \
buffers (`RWByteAddressBuffer`) and storage textures (`RWTexture2D`) at `u<binding>, space<group>`.",
        Lang::Msl => "**msl** (`NAME.metal`, every entry point): Metal Shading Language 2.1. Uniform blocks \
`buffer(0)`, `buffer(1)`, …, textures `texture(0)`, …, samplers `sampler(0)`, … in (group, binding) order; \
vertex attributes by `[[stage_in]]` (vertex buffers go after the uniform buffers' slots). Storage \
buffers take the buffer slots after the uniform blocks', storage textures the texture slots after the \
sampled textures', each in (group, binding) order; kernels also read `_buffer_sizes` (see the compute \
entry points).",
        Lang::Spv => "**spv** (`NAME.spv`, every entry point in one module): SPIR-V 1.0 for Vulkan 1.0; \
descriptor set = group, binding = binding. The vertex stage negates y (naga's coordinate adjustment), \
so an ordinary positive-height Vulkan viewport draws the frame upright. Compute entry points are \
`GLCompute` entry points of the same module.",
    }
}

/// Whether two interfaces have the same items in the same places (which entry point reads
/// what may differ).
fn same_interface(a: &[Item], b: &[Item]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| x.key == y.key && x.kind == y.kind && x.ty == y.ty && x.place == y.place)
}

/// A description, or a mark that it is missing (the tests refuse such a shader).
fn meaning(key: &str) -> &'static str {
    describe(key).unwrap_or("(no description)")
}

/// The resource, uniform-member and stage tables of one interface.
fn interface_tables(s: &mut String, parsed: &Parsed, interface: &[Item], langs: &[Lang]) {
    let rows: Vec<BindingRow> = binding_layout(&parsed.module);
    let others: Vec<Lang> = langs.iter().copied().filter(|l| *l != Lang::Wgsl).collect();
    s.push_str("### Resources\n\n| name | kind | WGSL |");
    for l in &others {
        let _ = write!(s, " {l} |");
    }
    s.push_str(" type | meaning |\n|---|---|---|");
    for _ in &others {
        s.push_str("---|");
    }
    s.push_str("---|---|\n");
    for item in interface.iter().filter(|i| i.kind.is_resource()) {
        let _ = write!(s, "| `{}` | {} | {} |", item.key, item.kind.label(), item.place);
        let row = rows.iter().find(|r| r.name == item.key);
        for l in &others {
            let place = match (row, l) {
                (Some(r), Lang::Glsl) => r.glsl(),
                (Some(r), Lang::Hlsl) => r.hlsl(),
                (Some(r), Lang::Msl) => r.msl(),
                (Some(r), Lang::Spv) => r.spv(),
                _ => String::new(),
            };
            let _ = write!(s, " {place} |");
        }
        let _ = writeln!(s, " `{}` | {} |", item.ty, meaning(&item.key));
    }
    let members: Vec<&Item> = interface.iter().filter(|i| i.kind == ItemKind::UniformMember).collect();
    if !members.is_empty() {
        s.push_str("\n### Uniform members (byte offsets in the block)\n\n| member | type | offset | meaning and unit |\n|---|---|---|---|\n");
        for m in members {
            let _ = writeln!(
                s,
                "| `{}` | `{}` | {} | {} |",
                m.key,
                m.ty,
                m.place.trim_start_matches("offset "),
                meaning(&m.key)
            );
        }
    }
    s.push_str("\n### Stage inputs and outputs\n\n| name | kind | binding | type | entry points | meaning |\n|---|---|---|---|---|---|\n");
    for item in interface.iter().filter(|i| {
        matches!(
            i.kind,
            ItemKind::VertexInput | ItemKind::Varying | ItemKind::FragmentOutput | ItemKind::ComputeInput
        )
    }) {
        let _ = writeln!(
            s,
            "| `{}` | {} | `{}` | `{}` | {} | {} |",
            item.key,
            item.kind.label(),
            item.place,
            item.ty,
            item.entry_points.join(", "),
            meaning(&item.key)
        );
    }
}

/// One shader's own section: what it is, its parameters, its entry points, what it reads.
fn shader_section(s: &mut String, shader: &ExportShader, parsed: &Parsed, interface: &[Item]) {
    let _ = writeln!(s, "\n### {}\n", shader.name);
    match shader.kind {
        ShaderKind::Relief(t) => {
            let d = t.descriptor();
            let lit = match (d.shading, t.shadow()) {
                (Shading::Unlit, _) => "`Frame.lit` = 0 (unlit)",
                (Shading::Lit, _) => "`Frame.lit` = 1 (lit)",
                (Shading::LitShadowed, ShadowMode::Horizon(_)) => {
                    "`Frame.lit` = 3 (lit, horizon self-shadows; `Frame.shadow_samples` > 0)"
                }
                (Shading::LitShadowed, _) => {
                    "`Frame.lit` = 2 (lit, soft self-shadows; `Frame.shadow_samples` > 0)"
                }
            };
            let _ = writeln!(s, "The relief technique `{}`: {}. Draw it with {lit}.", d.name, d.summary);
            if d.params.is_empty() {
                s.push_str("\nParameters: none (`Frame.params` unused).\n");
            } else {
                s.push_str("\nParameters (`Frame.params`, whole numbers):\n\n");
                for (i, p) in d.params.iter().enumerate() {
                    let _ = writeln!(s, "- `params[{i}]` = {}", p.help());
                }
            }
        }
        ShaderKind::Filters => s.push_str(
            "The texture filters' frame: one full-screen triangle whose fragments filter a texture at \
             each pixel's exact UV and UV Jacobian (from per-pixel surface textures), with the \
             hardware's sampler or with EWA written in the shader (`Filter.mode`).\n",
        ),
    }
    let entries: Vec<String> = parsed
        .module
        .entry_points
        .iter()
        .map(|ep| format!("`{}` ({:?})", ep.name, ep.stage).to_lowercase())
        .collect();
    let _ = writeln!(s, "\nEntry points: {}.", entries.join(", "));
    let stages = [naga::ShaderStage::Fragment, naga::ShaderStage::Compute];
    for ep in parsed.module.entry_points.iter().filter(|ep| stages.contains(&ep.stage)) {
        let used = |output: bool| -> Vec<String> {
            interface
                .iter()
                .filter(|i| i.kind.is_resource() && i.kind.is_output() == output)
                .filter(|i| i.entry_points.contains(&ep.name))
                .map(|i| format!("`{}`", i.key))
                .collect()
        };
        let writes = used(true);
        let writes =
            if writes.is_empty() { String::new() } else { format!("; writes {}", writes.join(", ")) };
        let _ = writeln!(s, "`{}` reads {}{writes}.", ep.name, used(false).join(", "));
    }
}
