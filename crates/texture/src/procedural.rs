//! The texture lab's procedural textures: the checker, the zone plate and the bricks albedo of
//! the test scenes, and, for the thesis's quad, a circuit board and an earth-like map.
//!
//! The texturing thesis maps three images onto its quad: a chess board, a circuit-board photo
//! and a map of the earth. Those images are not ours to ship, so the lab makes textures with the
//! same character in code: the circuit has long straight edges at every angle on screen (traces,
//! chip outlines, pins) and small high-contrast detail (pads, holes); the earth map has smooth
//! coastlines and fractal relief at every scale. Both are deterministic per seed, in linear
//! light, and tile seamlessly (the circuit's grid and the earth's noise both wrap), so the
//! scenes can repeat them.

use crate::error::{size_error, SceneError};
use glam::{Vec3, Vec4};
use renderlab_core::Image;
use renderlab_noise::{Fractal, FractalKind, FractalParams, Perlin};

/// Largest side of a procedural texture.
pub const MAX_TEXTURE_SIDE: u32 = 8192;

/// Checks a texture side: `min..=`[`MAX_TEXTURE_SIDE`].
fn check_side(what: &'static str, size: u32, min: u32) -> Result<(), SceneError> {
    if size < min || size > MAX_TEXTURE_SIDE {
        return Err(size_error(what, format!("{size} must lie in {min}..={MAX_TEXTURE_SIDE}")));
    }
    Ok(())
}

/// A checkerboard of `checks × checks` squares, black (0) and white (1) in linear light, on a
/// `size × size` texture. Errors for a size outside 1..=8192 or zero checks.
pub fn checker_texture(size: u32, checks: u32) -> Result<Image<Vec4>, SceneError> {
    check_side("checker size", size, 1)?;
    if checks == 0 || checks > size {
        return Err(size_error("checks", format!("{checks} must lie in 1..={size}")));
    }
    Ok(Image::from_fn_par(size, size, |x, y| {
        let cx = (x as u64 * checks as u64 / size as u64) as u32;
        let cy = (y as u64 * checks as u64 / size as u64) as u32;
        Vec4::splat(((cx + cy) % 2) as f32).with_w(1.0)
    }))
}

/// A zone plate `½ + ½·cos(k·r²)` (r in texels from the centre) inside the inscribed disc and
/// ½ outside. `k` puts the ring frequency `k·r/π` at just under ½ cycle per texel (Nyquist) on
/// the disc's edge, where the cosine is 0, so the texture is continuous and tiles seamlessly.
pub fn zone_plate_texture(size: u32) -> Result<Image<Vec4>, SceneError> {
    check_side("zone plate size", size, 1)?;
    let r_max = size as f64 / 2.0;
    // k·R² = π·(⌊R²/(2R)·…⌋) chosen as (m + ½)·π with m the largest keeping k·R/π ≤ ½.
    let m = (r_max / 2.0 - 0.5).floor().max(0.0);
    let k = (m + 0.5) * std::f64::consts::PI / (r_max * r_max);
    Ok(Image::from_fn_par(size, size, |x, y| {
        let dx = x as f64 + 0.5 - r_max;
        let dy = y as f64 + 0.5 - r_max;
        let r2 = dx * dx + dy * dy;
        let v = if r2 < r_max * r_max { 0.5 + 0.5 * (k * r2).cos() } else { 0.5 };
        Vec4::splat(v as f32).with_w(1.0)
    }))
}

/// The bricks material's albedo ([`crate::materials`]) as an RGBA texture.
pub fn bricks_texture(size: u32) -> Result<Image<Vec4>, SceneError> {
    check_side("bricks size", size, 1)?;
    let m = crate::materials::material("bricks", size.max(8))
        .map_err(|e| size_error("bricks size", e.to_string()))?;
    Ok(m.albedo.map(|c| c.extend(1.0)))
}

/// A 32-bit integer hash (lowbias32) of a cell and a channel, mixed with the seed.
#[inline]
fn hash(seed: u32, x: u32, y: u32, channel: u32) -> u32 {
    let mut h =
        seed ^ x.wrapping_mul(0x9E37_79B9) ^ y.wrapping_mul(0x85EB_CA6B) ^ channel.wrapping_mul(0xC2B2_AE35);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    h
}

/// The hash as a number in [0, 1).
#[inline]
fn unit(seed: u32, x: u32, y: u32, channel: u32) -> f32 {
    (hash(seed, x, y, channel) >> 8) as f32 / (1u32 << 24) as f32
}

/// Cells per side of the circuit's routing grid.
pub const CIRCUIT_CELLS: u32 = 32;
/// Cells per side of one chip site (chips sit on a coarser grid of these).
const CHIP_SITE: u32 = 8;

const MASK: Vec3 = Vec3::new(0.012, 0.10, 0.030);
const TRACE: Vec3 = Vec3::new(0.035, 0.30, 0.060);
const GOLD: Vec3 = Vec3::new(0.62, 0.42, 0.10);
const HOLE: Vec3 = Vec3::new(0.01, 0.01, 0.01);
const CHIP: Vec3 = Vec3::new(0.018, 0.018, 0.02);
const PIN: Vec3 = Vec3::new(0.55, 0.55, 0.52);
const SILK: Vec3 = Vec3::new(0.80, 0.80, 0.75);

/// A circuit board: a green solder mask over a grid of copper traces routed between cell
/// centres, gold ring pads where a trace ends, vias where traces branch, and black chips with
/// silver pins. `size` texels per side (64..=8192), [`CIRCUIT_CELLS`] routing cells per side.
pub fn circuit_texture(size: u32, seed: u32) -> Result<Image<Vec4>, SceneError> {
    check_side("circuit size", size, 64)?;
    let n = CIRCUIT_CELLS;
    let cell = size as f32 / n as f32;
    let wrap = |i: i64| i.rem_euclid(n as i64) as u32;
    // Edge (i, j) → (i + 1, j) and (i, j) → (i, j + 1), both wrapping, so the board tiles.
    let east = |i: i64, j: i64| unit(seed, wrap(i), wrap(j), 0) < 0.42;
    let south = |i: i64, j: i64| unit(seed, wrap(i), wrap(j), 1) < 0.38;
    let chip_at = |mi: u32, mj: u32| unit(seed, mi, mj, 7) < 0.45;
    Ok(Image::from_fn_par(size, size, |x, y| {
        let (px, py) = ((x as f32 + 0.5) / cell, (y as f32 + 0.5) / cell);
        let (ci, cj) = (px.floor() as i64, py.floor() as i64);
        let (fx, fy) = (px - ci as f32, py - cj as f32);

        // Chips first: a body on a CHIP_SITE grid covers whatever is routed below it.
        let sites = n / CHIP_SITE;
        let (mi, mj) = (wrap(ci) / CHIP_SITE, wrap(cj) / CHIP_SITE);
        if chip_at(mi % sites, mj % sites) {
            // Cell coordinates within the site.
            let sx = (wrap(ci) % CHIP_SITE) as f32 + fx;
            let sy = (wrap(cj) % CHIP_SITE) as f32 + fy;
            let (x0, x1, y0, y1) = (1.6, 6.4, 2.6, 5.4);
            if (x0..x1).contains(&sx) && (y0..y1).contains(&sy) {
                // A pin-1 dot in silkscreen.
                let d = ((sx - 2.1).powi(2) + (sy - 3.1).powi(2)).sqrt();
                return if d < 0.18 { SILK } else { CHIP }.extend(1.0);
            }
            // Pins: one per cell column along both long sides.
            let on_pin_col = sx > 2.0 && sx < 6.0 && (sx.fract() - 0.5).abs() < 0.16;
            if on_pin_col && ((y0 - 0.55..y0).contains(&sy) || (y1..y1 + 0.55).contains(&sy)) {
                return PIN.extend(1.0);
            }
            // The silkscreen outline around the chip's footprint.
            let outline = |lo: f32, hi: f32, v: f32| (v - lo).abs() < 0.06 || (v - hi).abs() < 0.06;
            if (sx > x0 - 0.3 && sx < x1 + 0.3 && outline(y0 - 0.75, y1 + 0.75, sy))
                || (sy > y0 - 0.75 && sy < y1 + 0.75 && outline(x0 - 0.3, x1 + 0.3, sx))
            {
                return SILK.extend(1.0);
            }
        }

        let e = east(ci, cj);
        let w = east(ci - 1, cj);
        let s = south(ci, cj);
        let nn = south(ci, cj - 1);
        let degree = [e, w, s, nn].iter().filter(|&&b| b).count();
        let half = 0.11;
        let (dx, dy) = (fx - 0.5, fy - 0.5);
        let r = (dx * dx + dy * dy).sqrt();
        if degree == 1 || degree >= 3 {
            // A through-hole pad where a trace ends, a smaller via where traces branch.
            let (outer, hole) = if degree == 1 { (0.30, 0.12) } else { (0.19, 0.08) };
            if r < hole {
                return HOLE.extend(1.0);
            }
            if r < outer {
                return GOLD.extend(1.0);
            }
        }
        let on_trace = (e && fx >= 0.5 && dy.abs() < half)
            || (w && fx <= 0.5 && dy.abs() < half)
            || (s && fy >= 0.5 && dx.abs() < half)
            || (nn && fy <= 0.5 && dx.abs() < half)
            || (degree > 0 && dx.abs() < half && dy.abs() < half);
        let base = if on_trace { TRACE } else { MASK };
        // A faint mottling of the mask, per texel, so that flat areas are not perfectly flat.
        let grain = 0.92 + 0.16 * unit(seed ^ 0x5eed, x, y, 3);
        (base * grain).extend(1.0)
    }))
}

/// An earth-like map: tileable fractal relief (8 octaves of fBm) cut by a sea level into
/// oceans (deeper = darker) and land coloured by height and a second, smoother "moisture"
/// field (deserts, grassland, forest, rock, snow), hill-shaded from the north-west.
/// `size` texels per side (16..=8192).
pub fn earth_texture(size: u32, seed: u32) -> Result<Image<Vec4>, SceneError> {
    check_side("earth size", size, 16)?;
    let noise_err = |e: renderlab_noise::NoiseError| size_error("earth noise", e.to_string());
    let relief_params =
        FractalParams::new(8, 3.0, 2.0, 0.5).and_then(|p| p.with_period(&[1, 1])).map_err(noise_err)?;
    let moist_params =
        FractalParams::new(4, 2.0, 2.0, 0.5).and_then(|p| p.with_period(&[1, 1])).map_err(noise_err)?;
    let relief = Fractal::new(Perlin::new(seed), relief_params, FractalKind::Fbm);
    let moisture = Fractal::new(Perlin::new(seed.wrapping_add(17)), moist_params, FractalKind::Fbm);
    let inv = 1.0 / size as f32;
    Ok(Image::from_fn_par(size, size, |x, y| {
        let p = [(x as f32 + 0.5) * inv, (y as f32 + 0.5) * inv];
        let (h, g) = relief.sample_with_derivative(p);
        let m = moisture.sample(p);
        const SEA: f32 = 0.02;
        let c = if h < SEA {
            let depth = ((SEA - h) / 0.5).clamp(0.0, 1.0);
            Vec3::new(0.010, 0.060, 0.22).lerp(Vec3::new(0.002, 0.010, 0.06), depth)
        } else {
            let alt = ((h - SEA) / 0.45).clamp(0.0, 1.0);
            let wet = (0.5 + 1.6 * m).clamp(0.0, 1.0);
            let lowland = Vec3::new(0.42, 0.33, 0.16).lerp(Vec3::new(0.03, 0.16, 0.03), wet);
            let land = if alt < 0.55 {
                lowland.lerp(Vec3::new(0.16, 0.12, 0.07), alt / 0.55)
            } else if alt < 0.8 {
                Vec3::new(0.16, 0.12, 0.07).lerp(Vec3::new(0.25, 0.24, 0.23), (alt - 0.55) / 0.25)
            } else {
                Vec3::new(0.25, 0.24, 0.23).lerp(Vec3::splat(0.85), ((alt - 0.8) / 0.2).min(1.0))
            };
            // Lambert hill shading: light from the north-west, relief exaggerated.
            let n = Vec3::new(-g[0] * 0.02, -g[1] * 0.02, 1.0).normalize();
            let l = Vec3::new(-0.6, -0.6, 0.55).normalize();
            let shade = (0.35 + 0.9 * n.dot(l).max(0.0)).min(1.2);
            // Sand along the coast.
            let beach = (1.0 - (h - SEA) / 0.015).clamp(0.0, 1.0);
            (land * shade).lerp(Vec3::new(0.55, 0.48, 0.30), beach * 0.8)
        };
        c.extend(1.0)
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mean(img: &Image<Vec4>) -> Vec3 {
        img.pixels().iter().map(|p| p.truncate()).sum::<Vec3>() / img.pixels().len() as f32
    }

    #[test]
    fn textures_are_deterministic_finite_and_in_range() {
        for (a, b) in [
            (circuit_texture(128, 3).unwrap(), circuit_texture(128, 3).unwrap()),
            (earth_texture(64, 3).unwrap(), earth_texture(64, 3).unwrap()),
        ] {
            assert_eq!(a.pixels(), b.pixels());
            for p in a.pixels() {
                assert!(p.is_finite() && p.min_element() >= 0.0 && p.max_element() <= 1.0, "{p}");
                assert_eq!(p.w, 1.0);
            }
        }
        assert_ne!(circuit_texture(128, 3).unwrap().pixels(), circuit_texture(128, 4).unwrap().pixels());
        assert_ne!(earth_texture(64, 3).unwrap().pixels(), earth_texture(64, 4).unwrap().pixels());
    }

    #[test]
    fn circuit_has_traces_pads_chips_and_tiles() {
        let size = 256;
        let t = circuit_texture(size, 1).unwrap();
        let count = |c: Vec3| t.pixels().iter().filter(|p| (p.truncate() - c).length() < 1e-6).count();
        let total = (size * size) as f32;
        assert!(count(GOLD) as f32 > 0.01 * total, "pads");
        assert!(count(CHIP) as f32 > 0.02 * total, "chips");
        assert!(count(PIN) > 0, "pins");
        // Traces and mask (with grain) dominate; traces are greener than the mask.
        let green = t.pixels().iter().filter(|p| p.y > 0.2).count() as f32;
        assert!(green > 0.05 * total, "traces: {green}");
        // Tiling: the routing wraps, so the left column continues the right one exactly where a
        // horizontal trace crosses the border (same colour class on both sides).
        let mut crossings = 0;
        for y in 0..size {
            let l = t.get(0, y).truncate();
            let r = t.get(size - 1, y).truncate();
            let class = |c: Vec3| {
                if c.y > 0.2 {
                    1
                } else if (c - GOLD).length() < 1e-6 {
                    2
                } else {
                    0
                }
            };
            if class(l) == 1 && class(r) == 1 {
                crossings += 1;
            }
        }
        assert!(crossings > 0, "some traces cross the tile border");
    }

    #[test]
    fn earth_has_sea_and_land_and_tiles() {
        let size = 128;
        let t = earth_texture(size, 5).unwrap();
        let sea = t.pixels().iter().filter(|p| p.z > p.x * 2.0 && p.z > p.y).count() as f32;
        let frac = sea / (size * size) as f32;
        assert!((0.2..0.8).contains(&frac), "sea fraction {frac}");
        // Seamless: the mean absolute step across the wrap equals a typical interior step.
        let step = |x0: u32, x1: u32| {
            (0..size).map(|y| (t.get(x0, y) - t.get(x1, y)).abs().truncate().length_squared()).sum::<f32>()
        };
        let across = step(size - 1, 0);
        let inside = step(size / 2 - 1, size / 2);
        assert!(across < 4.0 * inside + 1e-3, "wrap step {across} vs interior {inside}");
        let m = mean(&t);
        assert!(m.max_element() < 0.6 && m.min_element() > 0.0, "{m}");
    }

    #[test]
    fn bad_sizes_are_errors() {
        assert!(circuit_texture(0, 1).is_err());
        assert!(circuit_texture(32, 1).is_err());
        assert!(circuit_texture(MAX_TEXTURE_SIDE + 1, 1).is_err());
        assert!(earth_texture(0, 1).is_err());
        assert!(earth_texture(MAX_TEXTURE_SIDE + 1, 1).is_err());
    }
}
