//! The binary as a user meets it: every command answers `--help`, good input writes its
//! output, and bad input gets one clear line naming the file or flag, a non-zero exit, no
//! panic and no output file.

use std::path::Path;
use std::process::{Command, Output};

fn renderlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_renderlab")).args(args).output().expect("binary runs")
}

/// Asserts a clean failure: exit code 1, exactly one stderr line that mentions `needle`.
fn fails_with(args: &[&str], needle: &str) {
    let out = renderlab(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?} should fail with 1; stderr: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{args:?}: expected one line, got {err}");
    assert!(err.contains(needle), "{args:?}: '{needle}' not in: {err}");
}

fn write_png(path: &Path, w: u32, h: u32) {
    let img = renderlab_core_free_gray(w, h);
    let mut buf = Vec::new();
    {
        let mut enc = png_encoder(&mut buf, w, h);
        enc.write_image_data(&img).unwrap();
    }
    std::fs::write(path, buf).unwrap();
}

fn renderlab_core_free_gray(w: u32, h: u32) -> Vec<u8> {
    (0..w * h).map(|i| ((i % w) * 255 / w.max(1)) as u8 ^ ((i / w) as u8 & 16)).collect()
}

fn png_encoder(buf: &mut Vec<u8>, w: u32, h: u32) -> png::Writer<&mut Vec<u8>> {
    let mut e = png::Encoder::new(buf, w, h);
    e.set_color(png::ColorType::Grayscale);
    e.set_depth(png::BitDepth::Eight);
    e.write_header().unwrap()
}

#[test]
fn every_command_has_help() {
    for args in [
        vec!["--help"],
        vec!["report", "--help"],
        vec!["relief", "--help"],
        vec!["relief", "bench", "--help"],
        vec!["relief", "render", "--help"],
        vec!["complexity", "--help"],
        vec!["materials", "--help"],
        vec!["noise", "--help"],
        vec!["water", "--help"],
        vec!["smoke", "--help"],
        vec!["shaders", "--help"],
        vec!["shaders", "export", "--help"],
    ] {
        let out = renderlab(&args);
        assert!(out.status.success(), "{args:?}");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("Usage"), "{args:?}: {text}");
    }
}

#[test]
fn complexity_map_of_a_png() {
    let dir = tempfile::tempdir().unwrap();
    let h = dir.path().join("h.png");
    write_png(&h, 37, 19);
    let out_path = dir.path().join("c.png");
    let out = renderlab(&["complexity", h.to_str().unwrap(), out_path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("Complexity map saved as"));
    let bytes = std::fs::read(&out_path).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn bad_complexity_input() {
    let dir = tempfile::tempdir().unwrap();
    let d = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let out = d("c.png");
    fails_with(&["complexity", &d("missing.png"), &out], "missing.png");
    std::fs::write(d("empty.png"), b"").unwrap();
    fails_with(&["complexity", &d("empty.png"), &out], "empty.png");
    write_png(Path::new(&d("ok.png")), 20, 20);
    let full = std::fs::read(d("ok.png")).unwrap();
    std::fs::write(d("cut.png"), &full[..full.len() / 2]).unwrap();
    fails_with(&["complexity", &d("cut.png"), &out], "cut.png");
    std::fs::write(d("junk.png"), b"\x89PNG\r\n\x1a\nthis is not a png").unwrap();
    fails_with(&["complexity", &d("junk.png"), &out], "junk.png");
    fails_with(&["complexity", &d("ok.png"), &out, "--gamma", "nan"], "--gamma");
    fails_with(&["complexity", &d("ok.png"), &out, "--levels", "1"], "--levels");
    fails_with(&["complexity", &d("ok.png"), &d("c.bmp")], "c.bmp");
    assert!(!Path::new(&out).exists(), "no output may be written on error");
}

#[test]
fn bad_render_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.png");
    let o = out.to_str().unwrap();
    let small = ["--width", "32", "--height", "20", "--texture-size", "32"];
    let with = |extra: &[&str]| -> Vec<String> {
        let mut v: Vec<String> = ["relief", "render", "-o", o].iter().map(|s| s.to_string()).collect();
        v.extend(small.iter().map(|s| s.to_string()));
        v.extend(extra.iter().map(|s| s.to_string()));
        v
    };
    let run = |extra: &[&str], needle: &str| {
        let args = with(extra);
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        fails_with(&refs, needle);
    };
    run(&["-t", "fancy"], "fancy");
    run(&["-t", "pom:0"], "--technique");
    run(&["-t", "pom:99999"], "--technique");
    run(&["--material", "marble"], "marble");
    run(&["--angle", "nan"], "--angle");
    run(&["--angle", "95"], "--angle");
    run(&["--height-scale", "inf", "--albedo", "a.png", "--height-map", "h.png"], "--height-scale");
    let args: Vec<&str> = vec!["relief", "render", "-o", o, "--width", "100000", "--height", "20"];
    fails_with(&args, "100000");
    let args: Vec<&str> = vec!["relief", "render", "-o", o, "--width", "0", "--height", "20"];
    fails_with(&args, "--width");
    assert!(!out.exists());
}

#[test]
fn user_maps_of_different_resolutions_render() {
    // A 64² albedo over a 128² height map, as asset sets often ship them: each map is sampled
    // in UV through its own pyramid.
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.png");
    let h = dir.path().join("h.png");
    write_png(&a, 64, 64);
    write_png(&h, 128, 128);
    let out = dir.path().join("r.png");
    let args = [
        "relief",
        "render",
        "-o",
        out.to_str().unwrap(),
        "--albedo",
        a.to_str().unwrap(),
        "--height-map",
        h.to_str().unwrap(),
        "--width",
        "48",
        "--height",
        "32",
    ];
    let o = renderlab(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = renderlab_core::io::load_color(&out).unwrap();
    let px = img.pixels();
    assert!(px.iter().all(|c| c.is_finite()));
    let first = px[0];
    assert!(px.iter().any(|c| (*c - first).abs().max_element() > 0.05), "the image is blank");
}

#[test]
fn negative_numbers_reach_the_range_checks() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.png");
    let o = out.to_str().unwrap();
    let base = ["relief", "render", "-o", o, "--width", "16", "--height", "16"];
    let with = |extra: &[&'static str]| -> Vec<&str> { base.iter().chain(extra).copied().collect() };
    fails_with(
        &with(&["--height-scale", "-1", "--albedo", "a.png", "--height-map", "h.png"]),
        "--height-scale",
    );
    fails_with(&with(&["--angle", "-5"]), "--angle");
    fails_with(&with(&["--gamma", "-0.5"]), "gamma");
    fails_with(&["noise", "--out", o, "--frequency", "-3"], "--frequency");
    assert!(!out.exists());
}

#[test]
fn outputs_in_a_missing_directory_are_refused_before_the_work() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no_such_dir");
    let out = missing.join("out.png");
    let o = out.to_str().unwrap();
    for args in [
        vec!["relief", "render", "-o", o],
        vec!["texture", "render", "-o", o, "--filter", "reference"],
        vec!["complexity", "h.png", o],
    ] {
        fails_with(&args, "no_such_dir");
        let r = renderlab(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(err.contains("out.png") && err.contains("does not exist"), "{args:?}: {err}");
        assert!(String::from_utf8_lossy(&r.stdout).is_empty(), "{args:?}: nothing may be rendered");
        assert!(!out.exists() && !missing.exists(), "{args:?}");
    }
}

#[test]
fn renders_user_maps_and_builtins() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.png");
    let h = dir.path().join("h.png");
    write_png(&a, 24, 40);
    write_png(&h, 24, 40);
    for (t, extra) in [
        ("adaptive", vec![]),
        ("cone:24:3:secant", vec![]),
        ("cone-newton", vec!["--kernel", "scalar"]),
        ("pom:8", vec!["--debug", "error"]),
    ] {
        let out = dir.path().join(format!("{}.png", t.replace(':', "_")));
        let mut args = vec![
            "relief",
            "render",
            "-t",
            t,
            "-o",
            out.to_str().unwrap(),
            "--albedo",
            a.to_str().unwrap(),
            "--height-map",
            h.to_str().unwrap(),
            "--width",
            "48",
            "--height",
            "30",
            "--angle",
            "70",
        ];
        args.extend(extra.iter());
        let o = renderlab(&args);
        assert!(o.status.success(), "{t}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(out.exists());
    }
    let maps = dir.path().join("maps");
    let o = renderlab(&["materials", "--out", maps.to_str().unwrap(), "--size", "16"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(maps.join("bricks_height.png").exists() && maps.join("bark_willow_normal.png").exists());
}

#[test]
fn noise_help_and_clouds_png() {
    let out = renderlab(&["noise", "--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for flag in ["--out", "--seed", "--size", "--octaves", "--frequency", "Usage"] {
        assert!(text.contains(flag), "{flag} not in: {text}");
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("noise");
    let out = renderlab(&[
        "noise",
        "--out",
        d.to_str().unwrap(),
        "--seed",
        "7",
        "--size",
        "64",
        "--octaves",
        "5",
        "--quick",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let png = std::fs::read(d.join("clouds.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 64, "width");
    assert!(d.join("clouds_layer5.png").is_file());
    assert!(d.join("path_fig3_2_xy.svg").is_file());
    assert!(d.join("index.html").is_file());
    // Same flags, same bytes.
    let d2 = dir.path().join("again");
    assert!(renderlab(&[
        "noise",
        "--out",
        d2.to_str().unwrap(),
        "--seed",
        "7",
        "--size",
        "64",
        "--octaves",
        "5",
        "--quick"
    ])
    .status
    .success());
    assert_eq!(std::fs::read(d2.join("clouds.png")).unwrap(), png);
}

#[test]
fn bad_noise_flags() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("n");
    let o = out.to_str().unwrap();
    fails_with(&["noise", "--out", o, "--octaves", "0"], "--octaves");
    fails_with(&["noise", "--out", o, "--octaves", "33"], "--octaves");
    fails_with(&["noise", "--out", o, "--octaves", "32"], "--octaves");
    fails_with(&["noise", "--out", o, "--size", "0"], "--size");
    fails_with(&["noise", "--out", o, "--size", "100000"], "--size");
    fails_with(&["noise", "--out", o, "--frequency", "NaN"], "--frequency");
    fails_with(&["noise", "--out", o, "--frequency", "inf"], "--frequency");
    fails_with(&["noise", "--out", o, "--frequency", "0"], "--frequency");
    fails_with(&["noise", "--out", o, "--frequency", "1e30", "--octaves", "1"], "--octaves/--frequency");
    assert!(!out.exists(), "no output directory for rejected flags");
}

#[test]
fn water_frames_and_bad_flags() {
    let out = renderlab(&["water", "--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for flag in ["--out", "--frames", "--size", "--wind", "--amplitude", "Usage"] {
        assert!(text.contains(flag), "{flag} not in: {text}");
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("water");
    let o = d.to_str().unwrap();
    let out = renderlab(&["water", "--frames", "2", "--size", "64x40", "--out", o]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_two_frames_and_animation(&d, 64, 40);

    let bad = dir.path().join("bad");
    let b = bad.to_str().unwrap();
    fails_with(&["water", "--out", b, "--frames", "0"], "--frames");
    fails_with(&["water", "--out", b, "--fps", "0"], "--fps");
    fails_with(&["water", "--out", b, "--frames", "100000"], "--frames");
    fails_with(&["water", "--out", b, "--size", "0x0"], "--size");
    fails_with(&["water", "--out", b, "--size", "64"], "--size");
    fails_with(&["water", "--out", b, "--size", "99999x99999"], "--size");
    fails_with(&["water", "--out", b, "--frames", "10000", "--size", "8192x8192"], "--frames/--size");
    fails_with(&["water", "--out", b, "--amplitude", "NaN"], "--amplitude");
    fails_with(&["water", "--out", b, "--time-step", "inf"], "--time-step");
    fails_with(&["water", "--out", b, "--pitch", "95"], "--pitch");
    fails_with(&["water", "--out", b, "--octaves", "0"], "--octaves");
    fails_with(&["water", "--out", b, "--start", "1e9"], "--start");
    fails_with(&["water", "--out", b, "--wind", "1"], "--wind");
    fails_with(&["water", "--out", b, "--wind", "nan,1"], "--wind");
    assert!(!bad.exists(), "no output directory for rejected flags");
}

/// `d` holds exactly two PNG frames of `w × h` that differ, and their APNG animation.
fn assert_two_frames_and_animation(d: &Path, w: u32, h: u32) {
    let mut names: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["animation.png", "frame_0000.png", "frame_0001.png"]);
    let anim = std::fs::read(d.join("animation.png")).unwrap();
    assert!(anim.windows(4).any(|w| w == b"acTL"), "animation.png is an APNG");
    let f0 = std::fs::read(d.join("frame_0000.png")).unwrap();
    let f1 = std::fs::read(d.join("frame_0001.png")).unwrap();
    assert_eq!(&f0[1..4], b"PNG");
    assert_eq!(u32::from_be_bytes(f0[16..20].try_into().unwrap()), w, "width");
    assert_eq!(u32::from_be_bytes(f0[20..24].try_into().unwrap()), h, "height");
    assert_ne!(f0, f1, "frames should move");
}

#[test]
fn smoke_frames_and_bad_flags() {
    let out = renderlab(&["smoke", "--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for flag in ["--out", "--frames", "--size", "--grid", "--animation", "--filter", "--sigma", "Usage"] {
        assert!(text.contains(flag), "{flag} not in: {text}");
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("smoke");
    let o = d.to_str().unwrap();
    let out = renderlab(&["smoke", "--frames", "2", "--size", "64x64", "--grid", "32", "--out", o]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_two_frames_and_animation(&d, 64, 64);
    let t = dir.path().join("thesis");
    let args = ["smoke", "--frames", "1", "--size", "32x32", "--grid", "16", "--animation", "thesis"];
    let out = renderlab(&[&args[..], &["--filter", "median", "--out", t.to_str().unwrap()]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(t.join("frame_0000.png").exists());

    let bad = dir.path().join("bad");
    let b = bad.to_str().unwrap();
    fails_with(&["smoke", "--out", b, "--frames", "0"], "--frames");
    fails_with(&["smoke", "--out", b, "--fps", "5000"], "--fps");
    fails_with(&["smoke", "--out", b, "--frames", "100000"], "--frames");
    fails_with(&["smoke", "--out", b, "--size", "0x0"], "--size");
    fails_with(&["smoke", "--out", b, "--size", "64"], "--size");
    fails_with(&["smoke", "--out", b, "--size", "99999x99999"], "--size");
    fails_with(&["smoke", "--out", b, "--grid", "0"], "--grid");
    fails_with(&["smoke", "--out", b, "--grid", "100000"], "--grid");
    fails_with(&["smoke", "--out", b, "--frames", "10000", "--size", "4096x4096"], "--frames/--size");
    fails_with(&["smoke", "--out", b, "--frames", "10000", "--grid", "256"], "--frames/--grid");
    fails_with(&["smoke", "--out", b, "--sigma", "NaN"], "--sigma");
    fails_with(&["smoke", "--out", b, "--absorption", "inf"], "--absorption");
    fails_with(&["smoke", "--out", b, "--light", "0,0,0"], "--light");
    fails_with(&["smoke", "--out", b, "--light", "1,2"], "--light");
    fails_with(&["smoke", "--out", b, "--octaves", "0"], "--octaves");
    fails_with(&["smoke", "--out", b, "--shadow-steps", "0"], "--shadow-steps");
    fails_with(&["smoke", "--out", b, "--step", "0"], "--step");
    fails_with(&["smoke", "--out", b, "--time-step", "nan"], "--time-step");
    fails_with(&["smoke", "--out", b, "--start", "1e9"], "--start");
    fails_with(
        &["smoke", "--out", b, "--animation", "thesis", "--animation-factor", "inf"],
        "--animation-factor",
    );
    assert!(!bad.exists(), "no output directory for rejected flags");
}

#[test]
fn texture_help() {
    for args in
        [vec!["texture", "--help"], vec!["texture", "bench", "--help"], vec!["texture", "render", "--help"]]
    {
        let out = renderlab(&args);
        assert!(out.status.success(), "{args:?}");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("Usage"), "{args:?}: {text}");
    }
}

#[test]
fn texture_bench_on_a_tiny_frame_writes_the_expected_records() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("tex");
    let out = renderlab(&[
        "texture",
        "bench",
        "--out",
        out_dir.to_str().unwrap(),
        "--width",
        "48",
        "--height",
        "32",
        "--reps",
        "1",
        "--warmup",
        "0",
        "--tolerance",
        "0.05",
        "--max-strata",
        "16",
        "--no-sigma-study",
        "--scenes",
        "checkerboard,quad_tilt_70",
        "--filters",
        "trilinear,aniso16:box,ewa",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("results.json")).unwrap()).unwrap();
    let records = json["records"].as_array().unwrap();
    // 2 scenes × 3 filters × 2 references, plus 8 mapping modes × 2 references on the checkerboard.
    let filters: Vec<_> = records.iter().filter(|r| r["kind"] == "filter").collect();
    assert_eq!(filters.len(), 12);
    assert_eq!(records.iter().filter(|r| r["kind"] == "mapping").count(), 16);
    for r in &filters {
        for key in
            ["scene", "method", "reference", "ns_per_pixel", "fetches_per_pixel", "psnr_db", "ssim", "flip"]
        {
            assert!(!r[key].is_null(), "{key} missing in {r}");
        }
    }
    assert!(
        filters.iter().any(|r| r["reference"] == "box")
            && filters.iter().any(|r| r["reference"] == "gaussian")
    );
    // The reference's noise for 2 scenes × 2 models; no σ study.
    assert_eq!(json["noise"].as_array().unwrap().len(), 4);
    assert!(json["sigma_study"].as_array().unwrap().is_empty());
    for f in [
        "results.csv",
        "noise.csv",
        "index.html",
        "img/checkerboard_ewa.png",
        "img/checkerboard_ewa_crop.png",
    ] {
        assert!(out_dir.join(f).exists(), "{f} missing");
    }
}

#[test]
fn texture_render_and_bad_texture_flags() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("t.png");
    let p = png.to_str().unwrap();
    let out = renderlab(&[
        "texture",
        "render",
        "-o",
        p,
        "--scene",
        "zone_plate",
        "--filter",
        "aniso4",
        "--width",
        "32",
        "--height",
        "24",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(&std::fs::read(&png).unwrap()[1..4], b"PNG");
    let o = dir.path().join("b");
    let o = o.to_str().unwrap();
    fails_with(&["texture", "bench", "--out", o, "--filters", "aniso99"], "--filters");
    fails_with(&["texture", "bench", "--out", o, "--filters", "blur"], "unknown filter");
    fails_with(&["texture", "bench", "--out", o, "--scenes", "quad_tilt_90"], "--scenes");
    fails_with(&["texture", "bench", "--out", o, "--tolerance", "0"], "--tolerance");
    fails_with(&["texture", "bench", "--out", o, "--max-strata", "500"], "--max-strata");
    fails_with(&["texture", "bench", "--out", o, "--model", "box"], "--model");
    fails_with(&["texture", "bench", "--out", o, "--model", "sigma=9"], "--model");
    fails_with(&["texture", "bench", "--out", o, "--filters", "ewa:cut=0.5"], "--filters");
    fails_with(&["texture", "bench", "--out", o, "--width", "100000"], "--width");
    fails_with(&["texture", "render", "-o", p, "--scene", "teapot"], "--scene");
    fails_with(&["texture", "render", "-o", p, "--filter", "ewa:0:10"], "--filter");
    let missing = dir.path().join("no_such_texture.png");
    fails_with(
        &["texture", "bench", "--out", o, "--texture", missing.to_str().unwrap()],
        "no_such_texture.png",
    );
    assert!(!dir.path().join("b").exists(), "no output for bad flags");

    // The user's texture replaces the built-in one: a flat mid-grey image gives a flat frame
    // wherever the quad is, with every filter.
    let grey = dir.path().join("grey.png");
    let mut buf = Vec::new();
    png_encoder(&mut buf, 8, 8).write_image_data(&[128u8; 64]).unwrap();
    std::fs::write(&grey, buf).unwrap();
    let user = dir.path().join("user.png");
    let out = renderlab(&[
        "texture",
        "render",
        "-o",
        user.to_str().unwrap(),
        "--scene",
        "thesis_quad_circuit",
        "--texture",
        grey.to_str().unwrap(),
        "--width",
        "32",
        "--height",
        "24",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let img = renderlab_core::io::load_color(&user).unwrap();
    let centre = img.get(16, 12);
    let texel = renderlab_core::io::load_color(&grey).unwrap().get(0, 0);
    assert!((centre - texel).abs().max_element() < 2.0 / 255.0, "{centre} vs {texel}");
}

#[test]
fn errors_name_their_cause_once_and_unwritable_outputs_are_refused_before_work() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.png");
    let out =
        renderlab(&["complexity", missing.to_str().unwrap(), dir.path().join("c.png").to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("missing.png: cannot read"), "{err}");
    assert_eq!(err.matches("No such file").count(), 1, "the cause is printed once: {err}");
    // A JPEG output is refused by name before anything is rendered or written.
    for args in [
        vec!["relief", "render", "--width", "16", "--height", "16", "-o"],
        vec!["texture", "render", "--width", "16", "--height", "16", "-o"],
    ] {
        let jpg = dir.path().join("out.jpg");
        let mut a = args.clone();
        a.push(jpg.to_str().unwrap());
        fails_with(&a, "out.jpg");
        let out = renderlab(&a);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.matches("writes only .png and .exr").count(), 1, "{err}");
        assert!(String::from_utf8_lossy(&out.stdout).is_empty(), "nothing rendered: {:?}", out.stdout);
        assert!(!jpg.exists());
    }
}

/// Every technique has a shader, so `--backend gpu` renders one where an adapter exists (and
/// fails in one line where none does; under `CI` an adapter is required); `--backend auto`
/// renders either way; an unknown backend is a one-line error.
#[test]
fn relief_render_backends() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.png");
    let o = out.to_str().unwrap();
    let base = ["relief", "render", "-o", o, "--width", "24", "--height", "16", "--texture-size", "64"];
    let with =
        |extra: &[&'static str]| base.iter().copied().chain(extra.iter().copied()).collect::<Vec<&str>>();
    let gpu = renderlab(&with(&["-t", "pom-shadow", "--backend", "gpu"]));
    if gpu.status.success() {
        assert!(out.exists(), "the GPU render wrote its image");
        std::fs::remove_file(&out).unwrap();
    } else {
        let err = String::from_utf8_lossy(&gpu.stderr);
        assert!(std::env::var_os("CI").is_none(), "CI needs a GPU adapter (lavapipe): {err}");
        assert!(!out.exists(), "no output after a failure");
    }
    let run = renderlab(&with(&["-t", "pom-shadow", "--backend", "auto"]));
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(out.exists());
    std::fs::remove_file(&out).unwrap();
    // Without any Vulkan driver: `gpu` fails in one line naming the cause, `auto` falls back.
    let no_driver = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_renderlab"))
            .args(args)
            .env("VK_ICD_FILENAMES", "/nonexistent.json")
            .env("VK_DRIVER_FILES", "/nonexistent.json")
            .output()
            .expect("binary runs")
    };
    let gpu = no_driver(&with(&["-t", "pom", "--backend", "gpu"]));
    let err = String::from_utf8_lossy(&gpu.stderr);
    assert_eq!(gpu.status.code(), Some(1), "{err}");
    let lines: Vec<&str> =
        err.lines().filter(|l| !l.trim().is_empty() && !l.contains("XDG_RUNTIME_DIR")).collect();
    assert_eq!(lines.len(), 1, "one line: {err}");
    assert!(err.contains("adapter"), "{err}");
    assert!(!out.exists(), "no output after a failure");
    let auto = no_driver(&with(&["-t", "pom", "--backend", "auto"]));
    assert!(auto.status.success(), "{}", String::from_utf8_lossy(&auto.stderr));
    assert!(String::from_utf8_lossy(&auto.stdout).contains("rendering on the CPU instead"));
    assert!(out.exists());
    fails_with(&with(&["--backend", "metal"]), "--backend");
}

#[test]
fn shaders_export_writes_files_and_refuses_bad_input() {
    let out = renderlab(&["shaders", "export", "--help"]);
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    for word in ["wgsl", "glsl", "hlsl", "msl", "spv", "README.md", "--technique", "cs_color", "NAME.comp"] {
        assert!(help.contains(word), "shaders export --help lacks {word}");
    }

    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("shaders");
    let ds = d.to_str().unwrap();
    let out = renderlab(&["shaders", "export", "--lang", "glsl,spv", "--technique", "pom:16", "--out", ds]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut names: Vec<String> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "README.md",
            "pom.comp",
            "pom.cs_debug.comp",
            "pom.frag",
            "pom.fs_color_pdo.frag",
            "pom.fs_debug.frag",
            "pom.fs_debug_pdo.frag",
            "pom.spv",
            "pom.vert"
        ]
    );

    // Bad input: one line, exit 1, and nothing written.
    let bad = dir.path().join("bad");
    let bs = bad.to_str().unwrap();
    fails_with(&["shaders", "export", "--lang", "cuda", "--out", bs], "cuda");
    fails_with(&["shaders", "export", "--lang", "glsl", "--technique", "nope", "--out", bs], "nope");
    fails_with(&["shaders", "export", "--out", bs], "--lang");
    assert!(!bad.exists());
    // An output directory that cannot be created: a file stands where it would go.
    let file = dir.path().join("file");
    std::fs::write(&file, b"x").unwrap();
    let under = file.join("shaders");
    fails_with(
        &["shaders", "export", "--lang", "wgsl", "--out", under.to_str().unwrap()],
        "cannot create directory",
    );
}
