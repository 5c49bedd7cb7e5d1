//! What the binary says, and when: every input and output is checked before any work and
//! before any directory is made; no arguments give the help; a value that looks negative
//! reaches its flag's range check; one size parser serves every `WIDTHxHEIGHT` flag; an
//! option either applies or is refused; a frame beyond the memory budget is refused in one
//! line; GPU runs print nothing of Mesa's about `XDG_RUNTIME_DIR`; the viewer without a
//! Vulkan driver says what to install.

use std::path::Path;
use std::process::{Command, Output};

fn renderlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_renderlab")).args(args).output().expect("binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts a clean failure before any work: exit code 1, one stderr line naming `needle`
/// (and none of `absent`), nothing on stdout (every command prints its result there, after
/// the work).
fn refused_before_work(args: &[&str], needle: &str) -> String {
    let out = renderlab(args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{args:?} should fail with 1; stderr: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{args:?}: expected one line, got {err}");
    assert!(lines[0].starts_with("renderlab: error: "), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: '{needle}' not in: {err}");
    assert!(out.stdout.is_empty(), "{args:?} did work first: {}", String::from_utf8_lossy(&out.stdout));
    err
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn an_output_file_that_is_a_directory_is_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    // Directories named like images, so that only their being directories is wrong.
    let png = dir.path().join("frame.png");
    std::fs::create_dir(&png).unwrap();
    let o = s(&png);
    for args in [
        &["relief", "render", "--out", o, "--width", "16", "--height", "16", "--texture-size", "32"][..],
        &["texture", "render", "--out", o, "--width", "16", "--height", "16"][..],
        &["hybrid", "render", "--scene", "showcase", "--resolution", "16x9", "--out", o][..],
    ] {
        let err = refused_before_work(args, "is a directory");
        assert!(err.contains(o), "{err}");
    }
    let h = dir.path().join("h.png");
    write_gray_png(&h, 8, 8);
    refused_before_work(&["complexity", s(&h), o], "is a directory");
    assert!(png.is_dir() && std::fs::read_dir(&png).unwrap().next().is_none(), "nothing written inside");
}

#[test]
fn relief_bench_with_a_bad_input_makes_no_out_directory() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let o = s(&out);
    let small = ["relief", "bench", "--out", o, "--resolution", "16x16", "--texture-size", "32"];
    let with = |extra: &[&'static str]| [&small[..], extra].concat();
    refused_before_work(&with(&["--albedo", "missing.png", "--height-map", "missing.png"]), "missing.png");
    refused_before_work(&with(&["--material", "marble"]), "--material");
    refused_before_work(&with(&["--texture-size", "8"]), "--texture-size");
    refused_before_work(&with(&["--cone-size", "8"]), "--cone-size");
    assert!(!out.exists(), "relief bench made {o} before failing");
}

#[test]
fn output_directories_that_cannot_be_made_are_refused_before_work() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("file");
    std::fs::write(&file, b"x").unwrap();
    let under = file.join("run");
    for o in [s(&file), s(&under)] {
        for args in [
            &["water", "--out", o, "--frames", "1", "--size", "16x16"][..],
            &["materials", "--out", o, "--size", "16"][..],
            &["shaders", "export", "--lang", "wgsl", "--out", o][..],
            &["hybrid", "bench", "--out", o, "--scenes", "showcase", "--resolution", "16x9"][..],
            &["report", "--out", o][..],
        ] {
            refused_before_work(args, o);
        }
    }
    // A bad size of `materials` is found before its directory is made.
    let maps = dir.path().join("maps");
    refused_before_work(&["materials", "--out", s(&maps), "--size", "4"], "--size");
    assert!(!maps.exists());
}

#[test]
fn no_arguments_print_the_help_and_exit_2() {
    let out = renderlab(&[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("Usage:") && err.contains("Commands:"), "{err}");
    assert!(!err.contains("error:"), "{err}");
}

#[test]
fn values_that_look_negative_reach_their_range_check() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("x.png");
    let d = dir.path().join("d");
    for (args, needle) in [
        (vec!["relief", "render", "--out", s(&o), "--angle", "-inf"], "--angle"),
        (vec!["relief", "render", "--out", s(&o), "--angle", "-nan"], "--angle"),
        (vec!["relief", "bench", "--out", s(&d), "--angles", "0,-inf"], "--angles"),
        (vec!["water", "--out", s(&d), "--size", "-16x16"], "at least 1"),
        (vec!["smoke", "--out", s(&d), "--size", "16x-16"], "at least 1"),
        (
            vec!["hybrid", "render", "--scene", "showcase", "--out", s(&o), "--resolution", "-16x9"],
            "at least 1",
        ),
        (vec!["noise", "--out", s(&d), "--frequency", "-inf"], "--frequency"),
    ] {
        let err = refused_before_work(&args, needle);
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
    }
    assert!(!d.exists() && !o.exists());
}

#[test]
fn every_size_flag_takes_the_same_forms() {
    let dir = tempfile::tempdir().unwrap();
    let water = dir.path().join("water");
    let out = renderlab(&["water", "--out", s(&water), "--frames", "1", "--size", "16×9"]);
    assert!(out.status.success(), "water 16×9: {}", stderr(&out));
    assert!(water.join("frame_0000.png").is_file());
    let smoke = dir.path().join("smoke");
    let out = renderlab(&["smoke", "--out", s(&smoke), "--frames", "1", "--size", "16X16", "--grid", "8"]);
    assert!(out.status.success(), "smoke 16X16: {}", stderr(&out));
    let png = dir.path().join("h.png");
    let out =
        renderlab(&["hybrid", "render", "--scene", "showcase", "--resolution", "16×9", "--out", s(&png)]);
    assert!(out.status.success(), "hybrid 16×9: {}", stderr(&out));
    assert!(String::from_utf8_lossy(&out.stdout).contains("16x9"));
    // One message for a malformed size, wherever it is given.
    for args in [
        vec!["water", "--out", s(&water), "--size", "16y9"],
        vec!["hybrid", "render", "--scene", "showcase", "--out", s(&png), "--resolution", "16y9"],
        vec!["relief", "bench", "--out", s(&water), "--resolution", "16y9"],
    ] {
        refused_before_work(&args, "is not WIDTHxHEIGHT");
    }
}

#[test]
fn height_scale_applies_to_the_built_in_materials_and_is_checked_alike() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("r.png");
    let base =
        ["relief", "render", "--out", s(&o), "--width", "48", "--height", "32", "--texture-size", "64"];
    let with = |extra: &[&'static str]| [&base[..], &["--angle", "60"], extra].concat();
    for bad in ["-1", "5", "nan"] {
        refused_before_work(&with(&["--height-scale", bad]), "--height-scale");
        refused_before_work(&with(&["--height-scale", bad, "--scene", "room"]), "--height-scale");
    }
    assert!(!o.exists());
    let render = |extra: &[&'static str]| {
        let out = renderlab(&with(extra));
        assert!(out.status.success(), "{extra:?}: {}", stderr(&out));
        std::fs::read(&o).unwrap()
    };
    let own = render(&[]);
    let flat = render(&["--height-scale", "0"]);
    let deep = render(&["--height-scale", "0.2"]);
    assert_ne!(own, flat, "--height-scale 0 changed nothing");
    assert_ne!(own, deep, "--height-scale 0.2 changed nothing");
    // The viewer puts it on your maps only, and says so rather than ignore it.
    refused_before_work(&["view", "--height-scale", "0.1"], "--height-scale");
}

#[test]
fn a_frame_over_the_memory_budget_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("x.png");
    let run = dir.path().join("run");
    let err = refused_before_work(
        &["hybrid", "render", "--scene", "showcase", "--resolution", "4097x4097", "--out", s(&o)],
        "--resolution 4097x4097 needs about",
    );
    assert!(err.contains("GiB memory budget") && err.contains("the largest frame"), "{err}");
    refused_before_work(
        &["hybrid", "bench", "--out", s(&run), "--scenes", "showcase", "--resolution", "4097x4097"],
        "GiB memory budget",
    );
    assert!(!o.exists() && !run.exists());
}

#[test]
fn a_texture_over_the_memory_budget_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("x.png");
    refused_before_work(
        &["relief", "render", "--out", s(&o), "--width", "16", "--height", "16", "--texture-size", "8192"],
        "--texture-size",
    );
    assert!(!o.exists());
}

/// Whether Vulkan lists an adapter here (lavapipe counts); without one the GPU checks are
/// skipped unless `CI` is set (CI installs lavapipe).
fn have_vulkan(dir: &Path) -> bool {
    let o = dir.join("probe.png");
    let out = renderlab(&[
        "relief",
        "render",
        "--out",
        s(&o),
        "--width",
        "8",
        "--height",
        "8",
        "--texture-size",
        "16",
        "--backend",
        "gpu",
        "-t",
        "basic",
    ]);
    if out.status.success() {
        return true;
    }
    assert!(std::env::var_os("CI").is_none(), "CI is set but no Vulkan adapter: {}", stderr(&out));
    eprintln!("SKIPPED (no Vulkan adapter, and CI is not set)");
    false
}

#[test]
fn gpu_runs_print_nothing_about_xdg_runtime_dir() {
    let dir = tempfile::tempdir().unwrap();
    if !have_vulkan(dir.path()) {
        return;
    }
    let o = dir.path().join("g.png");
    let out = Command::new(env!("CARGO_BIN_EXE_renderlab"))
        .args(["relief", "render", "--out", s(&o), "--width", "16", "--height", "16", "--texture-size", "32"])
        .args(["--backend", "gpu", "-t", "basic"])
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("NODEVICE_SELECT")
        .env_remove("MESA_VK_DEVICE_SELECT")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).trim().is_empty(), "stderr: {}", stderr(&out));
    // Mesa 22.3's layer is silent there, Mesa 25's is not: check the cause, not only the
    // symptom. The Vulkan loader's own trace lists the layers of the instance it creates:
    // Mesa's device-select layer must be absent without XDG_RUNTIME_DIR, and present (left
    // alone) with a valid one, where the layer is installed at all.
    let layer = "Library:  libVkLayer_MESA_device_select";
    let traced = |xdg: Option<&Path>| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_renderlab"));
        c.args([
            "relief",
            "render",
            "--out",
            s(&o),
            "--width",
            "16",
            "--height",
            "16",
            "--texture-size",
            "32",
        ])
        .args(["--backend", "gpu", "-t", "basic"])
        .env("VK_LOADER_DEBUG", "layer")
        .env_remove("NODEVICE_SELECT")
        .env_remove("MESA_VK_DEVICE_SELECT");
        match xdg {
            Some(d) => c.env("XDG_RUNTIME_DIR", d),
            None => c.env_remove("XDG_RUNTIME_DIR"),
        };
        let out = c.output().unwrap();
        assert!(out.status.success(), "{}", stderr(&out));
        stderr(&out)
    };
    if Path::new("/usr/share/vulkan/implicit_layer.d/VkLayer_MESA_device_select.json").is_file() {
        assert!(
            traced(Some(dir.path())).contains(layer),
            "the layer should stay with a valid XDG_RUNTIME_DIR"
        );
        assert!(!traced(None).contains(layer), "the device-select layer is still loaded");
    }
}

#[test]
fn the_viewer_without_a_vulkan_driver_says_what_to_install() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_renderlab"))
        .args(["view", "--screenshot", s(&dir.path().join("v.png")), "--frames", "1"])
        .env("XDG_CONFIG_HOME", dir.path())
        .env("VK_ICD_FILENAMES", "/nonexistent.json")
        .env("VK_DRIVER_FILES", "/nonexistent.json")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(err.contains("no GPU adapter found") && err.contains("mesa-vulkan-drivers"), "{err}");
    assert!(!err.contains("Failed to create surface"), "{err}");
}

fn write_gray_png(path: &Path, w: u32, h: u32) {
    let mut buf = Vec::new();
    {
        let mut e = png::Encoder::new(&mut buf, w, h);
        e.set_color(png::ColorType::Grayscale);
        e.set_depth(png::BitDepth::Eight);
        let mut wr = e.write_header().unwrap();
        let data: Vec<u8> = (0..w * h).map(|i| (i * 7 % 251) as u8).collect();
        wr.write_image_data(&data).unwrap();
    }
    std::fs::write(path, buf).unwrap();
}

#[test]
fn a_value_out_of_range_is_refused_in_one_line_naming_the_flag_the_value_and_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("x.png");
    let d = dir.path().join("d");
    for (args, flag, value, range) in [
        (vec!["water", "--out", s(&d), "--fps", "0"], "--fps", "0", "1..=1000"),
        (vec!["water", "--out", s(&d), "--pitch", "95"], "--pitch", "95", "[-89, 89]"),
        (vec!["water", "--out", s(&d), "--size", "4x4"], "--size", "4x4", "8..=8192"),
        (vec!["water", "--out", s(&d), "--time-step", "0"], "--time-step", "0", "(0, 60]"),
        (vec!["smoke", "--out", s(&d), "--sigma", "nan"], "--sigma", "NaN", "(0, 8]"),
        (vec!["smoke", "--out", s(&d), "--grid", "2"], "--grid", "2", "4..=256"),
        (vec!["noise", "--out", s(&d), "--octaves", "-1"], "--octaves", "-1", "1..=32"),
        (vec!["relief", "bench", "--out", s(&d), "--reps", "0"], "--reps", "0", "1..=1000"),
        (vec!["relief", "bench", "--out", s(&d), "--angles", "0,90"], "--angles", "90", "[0, 89]"),
        (vec!["relief", "render", "--out", s(&o), "--angle", "inf"], "--angle", "inf", "[0, 89]"),
        (vec!["relief", "render", "--out", s(&o), "--height-scale", "2"], "--height-scale", "2", "[0, 1]"),
        (vec!["materials", "--out", s(&d), "--size", "8"], "--size", "8", "16..=8192"),
        (vec!["view", "--texture-size", "4"], "--texture-size", "4", "8..=8192"),
    ] {
        let err = refused_before_work(&args, flag);
        assert!(err.contains(value) && err.contains(range), "{args:?}: {err}");
    }
    assert!(!d.exists() && !o.exists());
}
