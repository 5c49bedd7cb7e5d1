//! The README's section on the compute entry points (the relief techniques' `cs_color` and
//! `cs_debug`): what the engine supplies, the visibility buffer's layout, how to dispatch
//! them, and what each language adds. Written only when an exported module has compute
//! entry points; the entry points' names, workgroup size, bindings and MSL buffer slots come
//! from the module and its binding layout, so the section follows the shaders.
//!
//! The kernels shade one pixel per invocation with the fragment entry points' `shade`, from
//! the surface the visibility buffer names (its triangle and the barycentric weights of the
//! point where the pixel centre's camera ray meets it) instead of the rasterizer's
//! interpolants. An invocation whose pixel shows no surface, or another material's, returns
//! at once, so one dispatch per material writes disjoint pixels.

use super::backends::{binding_layout, glsl_file_name, msl_sizes_slot, ResourceClass};
use super::source::{ExportShader, Lang, Parsed};
use naga::{ArraySize, ShaderStage, TypeInner};
use std::fmt::Write;

/// Appends the section when some of `shaders` (parsed as `parsed`) has compute entry points.
pub fn compute_section(s: &mut String, shaders: &[ExportShader], parsed: &[Parsed], langs: &[Lang]) {
    let with: Vec<usize> = (0..shaders.len()).filter(|&i| has_compute(&parsed[i])).collect();
    let Some(&first) = with.first() else { return };
    let module = &parsed[first].module;
    let eps: Vec<&naga::EntryPoint> =
        module.entry_points.iter().filter(|ep| ep.stage == ShaderStage::Compute).collect();
    let names: Vec<String> = eps.iter().map(|ep| format!("`{}`", ep.name)).collect();
    let [gx, gy, gz] = eps[0].workgroup_size;
    let shader_names: Vec<&str> = with.iter().map(|&i| shaders[i].name.as_str()).collect();
    let holders = match shader_names.as_slice() {
        [one] => format!("The shader {one} also holds"),
        many => format!("The shaders {} also hold", many.join(", ")),
    };
    let rows = binding_layout(module);
    // The groups only the compute entry points use.
    let fragment_groups: Vec<u32> = rows
        .iter()
        .filter(|r| !matches!(r.class, ResourceClass::StorageBuffer { .. } | ResourceClass::StorageTexture))
        .map(|r| r.group)
        .collect();
    let compute_rows: Vec<String> = rows
        .iter()
        .filter(|r| !fragment_groups.contains(&r.group))
        .map(|r| format!("`{}` (`@group({}) @binding({})`)", r.name, r.group, r.binding))
        .collect();

    let _ = writeln!(
        s,
        "\n## Compute entry points\n\n\
         {holders} the compute entry points {}: `cs_color` writes the image alone (as `fs_color`), \
         `cs_debug` also the displaced UV and the layer count (as `fs_debug`). They shade each pixel \
         with the same code as the fragment entry points, but take the pixel's surface from a \
         visibility buffer instead of the rasterizer's interpolants (position and the exact UV \
         Jacobian are rebuilt from the triangle and the pixel's camera ray), so the frame's shading \
         runs on compute units alone. Engines that draw the frame with the fragment entry points \
         need none of this.\n",
        names.join(", "),
    );
    let _ = writeln!(
        s,
        "**What the engine supplies.**\n\n\
         1. The groups of the fragment entry points, with `Frame`'s compute members filled \
         (`Frame.ray_base`, `Frame.ray_dx`, `Frame.ray_dy` for the camera of `Frame.view_proj`, and \
         `Frame.size`) and `Material.index` in each material's block.\n\
         2. {}: the visibility buffer, the scene's vertex and index buffers bound as storage, one \
         record per object, and the output textures (formats in the resource table).\n\
         3. Its own visibility pass, run before the dispatches, writing `vis_buffer` at every pixel: \
         for example a rasterized pass that writes object and triangle IDs at the pixel centre, \
         or one ray per pixel centre cast through the engine's BVH. Where no surface shows, that pass also writes the \
         background (`Frame.background`) into `out_color` (and UV 0 and layer count 0 into `out_uv` \
         and `out_layers`, if the engine reads them): the compute entry points never write those \
         pixels.\n",
        compute_rows.join(", "),
    );
    s.push_str(
        "**The visibility buffer** holds one `vec2<u32>` (8 bytes) per pixel, row-major from the \
         top row (element `y · Frame.size.x + x`):\n\n\
         | component | holds |\n|---|---|\n\
         | x | the object: its index in `mesh_objects`; `0xffffffff` where no surface shows |\n\
         | y | the triangle within the object: its vertices are `mesh_indices[mesh_objects[x].x + 3·y + k]`, k = 0, 1, 2 |\n\n\
         The entry points find the point themselves: where the camera ray through the pixel \
         centre, `Frame.eye + s·(Frame.ray_base + (x + 0.5)·Frame.ray_dx + (y + 0.5)·Frame.ray_dy)`, \
         meets the triangle's plane, whose barycentric weights are what a rasterizer's \
         perspective-correct barycentrics at the pixel centre give. The surface must be the nearest \
         front face between the near and far planes (`Frame.depth_range`), as a rasterizer keeps \
         it.\n\n",
    );
    let _ = writeln!(
        s,
        "**Dispatch.** One invocation per pixel, in {gx}×{gy}×{gz} workgroups: for each material in \
         use, bind its group-1 resources (`Material.index` = its index) and dispatch \
         (⌈width/{gx}⌉, ⌈height/{gy}⌉, 1) workgroups of `cs_color` (or `cs_debug`). An invocation \
         returns at once when its pixel lies outside `Frame.size`, shows no surface, or shows an \
         object of another material, so the dispatches write disjoint pixels and need no barrier \
         between them; the visibility pass's writes must be made visible to them (a barrier after \
         that pass), and the outputs are complete after the last dispatch.\n"
    );
    for l in langs {
        let note = match l {
            Lang::Wgsl => format!(
                "`@compute @workgroup_size({gx}, {gy})` in `NAME.wgsl`, bindings as declared; this is \
                 the pipeline renderlab itself runs."
            ),
            Lang::Glsl => {
                let files: Vec<String> = eps
                    .iter()
                    .map(|ep| format!("`{}` ({})", glsl_file_name(module, "NAME", ep), ep.name))
                    .collect();
                format!(
                    "{}, `local_size` {gx}×{gy}, run with `glDispatchCompute`; storage buffers at their \
                     shader-storage binding points (`glBindBufferBase(GL_SHADER_STORAGE_BUFFER, …)`), \
                     storage textures at their image units (`glBindImageTexture` with `GL_WRITE_ONLY` and \
                     the texture's format); `glMemoryBarrier` for the visibility pass's writes.",
                    files.join(", ")
                )
            }
            Lang::Hlsl => format!(
                "`[numthreads({gx}, {gy}, {gz})]` functions in `NAME.hlsl`, compiled each with \
                 `dxc -T cs_6_0 -E <entry>` and run with `Dispatch`."
            ),
            Lang::Msl => {
                let sized: Vec<String> = sized_buffers(module).iter().map(|n| format!("`{n}`")).collect();
                format!(
                    "`kernel` functions in `NAME.metal`, run with \
                     `dispatchThreadgroups:(⌈width/{gx}⌉, ⌈height/{gy}⌉, 1) threadsPerThreadgroup:({gx}, {gy}, {gz})`. \
                     Besides the slots in the table each kernel reads `_buffer_sizes` at `buffer({})`: \
                     naga's struct `_mslBufferSizes`, one `uint` per runtime-sized storage buffer of the \
                     module in this order: {}, each the bound buffer's length in bytes.",
                    msl_sizes_slot(&rows),
                    sized.join(", ")
                )
            }
            Lang::Spv => format!(
                "`GLCompute` entry points with `LocalSize {gx} {gy} {gz}` in `NAME.spv`, run with \
                 `vkCmdDispatch`. Every storage format is in Vulkan's basic set (Rgba32f, R32ui), so \
                 the module needs no storage-format capability."
            ),
        };
        let _ = writeln!(s, "- **{l}**: {note}");
    }
}

/// Whether `parsed` has a compute entry point.
pub fn has_compute(parsed: &Parsed) -> bool {
    parsed.module.entry_points.iter().any(|ep| ep.stage == ShaderStage::Compute)
}

/// The storage buffers whose last (or only) part is a runtime-sized array, in declaration
/// order: the order of the sizes naga's Metal kernels read from `_buffer_sizes`.
fn sized_buffers(module: &naga::Module) -> Vec<String> {
    let types = &module.types;
    let runtime = |ty: naga::Handle<naga::Type>| {
        matches!(types[ty].inner, TypeInner::Array { size: ArraySize::Dynamic, .. })
    };
    module
        .global_variables
        .iter()
        .filter(|(_, g)| g.binding.is_some())
        .filter(|(_, g)| match &types[g.ty].inner {
            TypeInner::Struct { members, .. } => members.last().is_some_and(|m| runtime(m.ty)),
            _ => runtime(g.ty),
        })
        .map(|(_, g)| g.name.clone().unwrap_or_default())
        .collect()
}
