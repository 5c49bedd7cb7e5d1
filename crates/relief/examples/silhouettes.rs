//! The silhouette study's table (`renderlab_relief::study::silhouettes`): the built-in bricks on a
//! sphere, a cylinder side-on and oblique and a finite patch at a grazing view, at three
//! height scales; POM (the flat outline) and the silhouette technique against the exact
//! reference's coverage, with UV error, frame time (median of `RL_REPEATS`, default 5, scalar
//! kernel) and fetches per pixel. Images of every frame go to `/tmp/silhouettes/` (or
//! `RL_OUT`).
//!
//! `cargo run -p renderlab-relief --example silhouettes [-- WIDTH HEIGHT TEXTURE]` (defaults
//! 320 240 256).

use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::study::silhouettes::{cases, silhouette_study, StudyConfig};
use renderlab_relief::{ReliefMaterial, Technique};
use std::path::PathBuf;

fn arg(i: usize, default: u32) -> u32 {
    std::env::args().nth(i).map_or(default, |a| a.parse().expect("a whole number"))
}

fn main() {
    let (w, h, size) = (arg(1, 320), arg(2, 240), arg(3, 256));
    let repeats = std::env::var("RL_REPEATS").map_or(5, |r| r.parse().expect("RL_REPEATS: a count"));
    let out = PathBuf::from(std::env::var("RL_OUT").unwrap_or_else(|_| "/tmp/silhouettes".into()));
    std::fs::create_dir_all(&out).expect("output directory");
    let bricks = renderlab_texture::materials::material("bricks", size).expect("built-in bricks");
    let material = ReliefMaterial::new(&bricks, &ComplexityParams::default(), false);
    let methods = ["pom:32", "silhouette:16", "silhouette:32", "silhouette:64"]
        .iter()
        .map(|m| Technique::parse(m).expect("a technique"))
        .collect();
    let config = StudyConfig { methods, height_scales: vec![0.02, 0.05, 0.1], repeats };
    let rows = silhouette_study(&cases(w, h), &material, &config, |name, image| {
        renderlab_core::io::save_color(out.join(name), image).expect("image written");
    })
    .expect("the study runs");
    println!("{w}x{h}, bricks {size}², scalar kernel, median of {repeats} frames");
    println!(
        "| case | scale | method | band px | false covered | false empty (beside) | UV err (texels) | depth err (texels) | ms | fetches/px |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {} | {} ({:.1}%) | {} ({:.1}%) ({}) | {:.3} | {:.3} | {:.2} | {:.1} |",
            r.case,
            r.height_scale,
            r.method,
            r.band,
            r.false_covered,
            r.percent_of_band(r.false_covered),
            r.false_empty,
            r.percent_of_band(r.false_empty),
            r.beside,
            r.uv_error_texels,
            r.depth_error_texels,
            r.frame_ms,
            r.fetches_per_pixel
        );
    }
    println!("images: {}", out.display());
}
