//! Renders a sample lab report from synthetic images, to see every part of the toolkit at
//! work: metrics, heat maps with legends, a scatter and a bar chart, tables, CSV/JSON and the
//! index page.
//!
//! ```text
//! cargo run --release -p renderlab-lab --example report_demo -- /tmp/labdemo
//! ```

use glam::Vec3;
use renderlab_core::color::srgb_to_linear;
use renderlab_core::io::{save_color, save_rgb8};
use renderlab_core::Image;
use renderlab_lab::heatmap::{heat_image, percentile, with_legend};
use renderlab_lab::metrics::{compare, per_pixel_abs_error};
use renderlab_lab::plot::{bar_svg, scatter_svg, BarSeries, Series};
use renderlab_lab::report::{format_number, write_page, Template};
use renderlab_lab::results::{write_csv, write_json};
use renderlab_lab::suite::{write_index, IndexCard};
use renderlab_lab::timing::measure;
use serde::Serialize;

const W: u32 = 480;
const H: u32 = 300;

/// A procedural "reference": bricks with mortar and a soft light gradient, in linear light.
fn reference(x: u32, y: u32) -> Vec3 {
    let (u, v) = (x as f32 / 48.0, y as f32 / 24.0);
    let row = v.floor();
    let u = u + 0.5 * (row % 2.0);
    let (fu, fv) = (u.fract(), v.fract());
    let mortar = fu < 0.06 || fv < 0.1;
    let shade = 0.55 + 0.45 * (x as f32 / W as f32);
    let base = if mortar {
        Vec3::new(0.75, 0.74, 0.70)
    } else {
        let k = ((u.floor() * 12.9898 + row * 78.233).sin() * 43_758.547).fract().abs();
        Vec3::new(0.62, 0.28, 0.2) * (0.8 + 0.4 * k)
    };
    (base * shade).map(srgb_to_linear)
}

/// A degraded rendering: blur of radius `r` plus noise of amplitude `noise`.
fn technique(r: i64, noise: f32, seed: u32) -> Image<Vec3> {
    let reference = Image::from_fn(W, H, reference);
    Image::from_fn_par(W, H, |x, y| {
        let mut acc = Vec3::ZERO;
        let mut n = 0.0;
        for dy in -r..=r {
            for dx in -r..=r {
                acc += reference.get_clamped(x as i64 + dx, y as i64 + dy);
                n += 1.0;
            }
        }
        let h = (x.wrapping_mul(73_856_093) ^ y.wrapping_mul(19_349_663) ^ seed) % 1000;
        acc / n + Vec3::splat(noise * (h as f32 / 1000.0 - 0.5))
    })
}

/// A technique: its name and its variants as (steps, blur radius, noise amplitude).
type TechniqueSpec = (&'static str, &'static [(u32, i64, f32)]);

/// One CSV/JSON row: flat fields (a CSV record cannot hold a nested `Timing`).
#[derive(Serialize)]
struct Row {
    technique: String,
    steps: u32,
    median_ms: f64,
    min_ms: f64,
    max_ms: f64,
    psnr_db: f64,
    ssim: f64,
    flip: f64,
}

/// The demo page's template: the lab's shared macros, the demo's own prose.
const TEMPLATE: Template = Template { name: "report_demo.html", source: include_str!("report_demo.html") };

/// Everything the demo page shows.
#[derive(Serialize)]
struct Page {
    scatter: String,
    bars: String,
    measurements: Vec<Vec<String>>,
    images: Vec<(String, String)>,
    flip_max: String,
    error_maps: Vec<(String, String)>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("labdemo"));
    let lab_dir = out.join("demo");
    std::fs::create_dir_all(lab_dir.join("img"))?;

    let reference = Image::from_fn(W, H, reference);
    save_color(lab_dir.join("img/reference.png"), &reference)?;

    // A visibility mask: the top-right corner is "sky" and does not count.
    let mask = Image::from_fn(W, H, |x, y| !(x > 380 && y < 60));

    let techniques: [TechniqueSpec; 3] = [
        ("box blur", &[(4, 3, 0.0), (8, 2, 0.0), (16, 1, 0.0)]),
        ("noisy", &[(4, 0, 0.3), (8, 0, 0.15), (16, 0, 0.05)]),
        ("blur + noise", &[(4, 2, 0.2), (8, 1, 0.1), (16, 0, 0.02)]),
    ];
    let mut rows = Vec::new();
    let mut grid = vec![("img/reference.png".to_string(), "Reference".to_string())];
    let mut flip_maps = Vec::new();
    for (ti, (name, variants)) in techniques.iter().enumerate() {
        for &(steps, r, noise) in variants.iter() {
            let (timing, img) = measure(1, 3, || technique(r, noise, ti as u32 * 7 + steps));
            let c = compare(&img, &reference, Some(&mask));
            let base = format!("{}_{steps}", name.replace([' ', '+'], ""));
            save_color(lab_dir.join(format!("img/{base}.png")), &img)?;
            if steps == 8 {
                grid.push((format!("img/{base}.png"), format!("{name}, {steps} steps")));
                flip_maps.push((base.clone(), name.to_string(), c.flip_map.clone(), img));
            }
            rows.push(Row {
                technique: name.to_string(),
                steps,
                median_ms: timing.median_ms,
                min_ms: timing.min_ms,
                max_ms: timing.max_ms,
                psnr_db: c.metrics.psnr_db,
                ssim: c.metrics.ssim,
                flip: c.metrics.flip,
            });
        }
    }
    // One shared colour scale for all FLIP maps.
    let flip_max = flip_maps
        .iter()
        .map(|(_, _, m, _)| percentile(m, Some(&mask), 0.99))
        .fold(0.0f32, f32::max)
        .max(1e-3);
    let mut heat_grid = Vec::new();
    for (base, name, map, img) in &flip_maps {
        let heat = with_legend(&heat_image(map, flip_max, Some(&mask)), flip_max, "FLIP");
        save_rgb8(lab_dir.join(format!("img/{base}_flip.png")), &heat)?;
        heat_grid.push((format!("img/{base}_flip.png"), format!("{name}: FLIP")));
        let abs = per_pixel_abs_error(img, &reference);
        let heat = with_legend(&heat_image(&abs, 0.25, Some(&mask)), 0.25, "abs error");
        save_rgb8(lab_dir.join(format!("img/{base}_abs.png")), &heat)?;
        heat_grid.push((format!("img/{base}_abs.png"), format!("{name}: |error|")));
    }
    write_csv(lab_dir.join("results.csv"), &rows)?;
    write_json(lab_dir.join("results.json"), &rows)?;

    let series: Vec<Series> = techniques
        .iter()
        .map(|(name, _)| {
            let rs: Vec<&Row> = rows.iter().filter(|r| r.technique == *name).collect();
            Series::new(*name, rs.iter().map(|r| (r.steps as f64, r.flip)).collect())
                .with_labels(rs.iter().map(|r| format!("{} steps", r.steps)).collect())
                .connected()
        })
        .collect();

    let page = Page {
        scatter: scatter_svg(
            "FLIP against steps",
            "steps per pixel",
            "mean FLIP (masked)",
            &series,
            true,
            false,
        ),
        bars: bar_svg(
            "PSNR by step count",
            "PSNR (dB)",
            &["4 steps", "8 steps", "16 steps"],
            &techniques
                .iter()
                .map(|(name, _)| {
                    BarSeries::new(
                        *name,
                        rows.iter().filter(|r| r.technique == *name).map(|r| r.psnr_db).collect(),
                    )
                })
                .collect::<Vec<_>>(),
        ),
        measurements: rows
            .iter()
            .map(|r| {
                vec![
                    r.technique.clone(),
                    r.steps.to_string(),
                    format_number(r.median_ms, 2),
                    format_number(r.psnr_db, 2),
                    format_number(r.ssim, 4),
                    format_number(r.flip, 4),
                ]
            })
            .chain(std::iter::once(vec![
                "reference".into(),
                "–".into(),
                "–".into(),
                format_number(f64::INFINITY, 2),
                format_number(1.0, 4),
                format_number(0.0, 4),
            ]))
            .collect(),
        images: grid,
        flip_max: format!("{flip_max:.3}"),
        error_maps: heat_grid,
    };
    write_page(&lab_dir.join("index.html"), TEMPLATE, "Demo lab: synthetic degradations", &page)?;
    let card = |title: &str, link: &str, summary: &str| IndexCard {
        title: title.into(),
        link: link.into(),
        summary: summary.into(),
        image: None,
    };
    let index = write_index(
        &out,
        &[
            card(
                "Demo lab",
                "demo/index.html",
                "Synthetic blur and noise against a brick reference: every toolkit part.",
            ),
            card(
                "Relief lab",
                "relief/index.html",
                "Parallax, POM, relief and cone-step mapping against exact ray casting.",
            ),
        ],
    )?;
    println!("wrote {} and {}", index.display(), lab_dir.join("index.html").display());
    Ok(())
}
