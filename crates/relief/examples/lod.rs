//! The level-of-detail study ([`renderlab_relief::study::lod`]) with its tables printed and
//! its images written to `/tmp/lod/`: each technique's first frame, the reference's, a heat
//! map of each layered technique's layer counts (dark blue 0 to dark red at the largest count
//! of any technique) and one of its colour error against the reference (0 to 16 8-bit levels,
//! the mean of the channels, as displayed).
//!
//! `cargo run --release -p renderlab-relief --example lod -- [WIDTHxHEIGHT] [FRAMES] [tile=UNITS] [TECH...]`
//! (defaults: 640x360, 16 frames, the floor tile of the thesis room, the study's technique
//! list).

use renderlab_core::color::heat_color;
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_core::Image;
use renderlab_relief::study::lod::bands::{displayed, BANDS, BAND_NAMES};
use renderlab_relief::study::lod::{lod_study, LodConfig, LodStudy};
use renderlab_relief::Technique;
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut config = LodConfig::default();
    let mut techniques = Vec::new();
    for arg in std::env::args().skip(1) {
        if let Some((w, h)) = arg.split_once('x').and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        {
            (config.width, config.height) = (w, h);
        } else if let Some(tile) = arg.strip_prefix("tile=") {
            config.tile = tile.parse()?;
        } else if let Ok(n) = arg.parse() {
            config.frames = n;
        } else {
            techniques.push(Technique::parse(&arg)?);
        }
    }
    if !techniques.is_empty() {
        config.techniques = techniques;
    }
    let started = std::time::Instant::now();
    let study = lod_study(&config)?;
    print_tables(&study);
    println!("(study ran {:.1} s)", started.elapsed().as_secs_f64());
    save_images(&study, Path::new("/tmp/lod"))
}

fn print_tables(s: &LodStudy) {
    let c = &s.config;
    println!(
        "floor '{}' {}², tile {} units, {}x{}, walk of {} frames at {} units/frame, scalar kernel, medians of {}",
        c.material, c.texture_size, c.tile, c.width, c.height, c.frames, c.step, c.repeats
    );
    print!("\nband pixels (first frame):");
    for (name, n) in BAND_NAMES.iter().zip(s.band_pixels) {
        print!("  {name} {n}");
    }
    println!();
    let header = |what: &str| {
        print!("\n{what:<28}");
        for name in BAND_NAMES {
            print!("{name:>9}");
        }
        println!("{:>9}", "all");
    };
    type Get = fn(&renderlab_relief::study::lod::BandResult) -> f64;
    let tables: [(&str, Get, usize); 6] = [
        ("UV error (texels)", |b| b.uv_error, 3),
        ("UV error (pixels)", |b| b.uv_error_px, 3),
        ("colour error (8-bit levels)", |b| b.colour_error, 3),
        ("fetches per pixel", |b| b.fetches, 1),
        ("band trace time (ms)", |b| b.trace_ms, 2),
        ("flicker (8-bit levels)", |b| b.flicker, 3),
    ];
    for (what, get, digits) in tables {
        header(what);
        for r in &s.results {
            print!("{:<28}", r.technique.name());
            for b in &r.bands {
                print!("{:>9.*}", digits, get(b));
            }
            println!("{:>9.*}", digits, get(&r.all));
        }
    }
    header("band share of trace time");
    for r in &s.results {
        print!("{:<28}", r.technique.name());
        for b in &r.bands {
            print!("{:>8.1}%", 100.0 * b.trace_ms / r.all.trace_ms.max(1e-12));
        }
        println!();
    }
    header("change |I_t - I_t-1|");
    print!("{:<28}", "reference");
    for v in s.reference_change.0 {
        print!("{v:>9.3}");
    }
    println!("{:>9.3}", s.reference_change.1);
    for r in &s.results {
        print!("{:<28}", r.technique.name());
        for b in &r.bands {
            print!("{:>9.3}", b.change);
        }
        println!("{:>9.3}", r.all.change);
    }
    println!("\n{:<28}{:>12}{:>12}", "whole frame", "median ms", "fetches/px");
    for r in &s.results {
        println!("{:<28}{:>12.2}{:>12.2}", r.technique.name(), r.frame_ms, r.all.fetches);
    }
    debug_assert_eq!(BANDS, BAND_NAMES.len());
}

/// The heat colour of `t` in [0, 1] as 8-bit sRGB.
fn heat8(t: f32) -> [u8; 3] {
    let c = heat_color(t);
    [c.x, c.y, c.z].map(|v| (v * 255.0).round() as u8)
}

fn save_images(s: &LodStudy, dir: &Path) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(dir)?;
    save_color(dir.join("reference.png"), &s.reference.image)?;
    let reference = displayed(&s.reference);
    let most =
        s.results.iter().flat_map(|r| r.first.layers.pixels().iter().copied()).max().unwrap_or(0).max(1);
    for r in &s.results {
        let name = r.technique.name().replace(':', "_");
        save_color(dir.join(format!("{name}.png")), &r.first.image)?;
        let shown = displayed(&r.first);
        let error = Image::from_fn(shown.width(), shown.height(), |x, y| {
            let d = (shown.get(x, y) - reference.get(x, y)).abs().element_sum() / 3.0;
            heat8(d / 16.0)
        });
        save_rgb8(dir.join(format!("{name}-error.png")), &error)?;
        if r.first.layers.pixels().iter().any(|&l| l > 0) {
            let heat = r.first.layers.map(|l| heat8(l as f32 / most as f32));
            save_rgb8(dir.join(format!("{name}-layers.png")), &heat)?;
        }
    }
    println!("images in {} (layer heat maps: 0 to {most} layers)", dir.display());
    Ok(())
}
