//! The fused CPU frame against Mesa's llvmpipe drawing the same frame with hand-written GLSL
//! (`scripts/llvmpipe_bench`), side by side in one run. Run by hand from the repository root
//! (not by CI; nothing in the workspace links OpenGL):
//!
//! ```text
//! cc -O2 -o out/llvmpipe_bench scripts/llvmpipe_bench/llvmpipe_bench.c -lEGL -lOpenGL
//! LP_NUM_THREADS=2 cargo run --release -p renderlab-relief --example llvmpipe -- out/llvmpipe_bench [REPS] [TECH…]
//! ```
//!
//! The example builds the relief benchmark's frame (1280×800, the bricks wall 1024², 6 units
//! away at 0°, 45°, 60° and 80°), writes its inputs to `out/llvmpipe/frame.bin` exactly as the
//! fused frame reads them (the mesh, each view's matrix and eye, the light and material
//! constants, the 8-bit sRGB albedo and unorm normal map with their mip chains, the packed
//! map's 16-bit depths, the complexity map, the packed map with its cone ratios), and starts the GL program on it with `LP_NUM_THREADS` threads
//! (default 2; our frame gets a pool of as many). Per view it reads back one llvmpipe frame
//! per technique and prints the PSNR between it and ours, and between ours and the float
//! renderer's frame of the same technique (the precision the 8-bit formats give up; both as
//! the relief lab measures PSNR: sRGB-encoded, peak 1, over the pixels showing the wall), then, after one warm-up frame each, times REPS rounds (default 9) in which every
//! technique's frame is drawn by us and then by llvmpipe, alternating: ours by wall time
//! around `render_fused`, llvmpipe's by wall time around clear + draw + `glFinish`. It
//! prints the medians and our time over llvmpipe's, with `lscpu`'s model and the load.
//! Techniques (default all): basic, normal, parallax, pom:32, steep:32, relief:16:6, adaptive
//! (the thesis's adaptive POM, 4 to 32 layers), cone-newton:64:3:25, cone:16:5:binary (relaxed
//! cone stepping; the GL program's nine).

use renderlab_core::color::linear_to_srgb;
use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::stats::median;
use renderlab_core::{Camera, Scene, SceneObject};
use renderlab_relief::fused::{render_fused, FusedFrame, Texture8};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::maps::packed::{DEPTH_STEP, RATIO_STEP};
use renderlab_relief::march::{cone_newton, cone_step};
use renderlab_relief::{FrameInput, KernelChoice, ReliefMaterial, Technique};
use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

/// The benchmark's views, in degrees from the wall's normal.
const ANGLES: [f32; 4] = [0.0, 45.0, 60.0, 80.0];
/// The GL program's techniques, in its numbering.
const TECHS: [&str; 9] = [
    "basic",
    "normal",
    "parallax",
    "pom:32",
    "steep:32",
    "relief:16:6",
    "adaptive",
    "cone-newton:64:3:25",
    "cone:16:5:binary",
];

fn put_u32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put_f32(out: &mut Vec<u8>, v: f32) {
    out.extend_from_slice(&v.to_le_bytes());
}

/// A texture's levels: count, then per level its size and texels.
fn put_texture(out: &mut Vec<u8>, t: &Texture8) {
    put_u32(out, t.level_count() as u32);
    let (mut w, mut h) = t.size();
    let mut offset = 0;
    for _ in 0..t.level_count() {
        put_u32(out, w);
        put_u32(out, h);
        let n = (w * h) as usize;
        for &texel in &t.texels()[offset..offset + n] {
            put_u32(out, texel);
        }
        offset += n;
        (w, h) = ((w / 2).max(1), (h / 2).max(1));
    }
    assert_eq!(offset, t.texels().len(), "the levels halve down to one texel");
}

/// The GL program's input file (its layout is documented in `llvmpipe_bench.c`).
fn frame_file(scene: &Scene, mat: &ReliefMaterial, cams: &[Camera]) -> Vec<u8> {
    let mut out = b"RLLPIPE3".to_vec();
    put_u32(&mut out, cams[0].width);
    put_u32(&mut out, cams[0].height);
    for c in scene.background.to_array() {
        put_f32(&mut out, c);
    }
    for c in scene.light.to_light.to_array() {
        put_f32(&mut out, c);
    }
    let l = scene.lighting;
    for v in [l.ambient, l.specular_exponent, l.specular_strength, mat.height_scale] {
        put_f32(&mut out, v);
    }
    let mesh = &scene.objects[0].mesh;
    put_u32(&mut out, mesh.vertices.len() as u32);
    for v in &mesh.vertices {
        for c in v.position.to_array().into_iter().chain(v.normal.to_array()).chain(v.uv.to_array()) {
            put_f32(&mut out, c);
        }
        for c in v.tangent.to_array() {
            put_f32(&mut out, c);
        }
    }
    put_u32(&mut out, mesh.triangles.len() as u32 * 3);
    for &i in mesh.triangles.iter().flatten() {
        put_u32(&mut out, i);
    }
    put_u32(&mut out, cams.len() as u32);
    for cam in cams {
        for c in cam.view_projection().to_cols_array() {
            put_f32(&mut out, c);
        }
        for c in cam.position.to_array() {
            put_f32(&mut out, c);
        }
    }
    put_texture(&mut out, &mat.textures8.albedo);
    put_texture(&mut out, &mat.textures8.normal);
    let p = &mat.packed;
    put_u32(&mut out, p.width());
    put_u32(&mut out, p.height());
    for y in 0..p.height() {
        for x in 0..p.width() {
            out.extend_from_slice(&p.texel(x, y).0.to_le_bytes());
        }
    }
    let c = &mat.complexity;
    put_u32(&mut out, c.width());
    put_u32(&mut out, c.height());
    for &v in c.pixels() {
        put_f32(&mut out, v);
    }
    // The packed map on its padded grid (depth and cone ratio codes), and the constants the
    // cone marches read.
    put_u32(&mut out, p.stride() as u32);
    put_u32(&mut out, p.height() + 1);
    for &t in p.texels() {
        put_u32(&mut out, t);
    }
    for v in [
        DEPTH_STEP,
        RATIO_STEP,
        cone_newton::MIN_STEP,
        cone_newton::MIN_SLOPE,
        cone_newton::MAX_EPS,
        cone_newton::JUMP,
        cone_step::TAIL as f32,
    ] {
        put_f32(&mut out, v);
    }
    out
}

/// The running GL program.
struct Gl {
    child: std::process::Child,
    input: std::process::ChildStdin,
    output: BufReader<std::process::ChildStdout>,
}

impl Gl {
    fn ask(&mut self, line: &str) -> String {
        writeln!(self.input, "{line}").expect("the GL program reads its commands");
        self.input.flush().expect("the GL program reads its commands");
        let mut answer = String::new();
        self.output.read_line(&mut answer).expect("the GL program answers");
        assert!(!answer.is_empty(), "the GL program ended (see its messages above)");
        answer
    }

    /// Wall ms of one frame of technique `t` at view `v`.
    fn time(&mut self, t: usize, v: usize) -> f64 {
        let a = self.ask(&format!("time {t} {v} 1"));
        a.split_whitespace().nth(1).and_then(|s| s.parse().ok()).expect("a time")
    }

    /// One frame's RGBA8 pixels (row 0 at the top).
    fn pixels(&mut self, t: usize, v: usize, path: &Path) -> Vec<u32> {
        assert_eq!(self.ask(&format!("dump {t} {v} {}", path.display())).trim(), "ok");
        let bytes = std::fs::read(path).expect("the dump");
        bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
    }
}

/// The sRGB-encoded channels of an RGBA8 pixel, in [0, 1].
fn srgb(p: u32) -> [f64; 3] {
    [p & 0xff, p >> 8 & 0xff, p >> 16 & 0xff].map(|c| c as f64 / 255.0)
}

/// PSNR (dB) between `ours` and `other` (sRGB-encoded channels in [0, 1] per pixel) over the
/// pixels `mask` marks, as the relief lab measures: peak 1, every channel.
fn psnr(ours: &[u32], other: impl Fn(usize) -> [f64; 3], mask: &[bool]) -> f64 {
    let (mut se, mut n) = (0.0, 0usize);
    for (i, &p) in ours.iter().enumerate().filter(|&(i, _)| mask[i]) {
        let (a, b) = (srgb(p), other(i));
        se += (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>();
        n += 3;
    }
    10.0 * (n as f64 / se).log10()
}

/// `lscpu`'s model name and the load average, for the record.
fn machine() -> (String, String) {
    let lscpu = Command::new("lscpu").output().map(|o| String::from_utf8_lossy(&o.stdout).into_owned());
    let model = lscpu
        .unwrap_or_default()
        .lines()
        .find(|l| l.starts_with("Model name:"))
        .map(|l| l["Model name:".len()..].trim().to_string())
        .unwrap_or_default();
    let load = std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default();
    (model, load)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let program = args.first().expect("usage: llvmpipe GL_PROGRAM [REPS] [TECH…]").clone();
    let reps: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(9);
    let techs: Vec<usize> = if args.len() > 2 {
        args[2..]
            .iter()
            .map(|a| {
                TECHS.iter().position(|t| t == a).expect(
                    "basic, normal, parallax, pom:32, steep:32, relief:16:6, adaptive, cone-newton:64:3:25 or cone:16:5:binary",
                )
            })
            .collect()
    } else {
        (0..TECHS.len()).collect()
    };
    let threads: usize = std::env::var("LP_NUM_THREADS").ok().and_then(|s| s.parse().ok()).unwrap_or(2);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool");

    let m = renderlab_texture::materials::material("bricks", 1024).expect("built-in material");
    // With the relaxed cone map, which cone-newton reads (the other techniques read only the depths).
    let mat = ReliefMaterial::new(&m, &ComplexityParams::default(), true);
    let scene =
        Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![m]);
    let cams: Vec<Camera> =
        ANGLES.iter().map(|&a| Camera::orbit(BRICKS_WALL_CENTRE, 6.0, a, 1280, 800)).collect();
    let dir = Path::new("out/llvmpipe");
    std::fs::create_dir_all(dir).expect("out/llvmpipe");
    let input = dir.join("frame.bin");
    std::fs::write(&input, frame_file(&scene, &mat, &cams)).expect("writes the frame's inputs");

    let mut child = Command::new(&program)
        .arg(&input)
        .env("LP_NUM_THREADS", threads.to_string())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("starts the GL program");
    let (input_pipe, output) = (child.stdin.take().unwrap(), child.stdout.take().unwrap());
    let mut gl = Gl { child, input: input_pipe, output: BufReader::new(output) };

    let mats = [mat];
    let kernels: Vec<_> = TECHS
        .iter()
        .map(|n| {
            let t = Technique::parse(n).expect("technique");
            (t, t.kernel(KernelChoice::Auto).expect("kernel"))
        })
        .collect();
    let (model, load) = machine();
    println!("CPU: {model}; {threads} threads each; load at start {load}; {reps} rounds, medians");
    println!(
        "| technique (CPU kernel) | angle | ours ms | llvmpipe ms | ours / llvmpipe | PSNR ours vs llvmpipe dB | PSNR ours vs float frame dB |"
    );
    println!("|---|---|---|---|---|---|---|");
    let mut frame = FusedFrame::default();
    let render = |t: usize, v: usize, frame: &mut FusedFrame| {
        let (tech, kernel) = kernels[t];
        pool.install(|| render_fused(&scene, &cams[v], &mats, tech, kernel, true, frame)).expect("renders");
    };
    for (v, angle) in ANGLES.iter().enumerate() {
        let mut psnrs = Vec::new();
        let g = renderlab_raster::rasterize(&scene, &cams[v]);
        let input = FrameInput::new(cams[v].width, cams[v].height, g.pixels());
        for &t in &techs {
            render(t, v, &mut frame);
            let theirs = gl.pixels(t, v, &dir.join(format!("gl_{t}_{v}.rgba")));
            let (tech, kernel) = kernels[t];
            let float = renderlab_relief::render::render(
                input,
                &mats,
                tech,
                kernel,
                scene.lighting,
                scene.background,
                false,
            )
            .expect("renders");
            let mask = float.mask.pixels();
            let vs_gl = psnr(&frame.pixels, |i| srgb(theirs[i]), mask);
            let vs_float = psnr(
                &frame.pixels,
                |i| float.image.pixels()[i].to_array().map(|c| linear_to_srgb(c) as f64),
                mask,
            );
            psnrs.push((vs_gl, vs_float));
            gl.time(t, v);
        }
        let mut ours = vec![Vec::new(); techs.len()];
        let mut theirs = vec![Vec::new(); techs.len()];
        for _ in 0..reps {
            for (i, &t) in techs.iter().enumerate() {
                let start = Instant::now();
                render(t, v, &mut frame);
                ours[i].push(start.elapsed().as_secs_f64() * 1e3);
                theirs[i].push(gl.time(t, v));
            }
        }
        for (i, &t) in techs.iter().enumerate() {
            let (a, b) = (median(&mut ours[i]), median(&mut theirs[i]));
            println!(
                "| `{}` ({}) | {}° | {a:.1} | {b:.1} | {:.2} | {:.1} | {:.1} |",
                TECHS[t],
                kernels[t].1.name(),
                angle,
                a / b,
                psnrs[i].0,
                psnrs[i].1
            );
        }
    }
    let (_, load) = machine();
    println!("load at end {load}");
    let _ = writeln!(gl.input, "quit");
    drop(gl.input);
    let _ = gl.child.wait();
}
