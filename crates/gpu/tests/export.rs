//! `shaders export`: every shader in every language, the GLSL compiled by an outside compiler
//! (glslang), the SPIR-V's structure, the README's completeness, and bad input. None of these
//! needs a GPU: naga translates on the CPU.

use renderlab_gpu::export::backends::{ResourceClass, SPIRV_MAGIC};
use renderlab_gpu::export::descriptions::{describe, DESCRIPTIONS};
use renderlab_gpu::export::reflect::items;
use renderlab_gpu::export::{self, binding_layout, parse, shaders, translate, ExportShader, Lang};
use renderlab_gpu::GpuError;
use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_relief::Technique;
use std::collections::BTreeSet;
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

/// The SPIR-V header and instruction stream: magic, version 1.0, a positive id bound, every
/// instruction's word count inside the module and ending exactly at its end, and one
/// `OpEntryPoint` per entry point of the WGSL module.
fn check_spirv(name: &str, bytes: &[u8], entry_points: usize) {
    assert!(bytes.len().is_multiple_of(4) && bytes.len() > 20, "{name}: {} bytes", bytes.len());
    let words: Vec<u32> =
        bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    assert_eq!(words[0], SPIRV_MAGIC, "{name}: magic");
    assert_eq!(words[1], 0x0001_0000, "{name}: SPIR-V 1.0");
    assert!(words[3] > 1, "{name}: id bound {}", words[3]);
    let (mut at, mut found) = (5usize, 0usize);
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let opcode = words[at] & 0xffff;
        assert!(count >= 1 && at + count <= words.len(), "{name}: instruction at word {at} overruns");
        if opcode == 15 {
            found += 1; // OpEntryPoint
        }
        at += count;
    }
    assert_eq!(found, entry_points, "{name}: entry points");
}

#[test]
fn every_shader_translates_into_every_language() {
    for s in all() {
        let p = parse(&s.name, &s.wgsl).unwrap_or_else(|e| panic!("{e}"));
        let eps = p.module.entry_points.len();
        for lang in Lang::ALL {
            let files = translate(&s, &p, lang).unwrap_or_else(|e| panic!("{}: {lang}: {e}", s.name));
            let expected = if lang == Lang::Glsl { eps } else { 1 };
            assert_eq!(files.len(), expected, "{}: {lang}", s.name);
            for f in &files {
                assert!(!f.bytes.is_empty(), "{}", f.name);
                assert!(f.name.starts_with(&s.name), "{}", f.name);
                if lang == Lang::Spv {
                    check_spirv(&f.name, &f.bytes, eps);
                } else {
                    let text = std::str::from_utf8(&f.bytes).expect("text");
                    // Every entry point is in the file that holds it.
                    let has = p.module.entry_points.iter().filter(|ep| text.contains(&ep.name)).count();
                    if lang == Lang::Glsl {
                        assert!(text.starts_with("#version 450 core"), "{}", f.name);
                        assert!(text.contains("void main()"), "{}", f.name);
                    } else {
                        assert_eq!(has, eps, "{}: entry points in {lang}", f.name);
                    }
                }
            }
        }
    }
}

#[test]
fn bindings_follow_the_documented_layout() {
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
            let msl_ok = |tag: String| !used.contains(&r.name) || msl.contains(&tag);
            match r.class {
                ResourceClass::Uniform => {
                    // naga leaves out `space0`, the default.
                    let reg = match r.group {
                        0 => format!("register(b{})", r.binding),
                        g => format!("register(b{}, space{g})", r.binding),
                    };
                    assert!(hlsl.contains(&reg), "{}: {} not at {reg}", s.name, r.name);
                    assert!(msl_ok(format!("[[buffer({})]]", r.slot)), "{}: {}", s.name, r.name);
                }
                ResourceClass::Texture => {
                    let reg = match r.group {
                        0 => format!("register(t{})", r.binding),
                        g => format!("register(t{}, space{g})", r.binding),
                    };
                    assert!(hlsl.contains(&reg), "{}: {} not at {reg}", s.name, r.name);
                    assert!(msl_ok(format!("[[texture({})]]", r.slot)), "{}: {}", s.name, r.name);
                }
                ResourceClass::Sampler => {
                    assert!(msl_ok(format!("[[sampler({})]]", r.slot)), "{}: {}", s.name, r.name);
                }
            }
        }
        // Slots count each class from 0 without gaps.
        for class in [ResourceClass::Uniform, ResourceClass::Texture, ResourceClass::Sampler] {
            let slots: Vec<u32> = rows.iter().filter(|r| r.class == class).map(|r| r.slot).collect();
            assert_eq!(slots, (0..slots.len() as u32).collect::<Vec<_>>(), "{}: {class:?}", s.name);
        }
        // GLSL: every texture a stage reads sits at its documented unit.
        for f in translate(&s, &p, Lang::Glsl).expect("glsl") {
            let text = String::from_utf8(f.bytes).expect("text");
            let units = text.matches("sampler2D").count();
            let bound =
                (0..rows.len()).filter(|u| text.contains(&format!("layout(binding = {u}) uniform"))).count();
            assert!(units == 0 || bound > 0, "{}: textures without bindings", f.name);
        }
    }
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

/// Runs glslang on every exported `.vert` and `.frag`. Without `glslangValidator` the test
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
        .filter(|p| p.extension().is_some_and(|e| e == "vert" || e == "frag"))
        .collect();
    assert_eq!(stages.len(), written.len() - 1, "only stages beside the README");
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
