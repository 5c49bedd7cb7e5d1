//! `shaders export`: every shader in every language, the GLSL compiled by an outside compiler
//! (glslang), the SPIR-V's structure, the README's completeness, and bad input. None of these
//! needs a GPU: naga translates on the CPU.

use naga::ShaderStage;
use renderlab_gpu::export::backends::{msl_sizes_slot, ResourceClass, SPIRV_MAGIC};
use renderlab_gpu::export::descriptions::{describe, DESCRIPTIONS};
use renderlab_gpu::export::reflect::items;
use renderlab_gpu::export::{
    self, binding_layout, parse, shaders, translate, BindingRow, ExportShader, Lang, ShaderKind,
};
use renderlab_gpu::GpuError;
use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_relief::Technique;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

fn all() -> Vec<ExportShader> {
    shaders(&[]).expect("every registry technique has a shader")
}

#[test]
fn the_default_set_is_every_technique_and_the_filters() {
    let names: Vec<String> = all().into_iter().map(|s| s.name).collect();
    let mut expected: Vec<String> = DESCRIPTORS.iter().map(|d| d.name.to_string()).collect();
    expected.push(export::FILTERS_NAME.to_string());
    assert_eq!(names, expected);
    // A technique named twice (two settings of one shader) is exported once.
    let pom = Technique::parse("pom:8").expect("pom");
    let pom32 = Technique::parse("pom:32").expect("pom");
    let some = shaders(&[pom, pom32]).expect("pom has a shader");
    assert_eq!(some.iter().map(|s| s.name.as_str()).collect::<Vec<_>>(), ["pom"]);
}

/// What a SPIR-V module says of its entry points and bindings.
struct Spirv {
    /// `(execution model, name)` per `OpEntryPoint`, in order.
    entry_points: Vec<(u32, String)>,
    /// Per debug name of a decorated variable: its descriptor set and binding.
    bindings: BTreeMap<String, (u32, u32)>,
}

/// SPIR-V's execution models (`Vertex`, `Fragment`, `GLCompute`) by naga's stages.
fn execution_model(stage: ShaderStage) -> u32 {
    match stage {
        ShaderStage::Vertex => 0,
        ShaderStage::Fragment => 4,
        ShaderStage::Compute => 5,
        other => panic!("no renderlab shader has a {other:?} stage"),
    }
}

/// A literal string: UTF-8 bytes packed into little-endian words, ended by a zero byte.
fn spirv_string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|&b| b != 0).collect();
    String::from_utf8(bytes).expect("UTF-8 name")
}

/// The SPIR-V header and instruction stream: magic, version 1.0, a positive id bound, every
/// instruction's word count inside the module and ending exactly at its end; the entry
/// points (`OpEntryPoint`), and the descriptor set and binding (`OpDecorate`) of every
/// variable with a debug name (`OpName`).
fn check_spirv(name: &str, bytes: &[u8]) -> Spirv {
    assert!(bytes.len().is_multiple_of(4) && bytes.len() > 20, "{name}: {} bytes", bytes.len());
    let words: Vec<u32> =
        bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    assert_eq!(words[0], SPIRV_MAGIC, "{name}: magic");
    assert_eq!(words[1], 0x0001_0000, "{name}: SPIR-V 1.0");
    assert!(words[3] > 1, "{name}: id bound {}", words[3]);
    let mut entry_points = Vec::new();
    let mut names: BTreeMap<u32, String> = BTreeMap::new();
    let mut sets: BTreeMap<u32, u32> = BTreeMap::new();
    let mut binding_of: BTreeMap<u32, u32> = BTreeMap::new();
    let mut at = 5usize;
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let opcode = words[at] & 0xffff;
        assert!(count >= 1 && at + count <= words.len(), "{name}: instruction at word {at} overruns");
        let operands = &words[at + 1..at + count];
        match opcode {
            15 => entry_points.push((operands[0], spirv_string(&operands[2..]))), // OpEntryPoint
            5 => {
                names.insert(operands[0], spirv_string(&operands[1..])); // OpName
            }
            71 if operands[1] == 34 => {
                sets.insert(operands[0], operands[2]); // OpDecorate DescriptorSet
            }
            71 if operands[1] == 33 => {
                binding_of.insert(operands[0], operands[2]); // OpDecorate Binding
            }
            _ => {}
        }
        at += count;
    }
    let bindings = sets
        .iter()
        .map(|(id, &set)| {
            let var = names.get(id).unwrap_or_else(|| panic!("{name}: bound id {id} has no name")).clone();
            let binding =
                *binding_of.get(id).unwrap_or_else(|| panic!("{name}: {var} has a set, no binding"));
            (var, (set, binding))
        })
        .collect();
    Spirv { entry_points, bindings }
}

/// The relief techniques' compute entry points, which every language must carry.
const COMPUTE_ENTRY_POINTS: [&str; 2] = ["cs_color", "cs_debug"];

#[test]
fn every_shader_translates_into_every_language() {
    for s in all() {
        let p = parse(&s.name, &s.wgsl).unwrap_or_else(|e| panic!("{e}"));
        let eps = p.module.entry_points.len();
        let compute: Vec<&naga::EntryPoint> =
            p.module.entry_points.iter().filter(|ep| ep.stage == ShaderStage::Compute).collect();
        // Every relief technique has the compute pipeline's entry points; the filters have none.
        let names: Vec<&str> = compute.iter().map(|ep| ep.name.as_str()).collect();
        match s.kind {
            ShaderKind::Relief(_) => assert_eq!(names, COMPUTE_ENTRY_POINTS, "{}", s.name),
            ShaderKind::Filters => assert!(names.is_empty(), "{}", s.name),
        }
        for ep in &compute {
            assert_eq!(ep.workgroup_size, [8, 8, 1], "{}: {}", s.name, ep.name);
        }
        for lang in Lang::ALL {
            let files = translate(&s, &p, lang).unwrap_or_else(|e| panic!("{}: {lang}: {e}", s.name));
            let expected = if lang == Lang::Glsl { eps } else { 1 };
            assert_eq!(files.len(), expected, "{}: {lang}", s.name);
            if lang == Lang::Glsl {
                // `NAME.comp` for the first compute entry point, `NAME.ENTRY.comp` for the others.
                let comp: Vec<&str> =
                    files.iter().map(|f| f.name.as_str()).filter(|n| n.ends_with(".comp")).collect();
                let expected: Vec<String> = compute
                    .iter()
                    .enumerate()
                    .map(|(i, ep)| match i {
                        0 => format!("{}.comp", s.name),
                        _ => format!("{}.{}.comp", s.name, ep.name),
                    })
                    .collect();
                assert_eq!(comp, expected, "{}", s.name);
            }
            for f in &files {
                assert!(!f.bytes.is_empty(), "{}", f.name);
                assert!(f.name.starts_with(&s.name), "{}", f.name);
                if lang == Lang::Spv {
                    // One entry point per WGSL entry point, with its stage.
                    let spirv = check_spirv(&f.name, &f.bytes);
                    let expected: Vec<(u32, String)> = p
                        .module
                        .entry_points
                        .iter()
                        .map(|ep| (execution_model(ep.stage), ep.name.clone()))
                        .collect();
                    assert_eq!(spirv.entry_points, expected, "{}", f.name);
                } else {
                    let text = std::str::from_utf8(&f.bytes).expect("text");
                    // Every entry point is in the file that holds it.
                    let has = p.module.entry_points.iter().filter(|ep| text.contains(&ep.name)).count();
                    if lang == Lang::Glsl {
                        assert!(text.starts_with("#version 450 core"), "{}", f.name);
                        assert!(text.contains("void main()"), "{}", f.name);
                        let is_compute = f.name.ends_with(".comp");
                        assert_eq!(
                            text.contains("layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;"),
                            is_compute,
                            "{}",
                            f.name
                        );
                    } else {
                        assert_eq!(has, eps, "{}: entry points in {lang}", f.name);
                    }
                    // The compute entry points as each language declares a kernel.
                    for ep in &compute {
                        let kernel = match lang {
                            Lang::Wgsl => format!("@compute @workgroup_size(8, 8)\nfn {}(", ep.name),
                            Lang::Hlsl => format!("[numthreads(8, 8, 1)]\nvoid {}(", ep.name),
                            Lang::Msl => format!("kernel void {}(", ep.name),
                            _ => continue,
                        };
                        assert!(text.contains(&kernel), "{}: no `{kernel}`", f.name);
                    }
                }
            }
        }
    }
}

/// The HLSL register of a resource: `register(X<binding>)`, with `, space<group>` unless the
/// group is 0 (naga leaves out `space0`, the default).
fn hlsl_register(letter: char, r: &BindingRow) -> String {
    match r.group {
        0 => format!("register({letter}{})", r.binding),
        g => format!("register({letter}{}, space{g})", r.binding),
    }
}

#[test]
fn bindings_follow_the_documented_layout() {
    let mut classes = BTreeSet::new();
    for s in all() {
        let p = parse(&s.name, &s.wgsl).expect("parses");
        let rows = binding_layout(&p.module);
        let hlsl =
            String::from_utf8(translate(&s, &p, Lang::Hlsl).expect("hlsl")[0].bytes.clone()).expect("text");
        let msl =
            String::from_utf8(translate(&s, &p, Lang::Msl).expect("msl")[0].bytes.clone()).expect("text");
        // MSL declares a resource only as an argument of the entry points that read it.
        let used: BTreeSet<String> =
            items(&p).into_iter().filter(|i| !i.entry_points.is_empty()).map(|i| i.key).collect();
        for r in &rows {
            classes.insert(format!("{:?}", r.class));
            let msl_ok = |tag: String| !used.contains(&r.name) || msl.contains(&tag);
            let (letter, msl_kind) = match r.class {
                ResourceClass::Uniform => ('b', "buffer"),
                ResourceClass::Texture => ('t', "texture"),
                ResourceClass::StorageBuffer { writable: false } => ('t', "buffer"),
                ResourceClass::StorageBuffer { writable: true } => ('u', "buffer"),
                ResourceClass::StorageTexture => ('u', "texture"),
                ResourceClass::Sampler => ('s', "sampler"),
            };
            let msl_tag = format!("{} [[{msl_kind}({})]]", r.name, r.msl_slot);
            assert!(msl_ok(msl_tag.clone()), "{}: no `{msl_tag}`", s.name);
            assert_eq!(r.msl(), format!("{msl_kind}({})", r.msl_slot), "{}", r.name);
            if r.class != ResourceClass::Sampler {
                let reg = hlsl_register(letter, r);
                assert!(
                    hlsl.contains(&format!(" {} : {reg}", r.name)),
                    "{}: {} not at {reg}",
                    s.name,
                    r.name
                );
                // The README's cell says the same.
                assert_eq!(r.hlsl(), format!("{letter}{}, space{}", r.binding, r.group), "{}", r.name);
            }
        }
        // The fragment pipeline's layout is the one engines were given before the compute
        // entry points: uniform blocks, textures and samplers keep their slots in both
        // numberings, and the storage resources come after them in MSL.
        for r in rows.iter().filter(|r| {
            matches!(r.class, ResourceClass::Uniform | ResourceClass::Texture | ResourceClass::Sampler)
        }) {
            assert_eq!(r.slot, r.msl_slot, "{}: {}", s.name, r.name);
        }
        // GLSL numbers each of its namespaces from 0 without gaps; MSL its buffers, textures
        // and samplers.
        let glsl_ns = |c: ResourceClass| match c {
            ResourceClass::StorageBuffer { .. } => 3,
            ResourceClass::Uniform => 0,
            ResourceClass::Texture => 1,
            ResourceClass::Sampler => 2,
            ResourceClass::StorageTexture => 4,
        };
        let msl_ns = |c: ResourceClass| match c {
            ResourceClass::Uniform | ResourceClass::StorageBuffer { .. } => 0,
            ResourceClass::Texture | ResourceClass::StorageTexture => 1,
            ResourceClass::Sampler => 2,
        };
        for ns in 0..5 {
            let mut glsl: Vec<u32> = rows.iter().filter(|r| glsl_ns(r.class) == ns).map(|r| r.slot).collect();
            let mut metal: Vec<u32> =
                rows.iter().filter(|r| msl_ns(r.class) == ns).map(|r| r.msl_slot).collect();
            glsl.sort_unstable();
            metal.sort_unstable();
            assert_eq!(glsl, (0..glsl.len() as u32).collect::<Vec<_>>(), "{}: GLSL namespace {ns}", s.name);
            assert_eq!(metal, (0..metal.len() as u32).collect::<Vec<_>>(), "{}: MSL namespace {ns}", s.name);
        }
        // Metal kernels read their storage buffers' sizes at the slot after every buffer.
        if p.module.entry_points.iter().any(|ep| ep.stage == ShaderStage::Compute) {
            let tag = format!("_buffer_sizes [[buffer({})]]", msl_sizes_slot(&rows));
            assert!(msl.contains(&tag), "{}: no {tag}", s.name);
        }
        // GLSL: each resource a stage declares (naga names it `_group_G_binding_B_<stage>`)
        // sits at its documented binding point or unit, storage buffers as std430 blocks and
        // storage textures with their formats.
        let mut declared = BTreeSet::new();
        for f in translate(&s, &p, Lang::Glsl).expect("glsl") {
            let text = String::from_utf8(f.bytes).expect("text");
            for r in rows.iter().filter(|r| r.class != ResourceClass::Sampler) {
                let var = format!("_group_{}_binding_{}_", r.group, r.binding);
                let Some(line) = text.lines().find(|l| l.starts_with("layout(") && l.contains(&var)) else {
                    continue;
                };
                declared.insert(r.name.clone());
                assert!(
                    line.contains(&format!("binding = {}", r.slot)),
                    "{}: {} in `{line}`",
                    f.name,
                    r.name
                );
                match r.class {
                    ResourceClass::StorageBuffer { writable } => {
                        assert!(line.starts_with("layout(std430, ") && line.contains(" buffer "), "{line}");
                        assert_eq!(line.contains("readonly"), !writable, "{line}");
                    }
                    ResourceClass::StorageTexture => {
                        let format =
                            ["rgba32f", "rg32f", "r32ui"].iter().any(|f| line.contains(&format!(",{f})")));
                        assert!(
                            format && line.contains("writeonly uniform") && line.contains("image2D"),
                            "{line}"
                        );
                    }
                    ResourceClass::Uniform => assert!(line.starts_with("layout(std140, "), "{line}"),
                    _ => assert!(line.contains("sampler2D"), "{line}"),
                }
            }
        }
        // Every resource some entry point uses is declared in some stage's file.
        for r in rows.iter().filter(|r| r.class != ResourceClass::Sampler && used.contains(&r.name)) {
            assert!(declared.contains(&r.name), "{}: {} declared in no GLSL file", s.name, r.name);
        }
        // SPIR-V: descriptor set = group, binding = binding, for every resource.
        let spv = translate(&s, &p, Lang::Spv).expect("spv");
        let spirv = check_spirv(&spv[0].name, &spv[0].bytes);
        for r in &rows {
            assert_eq!(spirv.bindings.get(&r.name), Some(&(r.group, r.binding)), "{}: {}", s.name, r.name);
        }
    }
    // The shaders cover every class of binding the layout knows, save read-write storage
    // buffers (the relief compute pipeline's visibility pass has the only one, and it is not
    // exported).
    let expected: BTreeSet<String> = [
        ResourceClass::Uniform,
        ResourceClass::Texture,
        ResourceClass::Sampler,
        ResourceClass::StorageBuffer { writable: false },
        ResourceClass::StorageTexture,
    ]
    .iter()
    .map(|c| format!("{c:?}"))
    .collect();
    assert_eq!(classes, expected);
}

/// A read-write storage buffer (which no exported shader has) takes a `u` register in HLSL,
/// a writable std430 block in GLSL, a buffer slot after the uniform blocks' in MSL, and its
/// group and binding in SPIR-V.
#[test]
fn a_read_write_storage_buffer_binds_as_documented() {
    let wgsl = "@group(0) @binding(0) var<uniform> scale: vec4<f32>;\n\
                @group(1) @binding(2) var<storage, read_write> values: array<f32>;\n\
                @compute @workgroup_size(64)\n\
                fn cs_scale(@builtin(global_invocation_id) id: vec3<u32>) {\n\
                    if id.x < arrayLength(&values) { values[id.x] *= scale.x; }\n\
                }\n";
    let s = ExportShader { name: "rw".into(), kind: ShaderKind::Filters, wgsl: wgsl.into() };
    let p = parse(&s.name, &s.wgsl).expect("parses");
    let rows = binding_layout(&p.module);
    let values = rows.iter().find(|r| r.name == "values").expect("bound");
    assert_eq!(values.class, ResourceClass::StorageBuffer { writable: true });
    assert_eq!((values.slot, values.msl_slot), (0, 1));
    assert_eq!(values.hlsl(), "u2, space1");
    let text = |lang| {
        String::from_utf8(translate(&s, &p, lang).expect("translates")[0].bytes.clone()).expect("text")
    };
    assert!(text(Lang::Hlsl).contains("RWByteAddressBuffer values : register(u2, space1);"));
    let glsl = text(Lang::Glsl);
    let block = glsl.lines().find(|l| l.contains("_group_1_binding_2_cs")).expect("declared");
    assert!(
        block.starts_with("layout(std430, binding = 0) buffer") && !block.contains("readonly"),
        "{block}"
    );
    assert!(text(Lang::Msl).contains("values [[buffer(1)]]"));
    let spv = translate(&s, &p, Lang::Spv).expect("spv");
    assert_eq!(check_spirv("rw.spv", &spv[0].bytes).bindings.get("values"), Some(&(1, 2)));
}

#[test]
fn every_input_has_a_description_and_every_description_an_input() {
    let mut used = BTreeSet::new();
    for s in all() {
        let p = parse(&s.name, &s.wgsl).expect("parses");
        let list = items(&p);
        assert!(list.len() > 5, "{}: {} items", s.name, list.len());
        for item in list {
            assert!(
                describe(&item.key).is_some(),
                "{}: input '{}' ({}) has no description",
                s.name,
                item.key,
                item.kind.label()
            );
            used.insert(item.key);
        }
    }
    for (key, _) in DESCRIPTIONS {
        assert!(used.contains(*key), "description of '{key}', which no shader has");
    }
}

#[test]
fn the_readme_names_every_file_and_input() {
    let dir = tempfile::tempdir().expect("temp dir");
    let set = all();
    let written = export::export(dir.path(), &Lang::ALL, &set).expect("export");
    let readme = std::fs::read_to_string(dir.path().join("README.md")).expect("README");
    assert_eq!(written[0], dir.path().join("README.md"));
    for path in &written[1..] {
        let name = path.file_name().and_then(|n| n.to_str()).expect("file name");
        assert!(readme.contains(&format!("`{name}`")), "README does not list {name}");
        assert!(std::fs::metadata(path).expect("written").len() > 0, "{name}");
    }
    for s in &set {
        let p = parse(&s.name, &s.wgsl).expect("parses");
        for item in items(&p) {
            assert!(readme.contains(&format!("`{}`", item.key)), "README lacks {}", item.key);
        }
        assert!(readme.contains(&format!("### {}\n", s.name)), "README lacks {}'s section", s.name);
    }
    assert!(!readme.contains("(no description)"));
    // The compute entry points: their section, the visibility buffer's layout, Metal's sizes
    // buffer at the slot after the relief modules' seven buffers, and per shader what each
    // kernel reads and writes.
    for needle in [
        "\n## Compute entry points\n",
        "(⌈width/8⌉, ⌈height/8⌉, 1) workgroups",
        "| x | the object: its index in `mesh_objects`; `0xffffffff` where no surface shows |",
        "`_buffer_sizes` at `buffer(7)`",
        "`object_patches`, `mesh_vertices`, `mesh_indices`, `mesh_objects`, `vis_buffer`, each the bound buffer's length in bytes",
        "`NAME.comp` (cs_color), `NAME.cs_debug.comp` (cs_debug)",
    ] {
        assert!(readme.contains(needle), "README lacks {needle}");
    }
    for s in set.iter().filter(|s| matches!(s.kind, ShaderKind::Relief(_))) {
        let section = &readme[readme.find(&format!("### {}\n", s.name)).expect("section")..];
        for ep in COMPUTE_ENTRY_POINTS {
            let line = section.lines().find(|l| l.starts_with(&format!("`{ep}` reads "))).expect("listed");
            assert!(
                line.contains("`vis_buffer`") && line.contains("; writes `out_color`"),
                "{}: {line}",
                s.name
            );
        }
    }
    // Every parameter of every technique is named with its place in Frame.params.
    for d in DESCRIPTORS {
        for (i, p) in d.params.iter().enumerate() {
            assert!(readme.contains(&format!("`params[{i}]` = {}", p.help())), "{}: {}", d.name, p.name);
        }
    }
    // No temporary file is left behind.
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .expect("list")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// Runs glslang on every exported `.vert`, `.frag` and `.comp`. Without `glslangValidator` the test
/// fails when `CI` is set (`.ci/run` installs Debian's glslang-tools) and says it skipped
/// otherwise.
#[test]
fn exported_glsl_compiles_with_glslang() {
    let tool = "glslangValidator";
    if Command::new(tool).arg("--version").output().is_err() {
        if std::env::var_os("CI").is_some() {
            panic!("CI is set but {tool} is missing (install Debian's glslang-tools)");
        }
        eprintln!("SKIPPED ({tool} not found, and CI is not set): install glslang-tools");
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let written = export::export(dir.path(), &[Lang::Glsl], &all()).expect("export");
    let stages: Vec<&Path> = written
        .iter()
        .map(|p| p.as_path())
        .filter(|p| p.extension().is_some_and(|e| e == "vert" || e == "frag" || e == "comp"))
        .collect();
    assert_eq!(stages.len(), written.len() - 1, "only stages beside the README");
    // Every relief technique's two compute entry points are among them.
    let comp = stages.iter().filter(|p| p.extension().is_some_and(|e| e == "comp")).count();
    assert_eq!(comp, 2 * DESCRIPTORS.len(), "compute files");
    for path in stages {
        // OpenGL semantics (GLSL 4.50 core as an OpenGL driver compiles it), and OpenGL
        // SPIR-V, which also demands explicit locations and bindings.
        for flags in [&[][..], &["-G"][..]] {
            let out =
                Command::new(tool).args(flags).arg(path).current_dir(dir.path()).output().expect("runs");
            assert!(
                out.status.success(),
                "{tool} {flags:?} refuses {}:\n{}{}",
                path.display(),
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }
}

#[test]
fn bad_input_is_one_clear_error() {
    // An unknown language names itself and the languages accepted.
    let e = Lang::parse("cuda").expect_err("unknown language");
    let msg = e.to_string();
    assert!(msg.contains("cuda") && msg.contains("glsl") && !msg.contains('\n'), "{msg}");

    // Broken WGSL is refused by name with the place, on one line.
    let e = parse("broken", "fn f() -> f32 { return 1.0 + ; }").err().expect("does not parse");
    assert!(matches!(e, GpuError::Shader { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("broken") && msg.contains("line 1") && !msg.contains('\n'), "{msg}");
    // WGSL that parses but does not validate: a type error.
    let e = parse("mistyped", "fn f() -> f32 { return 1u; }").err().expect("does not validate");
    assert!(e.to_string().contains("validator") && !e.to_string().contains('\n'), "{e}");

    // An output directory that cannot be created (a file stands in the way): an error, and
    // nothing written.
    let dir = tempfile::tempdir().expect("temp dir");
    let blocker = dir.path().join("file");
    std::fs::write(&blocker, b"x").expect("write");
    let out = blocker.join("shaders");
    let e = export::export(&out, &[Lang::Wgsl], &all()).expect_err("cannot create");
    assert!(e.to_string().contains("cannot create directory") && !e.to_string().contains('\n'), "{e}");
    assert!(!out.exists());
    let e = export::export(dir.path(), &[], &all()).expect_err("no language");
    assert!(matches!(e, GpuError::Export(_)), "{e}");
}
