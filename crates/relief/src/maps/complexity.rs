//! The thesis's Sobel complexity map (seed §2.3 and listing §6.1), reproduced step by step
//! with the semantics of the OpenCV and NumPy calls it was written with:
//!
//! 1. 3×3 Sobel derivatives `Gx`, `Gy` (unnormalised kernels, `cv2.Sobel(…, CV_32F, …,
//!    ksize=3)`), borders mirrored without repeating the edge pixel (OpenCV's default
//!    `BORDER_REFLECT_101`: `gfedcb|abcdefgh|gfedcba`);
//! 2. magnitude `sqrt(Gx² + Gy²)`;
//! 3. division by the global maximum and clipping to [0, 1] (a flat map, whose maximum is 0,
//!    gives zeros here where the thesis's script would divide by zero);
//! 4. grey dilation with a 3×3 square repeated `dilation_iterations` times (`cv2.dilate`:
//!    samples outside the image never win the maximum);
//! 5. gamma `C^γ`;
//! 6. quantisation to `N` levels, `round(C / step) · step` with `step = 1/(N−1)` and NumPy's
//!    round-half-to-even.
//!
//! Every step runs in `f32` in the same operation order as the Python code. Checked against
//! OpenCV 4.14 and NumPy 2.4 (golden values in the tests): the Sobel magnitude is
//! bit-identical for images wider than 16 pixels (OpenCV switches to a differently ordered
//! code path for narrower ones, where the last bit may differ), and the quantised map matched
//! on every pixel of every test image at 24 and 10 levels. The one known source of difference
//! is `powf`: NumPy's vectorised `power` can be one ulp off the correctly rounded result used
//! here, which flips a level only at an exact rounding tie (2 pixels of 512² at 256 levels).
//! Saving follows the script's `(C·255).astype(np.uint8)`, i.e. truncation: see
//! [`to_u8_levels`] (and `renderlab_core::io::save_gray`, which does the same).

use rayon::prelude::*;
use renderlab_core::{CoreError, Image};

/// Parameters of the complexity-map generator.
///
/// The defaults are the values the thesis's script actually ran with: the call passes
/// `dilation_iterations=5, num_levels=24` and leaves `gamma` at its default of 0.8. (The
/// Python function's own defaults are 1 iteration and 10 levels, and the prose says γ = 0.9
/// and a "5×5" kernel; see [`ComplexityParams::function_defaults`] and seed §7.3 item 8.)
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ComplexityParams {
    /// How many times the 3×3 dilation is applied (`k` iterations equal one
    /// `(2k+1)×(2k+1)` square dilation); widens high-complexity regions.
    pub dilation_iterations: u32,
    /// Exponent applied after dilation; below 1 it lifts small complexity values.
    pub gamma: f32,
    /// Number of discrete output levels `N`; values become multiples of `1/(N−1)`.
    pub levels: u32,
}

impl Default for ComplexityParams {
    fn default() -> Self {
        Self { dilation_iterations: 5, gamma: 0.8, levels: 24 }
    }
}

/// Largest accepted dilation iteration count (a 129×129 square).
pub const MAX_DILATION_ITERATIONS: u32 = 64;
/// Largest accepted gamma.
pub const MAX_GAMMA: f32 = 10.0;
/// Largest accepted level count (an 8-bit output cannot hold more).
pub const MAX_LEVELS: u32 = 256;

impl ComplexityParams {
    /// The defaults of the thesis's Python function signature (1 iteration, γ 0.8,
    /// 10 levels), which its script overrides; kept so the difference can be measured.
    pub fn function_defaults() -> Self {
        Self { dilation_iterations: 1, gamma: 0.8, levels: 10 }
    }

    /// Checks the parameters; each error names the command-line flag at fault
    /// (`--gamma`, `--levels`, `--dilate`).
    pub fn validate(&self) -> Result<(), CoreError> {
        if !self.gamma.is_finite() || self.gamma <= 0.0 || self.gamma > MAX_GAMMA {
            return Err(CoreError::param(
                "--gamma",
                self.gamma,
                format!("must be a finite number in (0, {MAX_GAMMA}]"),
            ));
        }
        if !(2..=MAX_LEVELS).contains(&self.levels) {
            return Err(CoreError::param("--levels", self.levels, format!("must lie in [2, {MAX_LEVELS}]")));
        }
        if self.dilation_iterations > MAX_DILATION_ITERATIONS {
            return Err(CoreError::param(
                "--dilate",
                self.dilation_iterations,
                format!("must lie in [0, {MAX_DILATION_ITERATIONS}]"),
            ));
        }
        Ok(())
    }

    /// The parameters forced into their valid ranges (a NaN or non-positive gamma becomes 1,
    /// i.e. no gamma), so that [`complexity_map`] never panics on unchecked input.
    fn sanitized(&self) -> Self {
        let gamma = if self.gamma.is_finite() && self.gamma > 0.0 { self.gamma.min(MAX_GAMMA) } else { 1.0 };
        Self {
            dilation_iterations: self.dilation_iterations.min(MAX_DILATION_ITERATIONS),
            gamma,
            levels: self.levels.clamp(2, MAX_LEVELS),
        }
    }
}

/// The complexity map of a height map whose values are already in [0, 1] (the first channel
/// divided by 255, as the thesis's script does).
///
/// Parameters should pass [`ComplexityParams::validate`] first; out-of-range values are
/// clamped into range rather than rejected. Any size works, 1×1 included. Every output value
/// is a multiple of `1/(levels−1)` in [0, 1].
pub fn complexity_map(height: &Image<f32>, params: &ComplexityParams) -> Image<f32> {
    let p = params.sanitized();
    let magnitude = sobel_magnitude(height);
    let normalized = normalize_by_max(&magnitude);
    let mut map = dilate(&normalized, p.dilation_iterations);
    let step = level_step(p.levels);
    let gamma = p.gamma;
    map.pixels_mut().par_chunks_mut(PAR_CHUNK).for_each(|chunk| {
        for v in chunk {
            *v = quantize_with_step(v.powf(gamma), step);
        }
    });
    map
}

/// Pixels per parallel work item for the element-wise steps.
const PAR_CHUNK: usize = 16 * 1024;

/// The per-pixel Sobel gradient magnitude `sqrt(Gx² + Gy²)`, unnormalised, with OpenCV's
/// `BORDER_REFLECT_101` border.
///
/// `Gx` uses the kernel `[−1 0 1; −2 0 2; −1 0 1]` (x grows to the right) and `Gy` its
/// transpose (y grows downward), evaluated separably in OpenCV's order: a horizontal pass
/// (`[−1 0 1]` for `Gx`, `[1 2 1]` for `Gy`), then a vertical pass, each 3-tap smoothing
/// summed as `(a + c) + 2·b`. That order makes the result bit-identical to OpenCV's `f32`
/// filter. Non-finite input values propagate; [`normalize_by_max`] turns them into zeros.
pub fn sobel_magnitude(height: &Image<f32>) -> Image<f32> {
    let (w, h) = (height.width() as usize, height.height() as usize);
    let src = height.pixels();
    // Horizontal pass: the x-difference (for Gx) and the x-smoothing (for Gy) of every row.
    let mut diff = vec![0.0f32; w * h];
    let mut smooth = vec![0.0f32; w * h];
    diff.par_chunks_mut(w).zip(smooth.par_chunks_mut(w)).enumerate().for_each(|(y, (drow, srow))| {
        let row = &src[y * w..(y + 1) * w];
        for x in 0..w {
            let l = row[reflect101(x as isize - 1, w)];
            let c = row[x];
            let r = row[reflect101(x as isize + 1, w)];
            drow[x] = r - l;
            srow[x] = (l + r) + c * 2.0;
        }
    });
    // Vertical pass and magnitude.
    let mut out = vec![0.0f32; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, orow)| {
        let up = reflect101(y as isize - 1, h);
        let down = reflect101(y as isize + 1, h);
        let (d0, d1, d2) =
            (&diff[up * w..(up + 1) * w], &diff[y * w..(y + 1) * w], &diff[down * w..(down + 1) * w]);
        let (s0, s2) = (&smooth[up * w..(up + 1) * w], &smooth[down * w..(down + 1) * w]);
        for x in 0..w {
            let gx = (d0[x] + d2[x]) + d1[x] * 2.0;
            let gy = s2[x] - s0[x];
            orow[x] = (gx * gx + gy * gy).sqrt();
        }
    });
    Image::from_vec(height.width(), height.height(), out).expect("same size as the input")
}

/// OpenCV's `BORDER_REFLECT_101` index mapping for offsets of at most one pixel outside
/// `[0, n)`: `−1 → 1`, `n → n−2`; a one-pixel line maps every index to 0 (OpenCV's special
/// case), and a two-pixel line maps `−1 → 1` and `2 → 0`.
#[inline]
fn reflect101(i: isize, n: usize) -> usize {
    if n == 1 {
        return 0;
    }
    if i < 0 {
        (-i) as usize
    } else if i as usize >= n {
        2 * n - 2 - i as usize
    } else {
        i as usize
    }
}

/// Divides by the global maximum and clips to [0, 1] (`np.clip(G / max G, 0, 1)` in `f32`).
///
/// A map whose maximum is 0 (a flat input) becomes all zeros instead of NaN; NaN pixels and
/// non-finite maxima also give zeros. For any other map the largest value is exactly 1.
pub fn normalize_by_max(map: &Image<f32>) -> Image<f32> {
    let max = map.pixels().par_iter().copied().filter(|v| v.is_finite()).reduce(|| 0.0f32, f32::max);
    let mut out = map.clone();
    out.pixels_mut().par_chunks_mut(PAR_CHUNK).for_each(|chunk| {
        for v in chunk {
            let c = if max > 0.0 { *v / max } else { 0.0 };
            *v = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
        }
    });
    out
}

/// Grey dilation (a maximum filter) with a 3×3 square applied `iterations` times, as
/// `cv2.dilate(map, np.ones((3, 3)), iterations=k)` does.
///
/// Pixels outside the image are ignored (OpenCV's default dilation border never wins the
/// maximum), so `k` iterations equal one `(2k+1)×(2k+1)` square clipped to the image. It is
/// computed that way, separably, with the van Herk/Gil–Werman running maximum: the cost per
/// pixel does not depend on `k`. Zero iterations return a copy.
pub fn dilate(map: &Image<f32>, iterations: u32) -> Image<f32> {
    if iterations == 0 {
        return map.clone();
    }
    let r = iterations as usize;
    let (w, h) = (map.width() as usize, map.height() as usize);
    let rows = max_filter_rows(map.pixels(), w, h, r);
    let cols = max_filter_rows(&transpose(&rows, w, h), h, w, r);
    let data = transpose(&cols, h, w);
    Image::from_vec(map.width(), map.height(), data).expect("same size as the input")
}

/// Maximum over `[x − r, x + r] ∩ [0, w)` along every row of a `w × h` buffer.
fn max_filter_rows(src: &[f32], w: usize, h: usize, r: usize) -> Vec<f32> {
    let mut out = vec![0.0f32; w * h];
    out.par_chunks_mut(w).enumerate().for_each_init(Vec::new, |scratch, (y, orow)| {
        running_max(&src[y * w..(y + 1) * w], r, orow, scratch);
    });
    // A 1-high image still counts as having rows; nothing else to do.
    debug_assert_eq!(out.len(), w * h);
    out
}

/// Van Herk/Gil–Werman running maximum of window `2r+1` centred on each sample; samples
/// beyond the ends count as −∞. `scratch` is reused between rows.
fn running_max(line: &[f32], r: usize, out: &mut [f32], scratch: &mut Vec<f32>) {
    let n = line.len();
    let k = 2 * r + 1;
    let len = n + 2 * r;
    scratch.clear();
    scratch.resize(3 * len, f32::NEG_INFINITY);
    let (padded, rest) = scratch.split_at_mut(len);
    let (prefix, suffix) = rest.split_at_mut(len);
    padded[r..r + n].copy_from_slice(line);
    // Prefix maxima within blocks of k, and suffix maxima within the same blocks.
    for j in 0..len {
        prefix[j] = if j % k == 0 { padded[j] } else { prefix[j - 1].max(padded[j]) };
    }
    for j in (0..len).rev() {
        suffix[j] = if j % k == k - 1 || j == len - 1 { padded[j] } else { suffix[j + 1].max(padded[j]) };
    }
    // Window [i, i + k − 1] of the padded line is centred on sample i of the original.
    for (i, o) in out.iter_mut().enumerate() {
        *o = suffix[i].max(prefix[i + k - 1]);
    }
}

/// Transposes a row-major `w × h` buffer into a row-major `h × w` one, in cache-sized tiles.
fn transpose(src: &[f32], w: usize, h: usize) -> Vec<f32> {
    const TILE: usize = 32;
    let mut out = vec![0.0f32; w * h];
    // Output rows are source columns; each task fills TILE output rows.
    out.par_chunks_mut(h * TILE).enumerate().for_each(|(band, chunk)| {
        let x0 = band * TILE;
        let rows = chunk.len() / h;
        for y0 in (0..h).step_by(TILE) {
            let y1 = (y0 + TILE).min(h);
            for dx in 0..rows {
                let x = x0 + dx;
                let orow = &mut chunk[dx * h..(dx + 1) * h];
                for y in y0..y1 {
                    orow[y] = src[y * w + x];
                }
            }
        }
    });
    out
}

/// The quantisation step `1/(N−1)` as the script computes it: a Python (double) division
/// that NumPy then applies to a `float32` array, i.e. rounded to `f32`.
#[inline]
pub fn level_step(levels: u32) -> f32 {
    (1.0f64 / (levels.clamp(2, MAX_LEVELS) - 1) as f64) as f32
}

/// Quantises one value to `levels` levels exactly as `np.round(c / step) * step` does in
/// `float32`: round half to even, so 0.5 and 2.5 steps go down and 1.5 goes up.
#[inline]
pub fn quantize(c: f32, levels: u32) -> f32 {
    quantize_with_step(c, level_step(levels))
}

#[inline]
fn quantize_with_step(c: f32, step: f32) -> f32 {
    (c / step).round_ties_even() * step
}

/// The 8-bit image the thesis's script writes: each value `v` becomes `floor(v·255)`
/// computed in `f32` (`(C * 255).astype(np.uint8)`); NaN becomes 0 and values are clamped
/// to [0, 1] first. With the script's 24 levels this yields 0, 11, 22, …, 243, 255.
pub fn to_u8_levels(map: &Image<f32>) -> Image<u8> {
    map.map(|v| {
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        (v * 255.0) as u8
    })
}

/// A complexity map stored as one byte per texel, an index into the table of its distinct
/// values: the same values, bit for bit, in a quarter of the memory. The quantised maps the
/// thesis's script makes hold at most `N` (24 by default) distinct values, so they always fit;
/// the vector kernels read it where a map of `f32` would miss the caches far more often
/// (adaptive POM's layer counts look a texel up for every pixel).
#[derive(Clone, Debug)]
pub struct ComplexityCodes {
    width: u32,
    height: u32,
    /// One code per texel, row-major, and three bytes of padding so that a 32-bit read at
    /// any texel stays inside.
    codes: Vec<u8>,
    /// Each code's value; unused codes hold 0.
    values: Box<[f32; 256]>,
}

impl ComplexityCodes {
    /// The codes of `map`, or `None` when it holds more than 256 distinct values (by bit
    /// pattern, so that NaNs and signed zeros come back as they were).
    pub fn new(map: &Image<f32>) -> Option<Self> {
        // The distinct bit patterns, sorted; runs of one value (flat regions) skip the search.
        let mut distinct: Vec<u32> = Vec::new();
        let mut last = None;
        for &v in map.pixels() {
            let bits = v.to_bits();
            if last == Some(bits) {
                continue;
            }
            last = Some(bits);
            if let Err(at) = distinct.binary_search(&bits) {
                if distinct.len() == 256 {
                    return None;
                }
                distinct.insert(at, bits);
            }
        }
        let code = |v: f32| distinct.binary_search(&v.to_bits()).expect("a value seen above") as u8;
        let mut codes: Vec<u8> = map.pixels().iter().map(|&v| code(v)).collect();
        codes.extend([0; 3]);
        let mut values = Box::new([0.0f32; 256]);
        for (v, &bits) in values.iter_mut().zip(&distinct) {
            *v = f32::from_bits(bits);
        }
        Some(ComplexityCodes { width: map.width(), height: map.height(), codes, values })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The codes, row-major, with three bytes of padding after the last texel.
    pub fn codes(&self) -> &[u8] {
        &self.codes
    }

    /// The value of each code.
    pub fn values(&self) -> &[f32; 256] {
        &self.values
    }

    /// The value of texel `(x, y)` (`x < width`, `y < height`).
    pub fn get(&self, x: u32, y: u32) -> f32 {
        self.values[self.codes[y as usize * self.width as usize + x as usize] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every texel's code gives back its value bit for bit (NaN and −0 included); a map of
    /// more than 256 distinct values has no codes.
    #[test]
    fn codes_give_back_every_value() {
        let mut img = Image::new(37, 5, 0.0f32);
        for (i, p) in img.pixels_mut().iter_mut().enumerate() {
            *p = quantize((i % 29) as f32 / 28.0, 24);
        }
        img.pixels_mut()[3] = f32::NAN;
        img.pixels_mut()[4] = -0.0;
        let c = ComplexityCodes::new(&img).expect("few values");
        assert_eq!(c.codes().len(), 37 * 5 + 3);
        for y in 0..5 {
            for x in 0..37 {
                assert_eq!(c.get(x, y).to_bits(), img.get(x, y).to_bits(), "({x}, {y})");
            }
        }
        let many = Image::from_fn(32, 9, |x, y| (y * 32 + x) as f32);
        assert!(ComplexityCodes::new(&many).is_none());
        let map = complexity_map(
            &Image::from_fn(64, 64, |x, y| ((x * 7 + y * 3) % 13) as f32 / 13.0),
            &ComplexityParams::default(),
        );
        assert!(ComplexityCodes::new(&map).is_some(), "the thesis's quantised maps always fit");
    }

    #[test]
    fn reflect101_matches_opencv_border_interpolate() {
        // gfedcb|abcdefgh|gfedcba
        assert_eq!(reflect101(-1, 8), 1);
        assert_eq!(reflect101(8, 8), 6);
        assert_eq!(reflect101(3, 8), 3);
        assert_eq!(reflect101(-1, 2), 1);
        assert_eq!(reflect101(2, 2), 0);
        assert_eq!(reflect101(-1, 1), 0);
        assert_eq!(reflect101(1, 1), 0);
    }

    #[test]
    fn running_max_clips_at_the_ends() {
        let line = [0.0, 3.0, -1.0, -2.0, -5.0, 4.0];
        let mut out = [0.0; 6];
        let mut s = Vec::new();
        running_max(&line, 1, &mut out, &mut s);
        assert_eq!(out, [3.0, 3.0, 3.0, -1.0, 4.0, 4.0]);
        running_max(&line, 2, &mut out, &mut s);
        assert_eq!(out, [3.0, 3.0, 3.0, 4.0, 4.0, 4.0]);
        running_max(&line, 10, &mut out, &mut s);
        assert_eq!(out, [4.0; 6]);
        let neg = [-2.0, -1.0, -3.0];
        let mut out3 = [0.0; 3];
        running_max(&neg, 1, &mut out3, &mut s);
        assert_eq!(out3, [-1.0, -1.0, -1.0]);
    }

    #[test]
    fn transpose_round_trips() {
        let (w, h) = (37, 70);
        let v: Vec<f32> = (0..w * h).map(|i| i as f32).collect();
        let t = transpose(&v, w, h);
        assert_eq!(t[5 * h + 9], v[9 * w + 5]);
        assert_eq!(transpose(&t, h, w), v);
    }
}
