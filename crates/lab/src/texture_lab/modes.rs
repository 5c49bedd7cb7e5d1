//! The perspective-mapping evaluation modes: each mode fills the texture coordinates of every
//! surface pixel, timed side by side on one thread, with its coordinate error against the
//! direct mode and the exact mapping, and the image error it causes under trilinear filtering.

use super::config::TextureBenchConfig;
use super::record::TextureRecord;
use crate::error::Result;
use crate::metrics::compare;
use glam::{DVec2, Vec2};
use renderlab_core::Image;
use renderlab_texture::filter::{Filter, Trilinear};
use renderlab_texture::mapping::modes::{eval_spans, Mode, Span};
use renderlab_texture::mapping::{NoOps, Projective};
use renderlab_texture::reference::Reference;
use renderlab_texture::scene::{Surface, TestScene};
use std::time::Instant;

/// Per-row spans of surface pixels (first to last hit; the surfaces are convex per row).
fn spans(surface: &Surface) -> Vec<Span> {
    (0..surface.pixels.height())
        .map(|y| {
            let row = surface.pixels.row(y);
            match (row.iter().position(|p| p.hit), row.iter().rposition(|p| p.hit)) {
                (Some(a), Some(b)) => Span { x0: a as u32, len: (b - a + 1) as u32 },
                _ => Span { x0: 0, len: 0 },
            }
        })
        .collect()
}

/// The mapping modes' records and (incremental / direct, incremental-rows / direct).
pub type ModeResults = (Vec<TextureRecord>, Option<(f64, f64)>);

/// Times every mapping mode producing the texture coordinates of the scene's surface pixels
/// (one thread, modes interleaved repetition by repetition), measures their coordinate error
/// against the direct mode and the exact mapping, and the image error with trilinear
/// filtering. Returns the records and (incremental / direct, incremental-rows / direct).
pub fn measure_modes(
    scene: &TestScene,
    surface: &Surface,
    refs: &[Reference],
    mask: &Image<bool>,
    cfg: &TextureBenchConfig,
) -> Result<ModeResults> {
    let (w, h) = (scene.width as usize, scene.height as usize);
    let s = scene.uv_scale;
    let centre = Projective { m: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, 1.0]] };
    let scale = Projective { m: [[s, 0.0, 0.0], [0.0, s, 0.0], [0.0, 0.0, 1.0]] };
    let coeffs = centre.then(&scene.view.to_uv).then(&scale).coeffs();
    let sp = spans(surface);
    let count: usize = sp.iter().map(|s| s.len as usize).sum();
    if count == 0 {
        return Ok((Vec::new(), None));
    }
    let tex_size = scene.texture.size();
    // Enough frames per repetition for ~1 ms of work at ~0.5 ns per pixel, and many short
    // repetitions (at least 21): a burst of load on the shared machine then spoils a few
    // repetitions of every mode rather than most of one mode's.
    let inner = (2_000_000 / count).clamp(1, 1000);
    let reps = (cfg.reps as usize * 4).max(21);
    let modes = &cfg.modes;
    let mut bufs: Vec<Vec<Vec2>> = modes.iter().map(|_| vec![Vec2::ZERO; w * h]).collect();
    let mut samples: Vec<Vec<f64>> = modes.iter().map(|_| Vec::new()).collect();
    for rep in 0..reps + cfg.warmup as usize {
        for (k, &mode) in modes.iter().enumerate() {
            let t0 = Instant::now();
            for _ in 0..inner {
                eval_spans(&coeffs, mode, 0, &sp, w, std::hint::black_box(&mut bufs[k]), &mut NoOps)?;
            }
            let ns = t0.elapsed().as_nanos() as f64 / (inner * count) as f64;
            if rep >= cfg.warmup as usize {
                samples[k].push(ns);
            }
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        let n = v.len();
        if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        }
    };
    let direct_idx = modes.iter().position(|&m| m == Mode::Direct);
    let mut recs = Vec::new();
    let mut times = Vec::new();
    for (k, &mode) in modes.iter().enumerate() {
        let ns = median(&mut samples[k]);
        times.push(ns);
        let uv = &bufs[k];
        // Coordinate errors over the surface pixels, in texels.
        let (mut dmax, mut dsum, mut emax, mut n) = (0.0f64, 0.0f64, 0.0f64, 0u64);
        for y in 0..h {
            for x in 0..w {
                if !surface.pixels.get(x as u32, y as u32).hit {
                    continue;
                }
                let i = y * w + x;
                if let Some(d) = direct_idx {
                    let e = ((uv[i] - bufs[d][i]) * tex_size).length() as f64;
                    let e = if e.is_finite() { e } else { f64::INFINITY };
                    dmax = dmax.max(e);
                    dsum += e;
                }
                if let Some(fp) = scene.view.footprint(x as f64 + 0.5, y as f64 + 0.5) {
                    let exact: DVec2 = fp.uv * s;
                    let e = ((uv[i].as_dvec2() - exact) * tex_size.as_dvec2()).length();
                    emax = emax.max(if e.is_finite() { e } else { f64::INFINITY });
                }
                n += 1;
            }
        }
        // The image with these coordinates (exact Jacobians), trilinear.
        let tex = &scene.texture;
        let img = Image::from_fn_par(scene.width, scene.height, |x, y| {
            let p = surface.pixels.get(x, y);
            if p.hit {
                let c = uv[y as usize * w + x as usize];
                Trilinear.sample(tex, c, p.duv_dx, p.duv_dy, &mut renderlab_core::counter::NoCount).truncate()
            } else {
                scene.background
            }
        });
        let (fetches, fn_) = scene.count_fetches(surface, &Trilinear);
        for r in refs {
            let m = compare(&img, &r.image, Some(mask)).metrics;
            recs.push(TextureRecord {
                scene: scene.kind.name(),
                kind: "mapping",
                method: mode.name(),
                reference: r.filter.family(),
                ns_per_pixel: ns,
                fetches_per_pixel: fetches as f64 / fn_.max(1) as f64,
                psnr_db: m.psnr_db,
                ssim: m.ssim,
                flip: m.flip,
                uv_err_vs_direct_max_texels: if direct_idx.is_some() { dmax } else { f64::NAN },
                uv_err_vs_direct_mean_texels: if direct_idx.is_some() {
                    dsum / n.max(1) as f64
                } else {
                    f64::NAN
                },
                uv_err_vs_exact_max_texels: emax,
                pixels: n,
            });
        }
    }
    let t = |m: Mode| modes.iter().position(|&x| x == m).map(|i| times[i]);
    let ratio = match (t(Mode::Direct), t(Mode::Incremental), t(Mode::IncrementalRows)) {
        (Some(d), Some(i), Some(r)) => Some((i / d, r / d)),
        (Some(d), Some(i), None) => Some((i / d, f64::NAN)),
        _ => None,
    };
    Ok((recs, ratio))
}
