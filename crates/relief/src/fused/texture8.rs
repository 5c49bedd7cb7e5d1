//! Textures as a GPU stores them: 8 bits per channel, RGBA in one `u32` (red in the low
//! byte), every mip level in one allocation, with the per-level sizes and offsets in small
//! tables that a vector kernel indexes per lane. Albedo is stored sRGB-encoded and decoded
//! per texel before filtering (an `rgba8unorm-srgb` texture); normals are stored as
//! `(n + 1) / 2` in unorm (an `rgba8unorm` texture) and filtered as stored.
//!
//! Beside the 8-bit codes each texture keeps the values its filter reads, three 10-bit fields
//! in a `u32` (red in the low 10 bits, then green, blue, and 2 zero bits): the code itself for
//! unorm, and for sRGB the square root of the texel's linear light, `s = round(√linear ·
//! 1023)`, computed once when the texture is built (the filter reads `s²`, linear light in
//! units of [`LINEAR_STEP`] = 1/1023², exact in `f32`; the square root spends the bits where
//! sRGB does, in the darks: no code moves by more than a sixth of an 8-bit step, and what
//! that gives up is included in the fused frame's measured precision). Four bytes per texel
//! is what a GPU reads from an `rgba8` texture. That copy is padded: each level has one more
//! column and one more row, copies of its first column and row, so the four texels of a
//! bilinear cell are two pairs of neighbours in memory, `(x, y), (x + 1, y)` and the same one
//! padded row further, whatever the wrap ([`Texture8::wide`]).
//!
//! The levels are the float pyramid's own levels, rounded: the 8-bit path differs from the
//! float one only by that rounding (and the per-texel decode), which the relief lab
//! measures as the PSNR between the two frames.

use glam::Vec4;
use renderlab_core::color::{linear_to_srgb, srgb8_to_linear_table};
use renderlab_texture::Texture;

/// Most levels a [`Texture8`] holds: a 16,384-texel side (renderlab's image limit) has 15.
pub const MAX_LEVELS: usize = 16;

/// How a texture's channels are encoded in their 8 bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// sRGB-encoded colour, decoded to linear light per texel before filtering.
    Srgb,
    /// Signed values in [−1, 1] stored as `(v + 1) / 2` in unorm, filtered as stored.
    SignedUnorm,
}

/// Bits per channel of a [`Texture8::wide`] entry.
pub const WIDE_BITS: u32 = 10;

/// The largest value of a [`Texture8::wide`] channel (its mask).
pub const WIDE_MAX: u32 = (1 << WIDE_BITS) - 1;

/// The linear light of one unit of a squared [`Texture8::wide`] channel of an sRGB texture:
/// `1 / 1023²`.
pub const LINEAR_STEP: f32 = 1.0 / (WIDE_MAX * WIDE_MAX) as f32;

/// An 8-bit RGBA texture with its mip pyramid (repeat wrap).
#[derive(Clone, Debug)]
pub struct Texture8 {
    texels: Vec<u32>,
    /// The filter's values, padded ([`Texture8::wide`]).
    wide: Vec<u32>,
    /// Start of each level in `wide` (the last real level repeated to [`MAX_LEVELS`]).
    pub(crate) wide_offsets: [i32; MAX_LEVELS],
    encoding: Encoding,
    levels: usize,
    /// Start of each level in `texels` (the last real level repeated to [`MAX_LEVELS`]).
    pub(crate) offsets: [i32; MAX_LEVELS],
    /// Width of each level, as an integer and as a float.
    pub(crate) widths: [i32; MAX_LEVELS],
    /// Height of each level.
    pub(crate) heights: [i32; MAX_LEVELS],
    /// Width of each level as `f32`.
    pub(crate) widths_f: [f32; MAX_LEVELS],
    /// Height of each level as `f32`.
    pub(crate) heights_f: [f32; MAX_LEVELS],
}

/// One channel value in [0, 1] (sRGB-encoded or unorm) rounded to its 8-bit code.
#[inline]
fn code(v: f32) -> u32 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    (v * 255.0 + 0.5) as u32
}

impl Texture8 {
    /// Rounds every level of `tex` to 8 bits with `encoding`. The float texture's levels hold
    /// linear colour ([`Encoding::Srgb`]) or signed values ([`Encoding::SignedUnorm`]);
    /// alpha is stored as 255. At most [`MAX_LEVELS`] levels are kept (the image limits
    /// allow no more).
    pub fn from_texture(tex: &Texture, encoding: Encoding) -> Self {
        let levels = tex.level_count().min(MAX_LEVELS);
        let enc = |v: f32| match encoding {
            Encoding::Srgb => code(linear_to_srgb(v)),
            Encoding::SignedUnorm => code(v * 0.5 + 0.5),
        };
        let pack = |c: Vec4| enc(c.x) | enc(c.y) << 8 | enc(c.z) << 16 | 0xff00_0000;
        let mut out = Self {
            texels: Vec::new(),
            wide: Vec::new(),
            wide_offsets: [0; MAX_LEVELS],
            encoding,
            levels,
            offsets: [0; MAX_LEVELS],
            widths: [1; MAX_LEVELS],
            heights: [1; MAX_LEVELS],
            widths_f: [1.0; MAX_LEVELS],
            heights_f: [1.0; MAX_LEVELS],
        };
        for k in 0..MAX_LEVELS {
            let level = k.min(levels - 1);
            let img = tex.level(level);
            let (w, h) = img.size();
            if k == level {
                out.offsets[k] = out.texels.len() as i32;
                out.texels.extend(img.pixels().iter().map(|&c| pack(c)));
            } else {
                out.offsets[k] = out.offsets[level];
            }
            out.widths[k] = w as i32;
            out.heights[k] = h as i32;
            out.widths_f[k] = w as f32;
            out.heights_f[k] = h as f32;
        }
        let decode = srgb8_to_linear_table();
        let channel = |t: u32, c: u32| {
            let code = t >> (8 * c) & 0xff;
            match encoding {
                Encoding::Srgb => (decode[code as usize].sqrt() * WIDE_MAX as f32).round() as u32,
                Encoding::SignedUnorm => code,
            }
        };
        let wide = |t: u32| channel(t, 0) | channel(t, 1) << WIDE_BITS | channel(t, 2) << (2 * WIDE_BITS);
        for k in 0..MAX_LEVELS {
            if k < levels {
                out.wide_offsets[k] = out.wide.len() as i32;
                let (w, h, o) = (out.widths[k] as usize, out.heights[k] as usize, out.offsets[k] as usize);
                for y in 0..=h {
                    let row = &out.texels[o + (y % h) * w..][..w];
                    out.wide.extend(row.iter().chain(&row[..1]).map(|&t| wide(t)));
                }
            } else {
                out.wide_offsets[k] = out.wide_offsets[levels - 1];
            }
        }
        out
    }

    /// The values the filter reads, [`WIDE_BITS`] bits per channel (red in the low bits, then
    /// green, blue and 0): for sRGB, the square root of each texel's linear light (the square
    /// of a channel counts units of [`LINEAR_STEP`]); for unorm, the code. Level `k` (`w × h` texels) starts at
    /// `wide_offsets[k]` and holds `(w + 1) × (h + 1)` entries, row-major: texel `(x, y)` at
    /// `y · (w + 1) + x`, column `w` repeating column 0 and row `h` repeating row 0.
    pub fn wide(&self) -> &[u32] {
        &self.wide
    }

    /// Every level's texels, level 0 first.
    pub fn texels(&self) -> &[u32] {
        &self.texels
    }

    /// Number of mip levels.
    pub fn level_count(&self) -> usize {
        self.levels
    }

    /// Level 0's size in texels.
    pub fn size(&self) -> (u32, u32) {
        (self.widths[0] as u32, self.heights[0] as u32)
    }

    /// Whether `other` has the same level sizes and offsets (then one level of detail and
    /// one set of texel addresses serve both).
    pub fn same_shape(&self, other: &Texture8) -> bool {
        self.levels == other.levels
            && self.offsets == other.offsets
            && self.widths == other.widths
            && self.heights == other.heights
    }

    /// How the channels are encoded.
    pub fn encoding(&self) -> Encoding {
        self.encoding
    }

    /// Bytes of texel storage (a quarter of the float pyramid's).
    pub fn bytes(&self) -> usize {
        self.texels.len() * 4
    }
}

/// A material's textures in the fused frame's 8-bit formats.
#[derive(Clone, Debug)]
pub struct Textures8 {
    /// Albedo, sRGB-encoded (`rgba8unorm-srgb`).
    pub albedo: Texture8,
    /// Tangent-space normals, unorm-encoded (`rgba8unorm`).
    pub normal: Texture8,
}

impl Textures8 {
    /// Rounds `albedo` (linear colour) and `normal` (signed) pyramids to 8 bits.
    pub fn new(albedo: &Texture, normal: &Texture) -> Self {
        let albedo = Texture8::from_texture(albedo, Encoding::Srgb);
        let normal = Texture8::from_texture(normal, Encoding::SignedUnorm);
        Self { albedo, normal }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderlab_core::Image;
    use renderlab_texture::Wrap;

    #[test]
    fn levels_and_tables_follow_the_float_pyramid() {
        let img = Image::from_fn(37, 10, |x, y| glam::Vec3::new(x as f32 / 36.0, y as f32 / 9.0, 0.5));
        let tex = Texture::from_rgb(&img, Wrap::Repeat);
        let t8 = Texture8::from_texture(&tex, Encoding::Srgb);
        assert_eq!(t8.level_count(), tex.level_count());
        let mut offset = 0;
        for k in 0..t8.level_count() {
            let (w, h) = tex.level(k).size();
            assert_eq!((t8.widths[k], t8.heights[k]), (w as i32, h as i32));
            assert_eq!(t8.offsets[k], offset);
            offset += (w * h) as i32;
        }
        assert_eq!(t8.texels().len(), offset as usize);
        // Levels past the last repeat it, so a lane's clamped level index stays valid.
        let last = t8.level_count() - 1;
        assert_eq!(t8.offsets[MAX_LEVELS - 1], t8.offsets[last]);
        // Codes: linear 0.5 is sRGB 0.7354 → 188; alpha 255.
        assert_eq!(t8.texels()[0] >> 16 & 0xff, 188);
        assert_eq!(t8.texels()[0] >> 24, 255);
        // The linear copy: code 188 decodes to 0.50289, whose root 0.70915 is 725 of 1023;
        // code 0 to 0; no alpha.
        assert_eq!(t8.wide()[0] >> 20, 725);
        assert_eq!(t8.wide()[0] & WIDE_MAX, 0);
        let mut padded = 0;
        for k in 0..t8.level_count() {
            let (w, h) = (t8.widths[k], t8.heights[k]);
            assert_eq!(t8.wide_offsets[k], padded);
            for y in 0..=h {
                for x in 0..=w {
                    let c = t8.texels()[(t8.offsets[k] + (y % h) * w + x % w) as usize];
                    let l = t8.wide()[(padded + y * (w + 1) + x) as usize];
                    for ch in 0..3 {
                        let exact = srgb8_to_linear_table()[(c >> (8 * ch) & 0xff) as usize];
                        let s = (l >> (WIDE_BITS * ch) & WIDE_MAX) as f32;
                        // The root rounded to the nearest unit: within half a unit.
                        assert!((s - exact.sqrt() * 1023.0).abs() <= 0.5 + 1e-3, "{s} vs {exact}");
                        // Its square counts units of LINEAR_STEP, within a sixth of an 8-bit
                        // step once sRGB-encoded (the format's stated bound).
                        let back = renderlab_core::color::linear_to_srgb(s * s * LINEAR_STEP) * 255.0;
                        let code = (c >> (8 * ch) & 0xff) as f32;
                        assert!((back - code).abs() <= 1.0 / 6.0, "code {code} back as {back}");
                    }
                }
            }
            padded += (w + 1) * (h + 1);
        }
        assert_eq!(t8.wide().len(), padded as usize);
        assert_eq!(t8.wide_offsets[MAX_LEVELS - 1], t8.wide_offsets[last]);
    }

    #[test]
    fn signed_values_map_to_unorm() {
        let img =
            Image::from_fn(
                2,
                1,
                |x, _| if x == 0 { glam::Vec3::new(-1.0, 0.0, 1.0) } else { glam::Vec3::NAN },
            );
        let t8 = Texture8::from_texture(&Texture::from_rgb(&img, Wrap::Repeat), Encoding::SignedUnorm);
        assert_eq!(t8.texels()[0] & 0xff_ffff, 128 << 8 | 255 << 16);
        assert_eq!(t8.texels()[1] & 0xff_ffff, 0, "NaN stores as 0, not garbage");
        // Unorm textures are filtered as stored: the wide copy holds the codes.
        assert_eq!(t8.wide()[0], 128 << WIDE_BITS | 255 << (2 * WIDE_BITS));
        assert_eq!(t8.wide()[1], 0);
        assert_eq!(t8.wide()[2], t8.wide()[0], "column 0 repeated");
    }
}
