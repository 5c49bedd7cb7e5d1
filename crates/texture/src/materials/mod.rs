//! Built-in procedural materials named after the thesis's textures: `bricks`,
//! `sand_rocks`, `bark_willow` and `brick_pavement` (the thesis does not state the sources of
//! its texture files, so renderlab synthesises stand-ins with the same character).
//!
//! The catalogue: one file per material, each with its texel function and one
//! [`MaterialInfo`] in its `Entry` implementation, and one line per material in
//! the `registry!` below, from which [`MATERIALS`], [`MATERIAL_NAMES`] and the lookup by name
//! come. What the materials share is below them (`texel.rs`, `noise.rs`, `descriptor.rs`); no
//! material file imports this one.
//!
//! Every material is a pure function of the texel coordinates and fixed seeds, so the same
//! name and size always give bit-identical maps, whatever the thread count. Every feature is
//! periodic with period 1 in texture space (noise lattices wrapped modulo whole cells, brick
//! and paver layouts whose period divides the tile), so the maps tile seamlessly under wrap
//! addressing at any size ≥ 16, power of two or not.

#![warn(missing_docs)]

mod descriptor;
mod noise;
mod texel;

pub use descriptor::MaterialInfo;

use descriptor::{Entry, Sampler};
use glam::Vec3;
use renderlab_core::image::{check_dimensions, Image};
use renderlab_core::{CoreError, Material, Result};
use texel::{Detail, Texel};

/// Declares the catalogue: each material's module, [`MATERIALS`], and the lookup from a name
/// to its texel function.
macro_rules! registry {
    ($($module:ident::$ty:ident,)*) => {
        $(mod $module;)*

        /// Every built-in material, in the order the thesis's scene uses them.
        pub const MATERIALS: &[MaterialInfo] = &[$(<$module::$ty as Entry>::INFO,)*];

        /// The texel function and relief depth scale of the built-in material `name`.
        fn sampler(name: &str) -> Result<(Sampler, f32)> {
            $(
                if name == <$module::$ty as Entry>::INFO.name {
                    return Ok((<$module::$ty as Entry>::sampler(), <$module::$ty as Entry>::INFO.height_scale));
                }
            )*
            Err(CoreError::UnknownName { kind: "material", name: name.to_string(), known: MATERIAL_NAMES.join(", ") })
        }
    };
}

registry! {
    bricks::Bricks,
    sand_rocks::SandRocks,
    bark_willow::BarkWillow,
    brick_pavement::BrickPavement,
}

/// Names of the built-in materials, in the order the thesis's scene uses them.
pub const MATERIAL_NAMES: [&str; MATERIALS.len()] = {
    let mut names = [""; MATERIALS.len()];
    let mut i = 0;
    while i < names.len() {
        names[i] = MATERIALS[i].name;
        i += 1;
    }
    names
};

/// The material the binary builds when none is named: the thesis's benchmark wall.
pub const DEFAULT_MATERIAL: &str = "bricks";

/// Default texture size of the built-in materials.
pub const DEFAULT_SIZE: u32 = 1024;

/// Builds the built-in material `name` at `size × size` texels.
///
/// The albedo is in linear light; the height map spans [0, 1] (1 = top of the relief, 0 =
/// the deepest mortar joint or furrow) and the normal map is derived from it.
pub fn material(name: &str, size: u32) -> Result<Material> {
    check_dimensions("--texture-size", size as u64, size as u64)?;
    if size < 16 {
        return Err(CoreError::param("--texture-size", size, "must be at least 16"));
    }
    let (texel, scale) = sampler(name)?;
    let detail = Detail { size, texel: 1.0 / size as f32, max_cells: (size / 2).max(1) };
    let (albedo, height) = render(&detail, &*texel);
    Material::from_maps(name, albedo, height, None, scale)
}

/// Evaluates `texel` at every texel centre `((x + ½)/size, (y + ½)/size)` in parallel and
/// splits the result into an albedo and a height map normalised to exactly [0, 1].
fn render(detail: &Detail, texel: impl Fn(f32, f32, &Detail) -> Texel + Sync) -> (Image<Vec3>, Image<f32>) {
    let (size, inv) = (detail.size, detail.texel);
    let texels =
        Image::from_fn_par(size, size, |x, y| texel((x as f32 + 0.5) * inv, (y as f32 + 0.5) * inv, detail));
    let albedo = texels.map(|t| t.albedo.max(Vec3::ZERO));
    let height = normalize(texels.map(|t| t.height));
    (albedo, height)
}

/// Stretches `img` linearly to span [0, 1] (min and max are exact, so this is deterministic).
fn normalize(img: Image<f32>) -> Image<f32> {
    let (lo, hi) = img.pixels().iter().fold((f32::MAX, f32::MIN), |(lo, hi), &h| (lo.min(h), hi.max(h)));
    if hi - lo < 1e-6 {
        return img.map(|_| 0.5);
    }
    let s = 1.0 / (hi - lo);
    img.map(|h| ((h - lo) * s).clamp(0.0, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mean absolute difference between neighbouring columns `x` and `x + 1` (wrapping).
    fn column_step(h: &Image<f32>, x: u32) -> f32 {
        let (w, ht) = h.size();
        let s: f32 = (0..ht).map(|y| (h.get(x, y) - h.get((x + 1) % w, y)).abs()).sum();
        s / ht as f32
    }

    /// Mean absolute difference between neighbouring rows `y` and `y + 1` (wrapping).
    fn row_step(h: &Image<f32>, y: u32) -> f32 {
        let (w, ht) = h.size();
        let s: f32 = (0..w).map(|x| (h.get(x, y) - h.get(x, (y + 1) % ht)).abs()).sum();
        s / w as f32
    }

    /// FNV-1a over the bits of a material's albedo, height and normal maps and its scale.
    fn checksum(m: &Material) -> u64 {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        let mut add = |v: f32| {
            for b in v.to_bits().to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
        };
        m.albedo.pixels().iter().for_each(|c| c.to_array().into_iter().for_each(&mut add));
        m.height.pixels().iter().for_each(|&v| add(v));
        m.normal.pixels().iter().for_each(|n| n.to_array().into_iter().for_each(&mut add));
        add(m.height_scale);
        h
    }

    #[test]
    fn maps_are_bit_identical_to_the_recorded_ones() {
        // Recorded from the materials as they were built in `renderlab-core`, before their
        // noise moved onto `renderlab-noise`: any change to a map's bits is a change to every
        // relief image of the report.
        let recorded = [
            ("bricks", 16, 0xdb03_5fc4_4db9_2b62u64),
            ("sand_rocks", 16, 0xef2c_2bfe_6903_849c),
            ("bark_willow", 16, 0x0e10_ec8f_6125_cd87),
            ("brick_pavement", 16, 0xe6a1_1b30_28e5_9263),
            ("bricks", 48, 0xe44b_2a93_6ebb_55c9),
            ("sand_rocks", 48, 0x6bc1_8c55_5cca_fb86),
            ("bark_willow", 48, 0xa052_3402_daae_17e7),
            ("brick_pavement", 48, 0x8df8_2ccd_1289_cdae),
            ("bricks", 100, 0xdb4e_2786_352d_0f7d),
            ("sand_rocks", 100, 0xd280_713c_b1dc_c306),
            ("bark_willow", 100, 0x74ca_409c_4fbe_37c2),
            ("brick_pavement", 100, 0x017a_5ee9_5a81_e8eb),
            ("bricks", 256, 0x7314_c9d8_8406_30f5),
            ("sand_rocks", 256, 0x606a_305a_2784_f515),
            ("bark_willow", 256, 0xa6cf_697c_1802_eeff),
            ("brick_pavement", 256, 0x69bc_6ec5_bc5f_8052),
        ];
        for (name, size, sum) in recorded {
            assert_eq!(checksum(&material(name, size).unwrap()), sum, "{name} at {size}²");
        }
    }

    #[test]
    fn every_entry_is_named_once_described_and_builds_with_its_depth() {
        assert_eq!(MATERIAL_NAMES, ["bricks", "sand_rocks", "bark_willow", "brick_pavement"]);
        assert!(MATERIAL_NAMES.contains(&DEFAULT_MATERIAL));
        for (i, info) in MATERIALS.iter().enumerate() {
            assert!(MATERIALS[..i].iter().all(|m| m.name != info.name), "{} twice", info.name);
            assert!(!info.description.is_empty(), "{}", info.name);
            let m = material(info.name, 16).unwrap();
            assert_eq!(m.height_scale, info.height_scale, "{}", info.name);
            assert_eq!(m.size(), (16, 16));
        }
    }

    #[test]
    fn unknown_name_is_an_error() {
        let e = material("marble", 64).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("marble") && msg.contains("bricks"), "{msg}");
    }

    #[test]
    fn too_small_or_zero_size_is_an_error() {
        assert!(material("bricks", 8).is_err());
        assert!(material("bricks", 0).is_err());
        assert!(material("bricks", 100_000).is_err());
    }

    #[test]
    fn materials_are_deterministic() {
        for name in MATERIAL_NAMES {
            let a = material(name, 96).unwrap();
            let b = material(name, 96).unwrap();
            assert_eq!(a.albedo, b.albedo, "{name}");
            assert_eq!(a.height, b.height, "{name}");
            assert_eq!(a.normal, b.normal, "{name}");
        }
    }

    #[test]
    fn deterministic_across_thread_counts() {
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let three = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        for name in MATERIAL_NAMES {
            let a = one.install(|| material(name, 80).unwrap());
            let b = three.install(|| material(name, 80).unwrap());
            assert_eq!(a.albedo, b.albedo, "{name}");
            assert_eq!(a.height, b.height, "{name}");
        }
    }

    #[test]
    fn materials_tile_seamlessly() {
        for name in MATERIAL_NAMES {
            for size in [100u32, 256] {
                let m = material(name, size).unwrap();
                let h = &m.height;
                // The seam (last column next to the first) must look like any other pair of
                // neighbouring columns: compare with the worst interior pair.
                let seam_x = column_step(h, size - 1);
                let worst_x = (0..size - 1).map(|x| column_step(h, x)).fold(0.0f32, f32::max);
                let seam_y = row_step(h, size - 1);
                let worst_y = (0..size - 1).map(|y| row_step(h, y)).fold(0.0f32, f32::max);
                assert!(
                    seam_x <= 1.5 * worst_x && seam_y <= 1.5 * worst_y,
                    "{name} {size}: seam {seam_x}/{seam_y} vs interior {worst_x}/{worst_y}"
                );
                // Pixel by pixel, the seam jump stays within the largest interior jump.
                let max_jump = |a: (u32, u32), b: (u32, u32)| (h.get(a.0, a.1) - h.get(b.0, b.1)).abs();
                let interior = (0..size)
                    .flat_map(|y| (0..size - 1).map(move |x| (x, y)))
                    .map(|(x, y)| max_jump((x, y), (x + 1, y)))
                    .fold(0.0f32, f32::max);
                let seam = (0..size).map(|y| max_jump((size - 1, y), (0, y))).fold(0.0f32, f32::max);
                assert!(seam <= interior + 1e-6, "{name} {size}: {seam} vs {interior}");
                // The same for the albedo (luminance).
                let lum = |x: u32, y: u32| renderlab_core::color::luminance(m.albedo.get(x, y));
                let seam_c: f32 = (0..size).map(|y| (lum(size - 1, y) - lum(0, y)).abs()).sum();
                let mid_c: f32 = (0..size).map(|y| (lum(size / 2 - 1, y) - lum(size / 2, y)).abs()).sum();
                assert!(seam_c <= 3.0 * mid_c + 1e-3, "{name} {size}: {seam_c} vs {mid_c}");
            }
        }
    }

    #[test]
    fn texel_functions_have_period_one() {
        // The exact statement of tileability: shifting u or v by a whole tile gives the same
        // texel (up to float rounding; rare cell-boundary ties are allowed to differ).
        for name in MATERIAL_NAMES {
            let (texel, _) = sampler(name).unwrap();
            let d = Detail { size: 512, texel: 1.0 / 512.0, max_cells: 256 };
            let mut bad = 0;
            let n = 2000;
            for i in 0..n {
                let u = noise::unit(noise::hash(i * 2 + 1));
                let v = noise::unit(noise::hash(i * 2 + 2));
                let a = texel(u, v, &d);
                for (du, dv) in [(1.0, 0.0), (0.0, 1.0), (-1.0, -1.0)] {
                    let b = texel(u + du, v + dv, &d);
                    let dh = (a.height - b.height).abs();
                    let dc = (a.albedo - b.albedo).abs().max_element();
                    if dh > 2e-3 || dc > 2e-3 {
                        bad += 1;
                    }
                }
            }
            assert!(bad * 200 < 3 * n, "{name}: {bad} of {} samples differ", 3 * n);
        }
    }

    #[test]
    fn heights_use_the_whole_range() {
        for name in MATERIAL_NAMES {
            let m = material(name, 128).unwrap();
            let px = m.height.pixels();
            let lo = px.iter().copied().fold(f32::MAX, f32::min);
            let hi = px.iter().copied().fold(f32::MIN, f32::max);
            assert!(hi - lo >= 0.7, "{name}: height spans only {lo}..{hi}");
            assert!(px.iter().all(|h| (0.0..=1.0).contains(h)), "{name}");
            // Not a binary mask: a good share of texels lies strictly between the extremes.
            let mid = px.iter().filter(|&&h| h > 0.2 && h < 0.8).count();
            assert!(mid * 20 > px.len(), "{name}: heights are nearly binary");
            let scale = m.height_scale;
            assert!((0.03..=0.08).contains(&scale), "{name}: scale {scale}");
        }
    }

    #[test]
    fn odd_sizes_work() {
        for name in MATERIAL_NAMES {
            for size in [16u32, 100, 1000] {
                let m = material(name, size).unwrap();
                assert_eq!(m.size(), (size, size));
                assert!(m
                    .albedo
                    .pixels()
                    .iter()
                    .all(|c| c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0));
                assert!(m.normal.pixels().iter().all(|n| n.is_finite()));
            }
        }
    }

    #[test]
    fn materials_are_distinct() {
        let maps: Vec<_> = MATERIAL_NAMES.iter().map(|n| material(n, 64).unwrap()).collect();
        for i in 0..maps.len() {
            for j in i + 1..maps.len() {
                assert_ne!(maps[i].height, maps[j].height);
                let a = mean(&maps[i].albedo);
                let b = mean(&maps[j].albedo);
                assert!((a - b).length() > 1e-3 || maps[i].height != maps[j].height);
            }
        }
    }

    fn mean(img: &Image<Vec3>) -> Vec3 {
        img.pixels().iter().copied().sum::<Vec3>() / img.pixels().len() as f32
    }

    /// Writes every material to `$RENDERLAB_MATERIAL_DIR` (e.g. `/tmp/materials`) as PNGs for
    /// a visual check: `RENDERLAB_MATERIAL_DIR=/tmp/materials cargo test -p renderlab-texture
    /// --release save_material_pngs -- --ignored`. Also reports the build time.
    #[test]
    #[ignore = "writes PNGs for inspection"]
    fn save_material_pngs() {
        let dir = std::env::var("RENDERLAB_MATERIAL_DIR").unwrap_or("/tmp/materials".into());
        let size: u32 = std::env::var("RENDERLAB_MATERIAL_SIZE")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(DEFAULT_SIZE);
        std::fs::create_dir_all(&dir).unwrap();
        // CPU seconds used by this process so far (Linux), to report the build cost
        // independently of other load on the machine.
        let cpu = || -> Option<f64> {
            let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
            let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
            let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
            Some(ticks / 100.0)
        };
        for name in MATERIAL_NAMES {
            let (t, c) = (std::time::Instant::now(), cpu());
            let m = material(name, size).unwrap();
            let cpu_s = cpu().zip(c).map(|(b, a)| b - a).unwrap_or(f64::NAN);
            println!("{name}: {:.3} s at {size}² ({cpu_s:.2} CPU s)", t.elapsed().as_secs_f64());
            renderlab_core::io::save_color(format!("{dir}/{name}_albedo.png"), &m.albedo).unwrap();
            renderlab_core::io::save_gray(format!("{dir}/{name}_height.png"), &m.height, false).unwrap();
            // A quick lit preview: albedo × Lambert with a light from the upper left.
            let l = Vec3::new(-0.5, -0.6, 0.62).normalize();
            let lit = Image::from_fn(size, size, |x, y| {
                let n = m.normal.get(x, y);
                m.albedo.get(x, y) * (0.15 + 0.85 * n.dot(l).max(0.0)) * 1.4
            });
            renderlab_core::io::save_color(format!("{dir}/{name}_lit.png"), &lit).unwrap();
            // Two by two tiles of the lit preview, to check the seams by eye.
            let tiled = Image::from_fn(size, size, |x, y| lit.get((2 * x) % size, (2 * y) % size));
            renderlab_core::io::save_color(format!("{dir}/{name}_tiled.png"), &tiled).unwrap();
        }
    }
}
