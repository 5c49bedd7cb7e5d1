//! Tests of the Sobel complexity map: small cases computed by hand (the arithmetic is in the
//! comments), golden values produced by the thesis's Python code with OpenCV 4.14 and
//! NumPy 2.4, and property tests.

use proptest::prelude::*;
use renderlab_core::Image;
use renderlab_relief::maps::complexity::{
    complexity_map, dilate, level_step, normalize_by_max, quantize, sobel_magnitude, to_u8_levels,
    ComplexityParams,
};

fn img(w: u32, h: u32, v: &[f32]) -> Image<f32> {
    Image::from_vec(w, h, v.to_vec()).unwrap()
}

fn assert_close(got: &Image<f32>, want: &[f32], tol: f32) {
    assert_eq!(got.pixels().len(), want.len());
    for (i, (g, w)) in got.pixels().iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tol,
            "pixel {i} (x {}, y {}): got {g}, want {w}",
            i % got.width() as usize,
            i / got.width() as usize
        );
    }
}

const S2: f32 = std::f32::consts::SQRT_2;

// ----------------------------------------------------------------------------------------
// Sobel, by hand
// ----------------------------------------------------------------------------------------

#[test]
fn ramp_4x4() {
    // h(x, y) = x/4 on every row: 0, .25, .5, .75.
    // Row pass, reflect-101 (index −1 → 1, index 4 → 2):
    //   d(0) = h(1) − h(1) = 0, d(1) = h(2) − h(0) = .5, d(2) = h(3) − h(1) = .5,
    //   d(3) = h(2) − h(2) = 0.
    // Column pass [1 2 1] on rows that are all equal: Gx = 4·d = 0, 2, 2, 0.
    // The x-smoothing is the same on every row, so Gy = 0. |G| = 0, 2, 2, 0 on each row.
    let h = Image::from_fn(4, 4, |x, _| x as f32 * 0.25);
    let m = sobel_magnitude(&h);
    let row = [0.0, 2.0, 2.0, 0.0];
    let want: Vec<f32> = row.iter().cycle().take(16).copied().collect();
    assert_close(&m, &want, 0.0);
    // Normalised by the maximum 2: 0, 1, 1, 0; one dilation spreads the ones to the edges.
    let n = normalize_by_max(&m);
    assert_close(&n, &[0.0, 1.0, 1.0, 0.0].repeat(4), 0.0);
    assert_close(&dilate(&n, 1), &[1.0; 16], 0.0);
}

#[test]
fn impulse_in_the_interior() {
    // 5×5, a single 1 at (2, 2).
    // Row 2's x-difference: d(1) = h(2) − h(0) = 1, d(3) = h(4) − h(2) = −1, else 0.
    // Gx(x, y) = (d_{y−1} + d_{y+1}) + 2·d_y, so Gx(1, 1..=3) = 1, 2, 1 and
    // Gx(3, 1..=3) = −1, −2, −1. Gy is the transpose: Gy(1..=3, 1) = 1, 2, 1 and
    // Gy(1..=3, 3) = −1, −2, −1.
    // |G|: corners of the 3×3 ring sqrt(1 + 1) = √2, edge middles 2, centre 0.
    let mut v = [0.0f32; 25];
    v[2 * 5 + 2] = 1.0;
    let m = sobel_magnitude(&img(5, 5, &v));
    #[rustfmt::skip]
    let want = [
        0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, S2,  2.0, S2,  0.0,
        0.0, 2.0, 0.0, 2.0, 0.0,
        0.0, S2,  2.0, S2,  0.0,
        0.0, 0.0, 0.0, 0.0, 0.0,
    ];
    assert_close(&m, &want, 0.0);
}

#[test]
fn impulse_beside_the_border_uses_reflect_101() {
    // 4×4, a single 1 at (1, 1). With reflect-101 the mirrored neighbour of column 0 is
    // column 1, so d(0) = h(1) − h(1) = 0 and d(1) = h(2) − h(0) = 0: nothing to the left.
    // d(2) = h(3) − h(1) = −1 on row 1 only; the column pass (row −1 mirrors to row 1):
    //   Gx(2, 0) = (d_1 + d_1) + 2·d_0 = −2, Gx(2, 1) = (d_0 + d_2) + 2·d_1 = −2,
    //   Gx(2, 2) = (d_1 + d_3) + 2·d_2 = −1, Gx(2, 3) = (d_2 + d_2) + 2·d_3 = 0.
    // Gy is the transpose: Gy(0, 2) = −2, Gy(1, 2) = −2, Gy(2, 2) = −1.
    // (This is what cv2.Sobel returns for the same array.)
    let mut v = [0.0f32; 16];
    v[4 + 1] = 1.0;
    let m = sobel_magnitude(&img(4, 4, &v));
    #[rustfmt::skip]
    let want = [
        0.0, 0.0, 2.0, 0.0,
        0.0, 0.0, 2.0, 0.0,
        2.0, 2.0, S2,  0.0,
        0.0, 0.0, 0.0, 0.0,
    ];
    assert_close(&m, &want, 0.0);

    // Whole pipeline, no dilation: max 2, so (2, 2) normalises to √2/2 = 2^−½;
    // gamma 0.8 gives 2^−0.4 = 0.757858…; ×23 = 17.43 → 17, i.e. 17/23.
    let p = ComplexityParams { dilation_iterations: 0, ..Default::default() };
    let c = complexity_map(&img(4, 4, &v), &p);
    let k = 17.0 / 23.0;
    #[rustfmt::skip]
    let want = [
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 1.0, 0.0,
        1.0, 1.0, k,   0.0,
        0.0, 0.0, 0.0, 0.0,
    ];
    assert_close(&c, &want, 1e-6);
}

#[test]
fn vertical_step_edge() {
    // 6×3, 0 for x < 3 and 1 for x ≥ 3. d(2) = h(3) − h(1) = 1, d(3) = h(4) − h(2) = 1,
    // d(0) = h(1) − h(1) = 0, d(5) = h(4) − h(4) = 0, d(1) = d(4) = 0.
    // The rows are equal, so Gx = 4·d and Gy = 0: |G| = 0 0 4 4 0 0 on every row.
    let h = Image::from_fn(6, 3, |x, _| if x >= 3 { 1.0 } else { 0.0 });
    let m = sobel_magnitude(&h);
    assert_close(&m, &[0.0, 0.0, 4.0, 4.0, 0.0, 0.0].repeat(3), 0.0);
    let n = normalize_by_max(&m);
    // One dilation: 0 1 1 1 1 0; two: all ones.
    assert_close(&dilate(&n, 1), &[0.0, 1.0, 1.0, 1.0, 1.0, 0.0].repeat(3), 0.0);
    assert_close(&dilate(&n, 2), &[1.0; 18], 0.0);
}

#[test]
fn single_row_and_two_wide_borders() {
    // 5×1 ramp 0, .25, .5, .75, 1: d = 0, .5, .5, .5, 0 (ends mirror onto themselves).
    // With one row, rows −1 and 1 both mirror to row 0: Gx = (d + d) + 2·d = 4·d and
    // Gy = s − s = 0, so |G| = 0 2 2 2 0 (cv2.Sobel agrees).
    let h = img(5, 1, &[0.0, 0.25, 0.5, 0.75, 1.0]);
    assert_close(&sobel_magnitude(&h), &[0.0, 2.0, 2.0, 2.0, 0.0], 0.0);
    // The same ramp as a column gives the same numbers.
    let t = img(1, 5, &[0.0, 0.25, 0.5, 0.75, 1.0]);
    assert_close(&sobel_magnitude(&t), &[0.0, 2.0, 2.0, 2.0, 0.0], 0.0);
    // Two pixels wide: index −1 → 1 and index 2 → 0, so d(0) = h(1) − h(1) and
    // d(1) = h(0) − h(0): every derivative along a two-long axis is zero.
    let two = img(2, 2, &[0.0, 1.0, 0.3, 0.9]);
    assert_close(&sobel_magnitude(&two), &[0.0; 4], 0.0);
}

#[test]
fn flat_and_one_pixel_maps_give_zeros() {
    let p = ComplexityParams::default();
    let flat = Image::new(7, 5, 0.42f32);
    let c = complexity_map(&flat, &p);
    assert!(c.pixels().iter().all(|&v| v == 0.0));
    let one = Image::new(1, 1, 0.8f32);
    assert_eq!(complexity_map(&one, &p).pixels(), &[0.0]);
    assert_eq!(sobel_magnitude(&one).pixels(), &[0.0]);
    assert_eq!(dilate(&one, 5).pixels(), &[0.8]);
}

#[test]
fn non_finite_input_never_gives_nan() {
    let mut v = vec![0.5f32; 9 * 7];
    v[10] = f32::NAN;
    v[30] = f32::INFINITY;
    v[40] = 0.0;
    let c = complexity_map(&img(9, 7, &v), &ComplexityParams::default());
    assert!(c.pixels().iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)));
}

// ----------------------------------------------------------------------------------------
// Dilation, gamma, quantisation, by hand
// ----------------------------------------------------------------------------------------

#[test]
fn dilation_of_impulses_grows_squares_clipped_at_the_border() {
    // 7×7: 1 at (3, 3) and 0.5 at (6, 0) (top-right corner). One iteration: a 3×3 square
    // of ones at x, y ∈ 2..=4 and the corner value over x 5..=6, y 0..=1. Two
    // iterations: 5×5 of ones at 1..=5, the corner value over x 4..=6, y 0..=2, where
    // the ones win wherever both reach. (cv2.dilate gives these arrays.)
    let mut v = [0.0f32; 49];
    v[3 * 7 + 3] = 1.0;
    v[6] = 0.5;
    let m = img(7, 7, &v);
    let one = dilate(&m, 1);
    let two = dilate(&m, 2);
    for y in 0..7u32 {
        for x in 0..7u32 {
            let in3 = (2..=4).contains(&x) && (2..=4).contains(&y);
            let c1 = x >= 5 && y <= 1;
            let want1 = if in3 {
                1.0
            } else if c1 {
                0.5
            } else {
                0.0
            };
            assert_eq!(one.get(x, y), want1, "1 iteration at ({x}, {y})");
            let in5 = (1..=5).contains(&x) && (1..=5).contains(&y);
            let c2 = x >= 4 && y <= 2;
            let want2 = if in5 {
                1.0
            } else if c2 {
                0.5
            } else {
                0.0
            };
            assert_eq!(two.get(x, y), want2, "2 iterations at ({x}, {y})");
        }
    }
}

#[test]
fn dilation_ignores_samples_outside_the_image() {
    // All −1 except −0.5 in the centre of a 3×3: the result is −0.5 everywhere; had the
    // border counted as 0 the edges would read 0.
    let mut v = [-1.0f32; 9];
    v[4] = -0.5;
    assert_close(&dilate(&img(3, 3, &v), 1), &[-0.5; 9], 0.0);
    assert_close(&dilate(&img(3, 3, &v), 0), &v, 0.0);
}

#[test]
fn gamma_and_quantisation_of_known_values() {
    // 0.5^0.8 = 2^−0.8 = 0.574349…; ×23 = 13.21 → level 13 = 0.565217….
    let c = Image::new(1, 1, 0.5f32);
    let p = ComplexityParams::default();
    let g = 0.5f32.powf(p.gamma);
    assert!((g - 0.574_349_2).abs() < 1e-6);
    assert!((quantize(g, 24) - 13.0 / 23.0).abs() < 1e-6);
    // Through dilate + gamma + quantise as the pipeline does (a constant map stays constant).
    let d = dilate(&c, 5);
    assert_eq!(d.get(0, 0), 0.5);
    // Ties go to even, like np.round: with 3 levels the step is 0.5, so 0.25 is 0.5 steps
    // (→ 0) and 0.75 is 1.5 steps (→ 2 steps = 1.0); with 5 levels (step 0.25) 0.625 is
    // 2.5 steps (→ 2 = 0.5) and 0.875 is 3.5 steps (→ 4 = 1.0).
    assert_eq!(quantize(0.25, 3), 0.0);
    assert_eq!(quantize(0.75, 3), 1.0);
    assert_eq!(quantize(0.625, 5), 0.5);
    assert_eq!(quantize(0.875, 5), 1.0);
    assert_eq!(quantize(0.26, 3), 0.5);
    // The step is 1/(N − 1) rounded to f32, as NumPy applies a Python float to float32.
    assert_eq!(level_step(24), (1.0f64 / 23.0) as f32);
    assert_eq!(level_step(2), 1.0);
}

#[test]
fn eight_bit_output_truncates_like_astype_uint8() {
    // (k·step·255) truncated, in f32, for the script's 24 levels (NumPy prints this list).
    let step = level_step(24);
    let levels = Image::from_fn(24, 1, |k, _| k as f32 * step);
    let u = to_u8_levels(&levels);
    assert_eq!(
        u.pixels(),
        &[
            0, 11, 22, 33, 44, 55, 66, 77, 88, 99, 110, 121, 133, 144, 155, 166, 177, 188, 199, 210, 221,
            232, 243, 255
        ]
    );
    let odd = img(4, 1, &[f32::NAN, -1.0, 2.0, 0.999]);
    assert_eq!(to_u8_levels(&odd).pixels(), &[0, 0, 255, 254]);
}

#[test]
fn parameters_are_validated_with_flag_names() {
    assert!(ComplexityParams::default().validate().is_ok());
    assert_eq!(
        ComplexityParams::default(),
        ComplexityParams { dilation_iterations: 5, gamma: 0.8, levels: 24 }
    );
    assert!(ComplexityParams::function_defaults().validate().is_ok());
    let bad = |p: ComplexityParams, flag: &str| {
        let e = p.validate().unwrap_err().to_string();
        assert!(e.contains(flag), "{e} should name {flag}");
    };
    let d = ComplexityParams::default();
    bad(ComplexityParams { gamma: f32::NAN, ..d }, "--gamma");
    bad(ComplexityParams { gamma: 0.0, ..d }, "--gamma");
    bad(ComplexityParams { gamma: 10.5, ..d }, "--gamma");
    bad(ComplexityParams { gamma: f32::INFINITY, ..d }, "--gamma");
    bad(ComplexityParams { levels: 1, ..d }, "--levels");
    bad(ComplexityParams { levels: 257, ..d }, "--levels");
    bad(ComplexityParams { dilation_iterations: 65, ..d }, "--dilate");
    assert!(ComplexityParams { gamma: 10.0, levels: 256, dilation_iterations: 64 }.validate().is_ok());
    // Unvalidated parameters are clamped, never a panic.
    let h = Image::from_fn(5, 4, |x, y| ((x * 3 + y) % 4) as f32 / 3.0);
    for p in [
        ComplexityParams { gamma: f32::NAN, levels: 0, dilation_iterations: 1000 },
        ComplexityParams { gamma: -1.0, levels: 1, dilation_iterations: 0 },
    ] {
        let c = complexity_map(&h, &p);
        assert!(c.pixels().iter().all(|v| (0.0..=1.0).contains(v)));
    }
}

// ----------------------------------------------------------------------------------------
// Golden values from the thesis's code (OpenCV 4.14, NumPy 2.4)
// ----------------------------------------------------------------------------------------

/// A 32×24 test height map (8-bit): a cone-shaped bump at (10, 9), a plateau of 200 right
/// of x = 24, and a strip of small noise below y = 20.
fn golden_input() -> Image<f32> {
    Image::from_fn(32, 24, |x, y| {
        let (xi, yi) = (x as i32, y as i32);
        let r2 = (xi - 10).pow(2) + (yi - 9).pow(2);
        let mut b = (250 - 4 * r2).max(40);
        if x >= 24 {
            b = 200;
        }
        if y >= 20 && x < 24 {
            b = 40 + ((xi * 7 + yi * 13) % 9);
        }
        b as f32 / 255.0
    })
}

/// Level indices produced by `calculate_complexity(h, dilation_iterations=5,
/// num_levels=24)` ('a' = 0 … 'x' = 23).
const GOLDEN_24: [&str; 24] = [
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "ppppppppppppppppppxxxxxxxxxxxxaa",
    "lpppppppppppppppppxxxxxxxxxxxxaa",
    "eknpppppppppppppppxxxxxxxxxxxxaa",
    "cdgjllllllllllllljxxxxxxxxxxxxaa",
    "cccccdddddddddddccxxxxxxxxxxxxaa",
    "ccccccccccccccccccxxxxxxxxxxxxaa",
];

/// Level indices for the Python function's own defaults (1 iteration, 10 levels).
const GOLDEN_10: [&str; 24] = [
    "00000000111110000000009999000000",
    "00000124444444210000009999000000",
    "00002456666666542000009999000000",
    "00024666666666664200009999000000",
    "00146666666666666410009999000000",
    "00256666655566666520009999000000",
    "00466666554556666640009999000000",
    "01466665544455666641009999000000",
    "01466655433345566641009999000000",
    "01466654432344566641009999000000",
    "01466655433345566641009999000000",
    "01466665544455666641009999000000",
    "00466666554556666640009999000000",
    "00256666655566666520009999000000",
    "00146666666666666410009999000000",
    "00024666666666664200009999000000",
    "00002456666666542000009999000000",
    "00000124444444210000009999000000",
    "11101111111111111111109999000000",
    "11111111111111111111119999000000",
    "11111111111111111111119999000000",
    "01111011111111011111119999000000",
    "00000000000000000000009999000000",
    "00000000000000000000009999000000",
];

/// `np.sqrt(grad_x ** 2 + grad_y ** 2)` for rows 7, 8 and 9, as f32 bit patterns.
#[rustfmt::skip]
const GOLDEN_MAGNITUDE_ROWS_7_TO_9: [u32; 96] = [
        0x00000000, 0x00000000, 0x3d632959, 0x3f47b278, 0x3fbb69e4, 0x3fad0046, 0x3f8fab68, 0x3f67a902, 0x3f35baad, 0x3f0fab68, 0x3f008080, 0x3f0fab68, 0x3f35baad, 0x3f67a902, 0x3f8fab68, 0x3fad0046, 0x3fbb69e4, 0x3f47b278, 0x3d632959, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x4020a0a1, 0x4020a0a1, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000,
        0x00000000, 0x00000000, 0x3e13a7ad, 0x3f74f4f4, 0x3fc24219, 0x3fa3cefa, 0x3f8474f0, 0x3f4b2def, 0x3f0fab68, 0x3eb5baad, 0x3e808080, 0x3eb5baad, 0x3f0fab68, 0x3f4b2def, 0x3f8474f0, 0x3fa3cefa, 0x3fc24219, 0x3f74f4f4, 0x3e13a7ad, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x4020a0a1, 0x4020a0a1, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000,
        0x00000000, 0x00000000, 0x3e40c0c0, 0x3f808080, 0x3fc0c0c2, 0x3fa0a0a1, 0x3f808080, 0x3f40c0c0, 0x3f008080, 0x3e808080, 0x00000000, 0x3e808080, 0x3f008080, 0x3f40c0c0, 0x3f808080, 0x3fa0a0a1, 0x3fc0c0c2, 0x3f808080, 0x3e40c0c0, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x4020a0a1, 0x4020a0a1, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000,
];

fn check_golden(params: ComplexityParams, rows: &[&str; 24], digit: impl Fn(char) -> u32) {
    let c = complexity_map(&golden_input(), &params);
    let u = to_u8_levels(&c);
    let step = level_step(params.levels);
    for (y, row) in rows.iter().enumerate() {
        for (x, ch) in row.chars().enumerate() {
            let k = digit(ch);
            let want = k as f32 * step;
            let got = c.get(x as u32, y as u32);
            assert_eq!(got, want, "level at ({x}, {y})");
            assert_eq!(u.get(x as u32, y as u32), (want * 255.0) as u8);
        }
    }
}

#[test]
fn matches_the_thesis_script_bit_for_bit() {
    check_golden(ComplexityParams::default(), &GOLDEN_24, |c| c as u32 - 'a' as u32);
    check_golden(ComplexityParams::function_defaults(), &GOLDEN_10, |c| c.to_digit(10).unwrap());
    let m = sobel_magnitude(&golden_input());
    assert_eq!(m.pixels().iter().copied().fold(0.0f32, f32::max).to_bits(), 1075882615);
    for (i, &bits) in GOLDEN_MAGNITUDE_ROWS_7_TO_9.iter().enumerate() {
        let (x, y) = (i as u32 % 32, 7 + i as u32 / 32);
        assert_eq!(m.get(x, y).to_bits(), bits, "magnitude at ({x}, {y})");
    }
}

// ----------------------------------------------------------------------------------------
// Properties
// ----------------------------------------------------------------------------------------

/// Straightforward 2-D Sobel with explicit reflect-101 indexing, for comparison.
fn naive_sobel(h: &Image<f32>) -> Image<f32> {
    let (w, hh) = (h.width() as i64, h.height() as i64);
    let refl = |i: i64, n: i64| -> u32 {
        if n == 1 {
            0
        } else if i < 0 {
            (-i) as u32
        } else if i >= n {
            (2 * n - 2 - i) as u32
        } else {
            i as u32
        }
    };
    Image::from_fn(h.width(), h.height(), |x, y| {
        let s = |dx: i64, dy: i64| h.get(refl(x as i64 + dx, w), refl(y as i64 + dy, hh)) as f64;
        let gx = (s(1, -1) - s(-1, -1)) + 2.0 * (s(1, 0) - s(-1, 0)) + (s(1, 1) - s(-1, 1));
        let gy = (s(-1, 1) - s(-1, -1)) + 2.0 * (s(0, 1) - s(0, -1)) + (s(1, 1) - s(1, -1));
        (gx * gx + gy * gy).sqrt() as f32
    })
}

/// Brute-force clipped square maximum of radius `r`.
fn naive_dilate(m: &Image<f32>, r: u32) -> Image<f32> {
    let (w, h) = (m.width() as i64, m.height() as i64);
    Image::from_fn(m.width(), m.height(), |x, y| {
        let mut best = f32::NEG_INFINITY;
        for yy in (y as i64 - r as i64).max(0)..=(y as i64 + r as i64).min(h - 1) {
            for xx in (x as i64 - r as i64).max(0)..=(x as i64 + r as i64).min(w - 1) {
                best = best.max(m.get(xx as u32, yy as u32));
            }
        }
        best
    })
}

/// Rotates 90° counter-clockwise: pixel (x, y) of the result is (w − 1 − y, x) of `m`.
fn rot90(m: &Image<f32>) -> Image<f32> {
    let w = m.width();
    Image::from_fn(m.height(), m.width(), |x, y| m.get(w - 1 - y, x))
}

fn arb_map(max_side: u32) -> impl Strategy<Value = Image<f32>> {
    (1..=max_side, 1..=max_side).prop_flat_map(|(w, h)| {
        prop::collection::vec(0u8..=255, (w * h) as usize).prop_map(move |v| {
            Image::from_vec(w, h, v.into_iter().map(|b| b as f32 / 255.0).collect()).unwrap()
        })
    })
}

fn arb_params() -> impl Strategy<Value = ComplexityParams> {
    (0u32..=7, 0.05f32..=10.0, 2u32..=256).prop_map(|(dilation_iterations, gamma, levels)| ComplexityParams {
        dilation_iterations,
        gamma,
        levels,
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn output_is_quantised_into_unit_range(h in arb_map(14), p in arb_params()) {
        let c = complexity_map(&h, &p);
        prop_assert_eq!(c.size(), h.size());
        let n = (p.levels - 1) as f32;
        for &v in c.pixels() {
            prop_assert!((0.0..=1.0).contains(&v), "{} out of range", v);
            let k = (v * n).round();
            prop_assert!((v - k / n).abs() <= 1e-6, "{} is not a multiple of 1/{}", v, n);
        }
    }

    #[test]
    fn sobel_matches_a_direct_convolution(h in arb_map(20)) {
        let fast = sobel_magnitude(&h);
        let slow = naive_sobel(&h);
        for (a, b) in fast.pixels().iter().zip(slow.pixels()) {
            prop_assert!((a - b).abs() <= 1e-5, "{} vs {}", a, b);
        }
    }

    #[test]
    fn normalised_maximum_is_exactly_one(h in arb_map(14)) {
        let m = sobel_magnitude(&h);
        let n = normalize_by_max(&m);
        let max = n.pixels().iter().copied().fold(0.0f32, f32::max);
        if m.pixels().iter().any(|&v| v > 0.0) {
            prop_assert_eq!(max, 1.0);
        } else {
            prop_assert_eq!(max, 0.0);
        }
        prop_assert!(n.pixels().iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn dilation_is_a_clipped_square_maximum(h in arb_map(16), a in 0u32..6, b in 0u32..6) {
        let d = dilate(&h, a);
        // Equal to the brute-force (2a+1)² clipped maximum, hence ≥ the input.
        prop_assert_eq!(&d, &naive_dilate(&h, a));
        for (x, y) in d.pixels().iter().zip(h.pixels()) {
            prop_assert!(x >= y);
        }
        // Iterations compose: a then b equals a + b; and once the square covers the
        // image every pixel holds the global maximum, after which nothing changes.
        prop_assert_eq!(dilate(&d, b), dilate(&h, a + b));
        let all = h.width().max(h.height());
        let full = dilate(&h, all);
        let max = h.pixels().iter().copied().fold(f32::NEG_INFINITY, f32::max);
        prop_assert!(full.pixels().iter().all(|&v| v == max));
        prop_assert_eq!(dilate(&full, 3), full);
    }

    #[test]
    fn rotating_the_input_rotates_the_magnitude(h in arb_map(16)) {
        let a = rot90(&sobel_magnitude(&h));
        let b = sobel_magnitude(&rot90(&h));
        for (x, y) in a.pixels().iter().zip(b.pixels()) {
            prop_assert!((x - y).abs() <= 1e-5, "{} vs {}", x, y);
        }
    }

    #[test]
    fn rotating_dyadic_input_rotates_the_map_exactly(
        w in 1u32..=12,
        hh in 1u32..=12,
        seed in any::<u64>(),
        p in arb_params(),
    ) {
        // Multiples of 1/16 make every Sobel sum exact, so both orientations agree bit
        // for bit through the whole pipeline.
        let mut s = seed | 1;
        let h = Image::from_fn(w, hh, |_, _| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s % 17) as f32 / 16.0
        });
        prop_assert_eq!(rot90(&complexity_map(&h, &p)), complexity_map(&rot90(&h), &p));
    }
}
