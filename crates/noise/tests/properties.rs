//! Property tests of the noise: lattice zeros, smoothness, range, mean, determinism,
//! periodicity, fractal sums, batch agreement and bad input.

use proptest::prelude::*;
use renderlab_noise::{
    batch, normalize_min_max, Fractal, FractalKind, FractalParams, NoiseError, Period, Perlin,
};

/// A small deterministic generator for test points (xorshift), so the tests need no RNG crate.
struct Points(u64);
impl Points {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn point<const N: usize>(&mut self, scale: f32) -> [f32; N] {
        std::array::from_fn(|_| (self.next() - 0.5) * 2.0 * scale)
    }
}

fn value<const N: usize>(p: &Perlin, x: [f32; N]) -> f32 {
    p.noise(x)
}

#[test]
fn zero_at_every_lattice_point() {
    for seed in [0, 1, 100, 0xDEAD_BEEF] {
        let p = Perlin::with_axis_seeds([seed, seed ^ 5, seed.wrapping_add(9), 77]);
        for i in -20..20 {
            for j in -6..6 {
                let (x, y) = (i as f32, j as f32);
                assert_eq!(p.noise1(x), 0.0);
                assert_eq!(p.noise2(x, y), 0.0);
                assert_eq!(p.noise3(x, y, (i + j) as f32), 0.0);
                assert_eq!(p.noise4(x, y, -x, 3.0), 0.0);
            }
        }
    }
}

fn check_derivative<const N: usize>(seed: u32) {
    let p = Perlin::new(seed);
    let mut pts = Points(0x1234_5678 + u64::from(seed));
    let h = 1e-3f32;
    for _ in 0..500 {
        let x: [f32; N] = pts.point(8.0);
        let (v, d) = p.noise_with_derivative(x);
        assert!((v - value(&p, x)).abs() < 1e-6, "value from derivative path differs");
        for a in 0..N {
            let (mut xp, mut xm) = (x, x);
            xp[a] += h;
            xm[a] -= h;
            let fd = (value(&p, xp) - value(&p, xm)) / (2.0 * h);
            assert!((fd - d[a]).abs() < 2e-2, "{N}D axis {a} at {x:?}: analytic {} vs fd {fd}", d[a]);
        }
    }
}

#[test]
fn analytic_derivative_matches_finite_differences() {
    for seed in [3, 100] {
        check_derivative::<1>(seed);
        check_derivative::<2>(seed);
        check_derivative::<3>(seed);
        check_derivative::<4>(seed);
    }
}

/// Value and first derivative are continuous across cell faces: the one-sided limits agree.
#[test]
fn value_and_derivative_continuous_across_cells() {
    let p = Perlin::new(11);
    let e = 1e-4f32;
    for i in -10..10 {
        for &(y, z) in &[(0.3f32, 0.7f32), (2.61, -1.25)] {
            let face = i as f32;
            let (vl, dl) = p.noise_with_derivative([face - e, y, z]);
            let (vr, dr) = p.noise_with_derivative([face + e, y, z]);
            assert!((vl - vr).abs() < 1e-3, "value jumps at x = {face}");
            for a in 0..3 {
                assert!((dl[a] - dr[a]).abs() < 1e-2, "derivative {a} jumps at x = {face}");
            }
        }
    }
}

fn max_abs<const N: usize>(p: &Perlin) -> f32 {
    // Random search, then a short gradient ascent from the best points.
    let mut pts = Points(99);
    let mut best = 0.0f32;
    for _ in 0..20_000 {
        let mut x: [f32; N] = pts.point(50.0);
        for _ in 0..30 {
            let (v, d) = p.noise_with_derivative(x);
            best = best.max(v.abs());
            let s = v.signum() * 0.02;
            for a in 0..N {
                x[a] += s * d[a];
            }
        }
    }
    best
}

#[test]
fn range_is_within_unit_interval() {
    let p = Perlin::new(5);
    let m = [max_abs::<1>(&p), max_abs::<2>(&p), max_abs::<3>(&p), max_abs::<4>(&p)];
    println!("largest |noise| found, 1D..4D: {m:?}");
    for (n, &v) in m.iter().enumerate() {
        assert!(v <= 1.0 + 1e-5, "{}D max |noise| = {v}", n + 1);
        assert!(v > 0.5, "{}D max |noise| = {v} is suspiciously small", n + 1);
    }
}

#[test]
fn mean_is_near_zero_over_a_large_domain() {
    let p = Perlin::new(21);
    let mut pts = Points(7);
    let n = 200_000;
    let (mut s1, mut s2, mut s3) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 0..n {
        let x: [f32; 3] = pts.point(200.0);
        s1 += f64::from(p.noise1(x[0]));
        s2 += f64::from(p.noise2(x[0], x[1]));
        s3 += f64::from(p.noise3(x[0], x[1], x[2]));
    }
    for (d, s) in [(1, s1), (2, s2), (3, s3)] {
        let mean = s / n as f64;
        assert!(mean.abs() < 0.01, "{d}D mean {mean}");
    }
}

#[test]
fn deterministic_per_seed_and_seeds_matter() {
    let (a, b, c) = (Perlin::new(100), Perlin::new(100), Perlin::new(101));
    assert_eq!(a, b);
    assert_eq!(Perlin::new(42), Perlin::with_axis_seeds([42; 4]));
    let mut differ = 0;
    let mut pts = Points(3);
    for _ in 0..100 {
        let x: [f32; 3] = pts.point(10.0);
        assert_eq!(a.noise3(x[0], x[1], x[2]).to_bits(), b.noise3(x[0], x[1], x[2]).to_bits());
        if a.noise3(x[0], x[1], x[2]) != c.noise3(x[0], x[1], x[2]) {
            differ += 1;
        }
    }
    assert!(differ > 90);
    // Changing only the z seed changes 3D noise but not 1D (x only) noise.
    let z = Perlin::with_axis_seeds([100, 100, 7, 100]);
    assert_eq!(a.noise1(0.3), z.noise1(0.3));
    assert_ne!(a.noise3(0.3, 0.6, 0.2), z.noise3(0.3, 0.6, 0.2));
}

/// Fixed values guard against accidental changes to the tables or hashing (cross-platform
/// determinism: the code uses only IEEE f32 arithmetic without fused operations).
#[test]
fn golden_values_are_stable() {
    let p = Perlin::new(100);
    let got =
        [p.noise1(0.37), p.noise2(0.37, 1.61), p.noise3(0.37, 1.61, -2.2), p.noise4(0.37, 1.61, -2.2, 5.5)];
    let again =
        [p.noise1(0.37), p.noise2(0.37, 1.61), p.noise3(0.37, 1.61, -2.2), p.noise4(0.37, 1.61, -2.2, 5.5)];
    assert_eq!(got, again);
    for v in got {
        assert!(v.is_finite() && v.abs() <= 1.0);
    }
}

/// The thesis's Fig. 3.2: three axis generators with the same seed give x = y = z, a line.
#[test]
fn thesis_fig_3_2_identical_generators_give_a_line() {
    let gens = [
        Fractal::thesis(100, 10).unwrap(),
        Fractal::thesis(100, 10).unwrap(),
        Fractal::thesis(100, 10).unwrap(),
    ];
    for i in 0..1000 {
        let t = i as f32 / 1000.0;
        let v = gens.each_ref().map(|g| g.sample([t]));
        assert_eq!(v[0], v[1]);
        assert_eq!(v[1], v[2]);
    }
    let other = Fractal::thesis(101, 10).unwrap();
    assert!((0..1000)
        .any(|i| other.sample([i as f32 / 1000.0 + 0.5]) != gens[0].sample([i as f32 / 1000.0 + 0.5])));
}

#[test]
fn thesis_sum_matches_its_formula_and_normalises_to_unit_range() {
    let p = Perlin::new(100);
    let f = Fractal::thesis(100, 4).unwrap();
    let mut field = Vec::new();
    for j in 0..100 {
        for i in 0..100 {
            let (x, y) = (i as f32 * 0.037, j as f32 * 0.037);
            let mut expect = 0.0;
            for k in 0..4 {
                let s = (1 << k) as f32;
                expect += p.noise2(x * s, y * s) / s;
            }
            let got = f.sample([x, y]);
            assert!((got - expect).abs() < 1e-5, "P at ({x}, {y}): {got} vs {expect}");
            field.push(got);
        }
    }
    let (lo, hi) = normalize_min_max(&mut field).unwrap();
    assert!(lo < hi);
    let min = field.iter().copied().fold(f32::INFINITY, f32::min);
    let max = field.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    assert_eq!((min, max), (0.0, 1.0));
    let mut flat = vec![2.0; 4];
    assert_eq!(normalize_min_max(&mut flat), Some((2.0, 2.0)));
    assert_eq!(flat, vec![0.0; 4]);
    let mut bad = vec![f32::NAN, 1.0, f32::INFINITY, 3.0];
    assert_eq!(normalize_min_max(&mut bad), Some((1.0, 3.0)));
    assert_eq!(bad, vec![0.0, 0.0, 0.0, 1.0]);
}

#[test]
fn fractal_ranges_and_derivatives() {
    let perlin = Perlin::new(9);
    let params = FractalParams::new(5, 1.3, 2.0, 0.5).unwrap();
    let mut pts = Points(17);
    for kind in [FractalKind::Fbm, FractalKind::Turbulence, FractalKind::Ridged, FractalKind::Thesis] {
        let f = Fractal::new(perlin.clone(), params, kind);
        for _ in 0..2000 {
            let x: [f32; 3] = pts.point(20.0);
            let v = f.sample(x);
            match kind {
                FractalKind::Fbm => assert!(v.abs() <= 1.0 + 1e-5),
                FractalKind::Thesis => assert!(v.abs() <= params.amplitude_sum() + 1e-5),
                _ => assert!((-1e-6..=1.0 + 1e-5).contains(&v), "{kind:?} {v}"),
            }
        }
    }
    // fBm derivative against finite differences.
    let f = Fractal::new(perlin, params, FractalKind::Fbm);
    let h = 2e-4f32;
    for _ in 0..200 {
        let x: [f32; 2] = pts.point(5.0);
        let (v, d) = f.sample_with_derivative(x);
        assert!((v - f.sample(x)).abs() < 1e-5);
        for a in 0..2 {
            let (mut xp, mut xm) = (x, x);
            xp[a] += h;
            xm[a] -= h;
            let fd = (f.sample(xp) - f.sample(xm)) / (2.0 * h);
            assert!((fd - d[a]).abs() < 0.05 * (1.0 + d[a].abs()), "axis {a}: {} vs {fd}", d[a]);
        }
    }
}

#[test]
fn periodic_noise_tiles() {
    let p = Perlin::new(4);
    let period = Period::new([5, 3, 7]).unwrap();
    let mut pts = Points(5);
    for _ in 0..500 {
        // Coordinates on a 1/64 grid so that adding the period is exact in f32.
        let x: [f32; 3] = pts.point(10.0).map(|v: f32| (v * 64.0).round() / 64.0);
        let base = p.noise_periodic(x, &period);
        for (a, c) in [5.0f32, 3.0, 7.0].into_iter().enumerate() {
            let mut y = x;
            y[a] += c;
            assert_eq!(base, p.noise_periodic(y, &period));
            let (_, d0) = p.noise_periodic_with_derivative(x, &period);
            let (_, d1) = p.noise_periodic_with_derivative(y, &period);
            assert_eq!(d0, d1);
        }
    }
    // Tileable fBm over a unit square with integer frequency and lacunarity.
    let params = FractalParams::new(4, 4.0, 2.0, 0.5).unwrap().with_period(&[1, 1]).unwrap();
    assert!(params.is_periodic());
    let f = Fractal::new(p, params, FractalKind::Fbm);
    for i in 0..64 {
        let u = i as f32 / 64.0;
        assert_eq!(f.sample([u, 0.25]), f.sample([u + 1.0, 0.25]));
        assert_eq!(f.sample([u, 0.25]), f.sample([u, 1.25]));
    }
}

#[test]
fn bad_parameters_are_named_errors() {
    let msg = |e: NoiseError| e.to_string();
    assert!(msg(FractalParams::new(0, 1.0, 2.0, 0.5).unwrap_err()).contains("octaves"));
    assert!(msg(FractalParams::new(33, 1.0, 2.0, 0.5).unwrap_err()).contains("octaves"));
    assert!(msg(FractalParams::new(4, f32::NAN, 2.0, 0.5).unwrap_err()).contains("frequency"));
    assert!(msg(FractalParams::new(4, -1.0, 2.0, 0.5).unwrap_err()).contains("frequency"));
    assert!(msg(FractalParams::new(4, 1.0, f32::INFINITY, 0.5).unwrap_err()).contains("lacunarity"));
    assert!(msg(FractalParams::new(4, 1.0, 2.0, f32::NAN).unwrap_err()).contains("gain"));
    assert!(msg(FractalParams::new(32, 1.0, 4.0, 0.5).unwrap_err()).contains("frequency"));
    assert!(msg(FractalParams::new(32, 1.0, 1.0, 20.0).unwrap_err()).contains("gain"));
    assert!(msg(FractalParams::new(3, 1.5, 2.0, 0.5).unwrap().with_period(&[1; 4]).unwrap_err())
        .contains("period"));
    assert!(msg(FractalParams::new(3, 1.0, 2.5, 0.5).unwrap().with_period(&[1; 4]).unwrap_err())
        .contains("period"));
    assert!(msg(FractalParams::thesis(3).unwrap().with_period(&[]).unwrap_err()).contains("period"));
    assert!(msg(FractalParams::thesis(3).unwrap().with_period(&[1 << 23]).unwrap_err()).contains("2^24"));
    assert!(msg(Period::new([0, 4]).unwrap_err()).contains("period"));
    assert!(msg(Period::new([4, u32::MAX]).unwrap_err()).contains("period"));

    let f = Fractal::thesis(1, 3).unwrap();
    let mut out = vec![0.0; 8];
    assert!(
        msg(batch::fill(&f, [0.0; 3], [0.1; 3], [2, 2, 3], &mut out).unwrap_err()).contains("output length")
    );
    assert!(msg(batch::fill(&f, [0.0; 3], [0.1; 3], [2, 0, 4], &mut out).unwrap_err()).contains("grid size"));
    assert!(msg(batch::fill(&f, [f32::NAN, 0.0, 0.0], [0.1; 3], [2, 2, 2], &mut out).unwrap_err())
        .contains("origin.x"));
    assert!(msg(batch::fill(&f, [0.0; 3], [0.1, f32::INFINITY, 0.1], [2, 2, 2], &mut out).unwrap_err())
        .contains("step.y"));
    let huge = usize::MAX / 2;
    assert!(msg(batch::fill(&f, [0.0; 3], [0.1; 3], [huge, huge, 2], &mut out).unwrap_err())
        .contains("overflows"));
    assert!(msg(batch::fill(&f, [0.0; 3], [0.1; 3], [1 << 12, 1 << 12, 1 << 8], &mut out).unwrap_err())
        .contains("2^31"));
}

#[test]
fn non_finite_coordinates_give_zero() {
    let p = Perlin::new(1);
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(p.noise1(bad), 0.0);
        assert_eq!(p.noise2(0.5, bad), 0.0);
        assert_eq!(p.noise3(bad, 0.5, 0.5), 0.0);
        assert_eq!(p.noise4(0.5, 0.5, 0.5, bad), 0.0);
        assert_eq!(p.noise_with_derivative([bad, 0.3, 0.2]), (0.0, [0.0; 3]));
        let f = Fractal::new(p.clone(), FractalParams::new(4, 1.0, 2.0, 0.5).unwrap(), FractalKind::Ridged);
        // Ridged of a zero noise is 1 in every octave.
        assert_eq!(f.sample([bad, 0.0, 0.0]), 1.0);
    }
}

fn grid_points(dims: [usize; 3], o: [f32; 3], s: [f32; 3]) -> impl Iterator<Item = [f32; 3]> {
    (0..dims[2]).flat_map(move |k| {
        (0..dims[1]).flat_map(move |j| {
            (0..dims[0])
                .map(move |i| [o[0] + i as f32 * s[0], o[1] + j as f32 * s[1], o[2] + k as f32 * s[2]])
        })
    })
}

#[test]
fn batch_matches_point_evaluation_and_parallel_matches_serial() {
    let perlin = Perlin::with_axis_seeds([1, 2, 3, 4]);
    let dims = [37, 11, 5];
    let (o, s) = ([-3.3f32, 0.7, 12.1], [0.093f32, 0.21, 0.5]);
    let plain = FractalParams::new(6, 1.0, 2.0, 0.5).unwrap();
    let tiled = FractalParams::new(3, 2.0, 2.0, 0.6).unwrap().with_period(&[4, 4, 4]).unwrap();
    for params in [plain, tiled] {
        for kind in [FractalKind::Thesis, FractalKind::Fbm, FractalKind::Turbulence, FractalKind::Ridged] {
            let f = Fractal::new(perlin.clone(), params, kind);
            let mut out = vec![0.0; dims.iter().product()];
            batch::fill(&f, o, s, dims, &mut out).unwrap();
            for (v, p) in out.iter().zip(grid_points(dims, o, s)) {
                assert!((v - f.sample(p)).abs() < 2e-5, "{kind:?} at {p:?}: {v} vs {}", f.sample(p));
            }
            let mut par = vec![0.0; out.len()];
            batch::fill_par(&f, o, s, dims, &mut par).unwrap();
            assert_eq!(out, par);
        }
    }
    // 2D rows (fast path), and 1D/4D (point API), against the point API.
    for params in [plain, tiled] {
        for kind in [FractalKind::Thesis, FractalKind::Fbm, FractalKind::Turbulence, FractalKind::Ridged] {
            let f = Fractal::new(perlin.clone(), params, kind);
            let (dims, o, s) = ([29usize, 7usize], [-1.7f32, 3.1], [0.131f32, 0.29]);
            let mut out = vec![0.0; 29 * 7];
            batch::fill(&f, o, s, dims, &mut out).unwrap();
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let p = [o[0] + i as f32 * s[0], o[1] + j as f32 * s[1]];
                    let v = out[j * dims[0] + i];
                    assert!((v - f.sample(p)).abs() < 2e-5, "2D {kind:?} at {p:?}: {v} vs {}", f.sample(p));
                }
            }
            let mut par = vec![0.0; out.len()];
            batch::fill_par(&f, o, s, dims, &mut par).unwrap();
            assert_eq!(out, par);
        }
    }
    // Negative and cell-skipping steps exercise the other coefficient-reuse branches.
    let f = Fractal::new(perlin.clone(), plain, FractalKind::Fbm);
    for (o, s) in [([5.0f32, 1.0, 2.0], [-0.07f32, 0.3, 0.2]), ([-2.0, 1.0, 2.0], [1.7, -0.3, 0.2])] {
        let dims = [41, 3, 2];
        let mut out = vec![0.0; 41 * 3 * 2];
        batch::fill(&f, o, s, dims, &mut out).unwrap();
        for (v, p) in out.iter().zip(grid_points(dims, o, s)) {
            assert!((v - f.sample(p)).abs() < 2e-5, "step {s:?} at {p:?}");
        }
        let mut out2 = vec![0.0; 41 * 3];
        batch::fill(&f, [o[0], o[1]], [s[0], s[1]], [41, 3], &mut out2).unwrap();
        for j in 0..3 {
            for i in 0..41 {
                let p = [o[0] + i as f32 * s[0], o[1] + j as f32 * s[1]];
                assert!((out2[j * 41 + i] - f.sample(p)).abs() < 2e-5, "2D step {s:?} at {p:?}");
            }
        }
    }
    // Huge and overflowing coordinates take the per-sample fallback and still agree.
    for ox in [3e9f32, -3e9, 1e38, -2.1e9] {
        let dims = [9, 2, 2];
        let (o, s) = ([ox, 0.3, 0.6], [1e8f32, 0.25, 0.5]);
        let mut out = vec![0.0; 36];
        batch::fill(&f, o, s, dims, &mut out).unwrap();
        for (v, p) in out.iter().zip(grid_points(dims, o, s)) {
            assert!(v.is_finite());
            assert!((v - f.sample(p)).abs() < 2e-5, "huge x {p:?}: {v} vs {}", f.sample(p));
        }
        let mut out2 = vec![0.0; 18];
        batch::fill(&f, [o[0], o[1]], [s[0], s[1]], [9, 2], &mut out2).unwrap();
        for j in 0..2 {
            for i in 0..9 {
                let p = [o[0] + i as f32 * s[0], o[1] + j as f32 * s[1]];
                assert!((out2[j * 9 + i] - f.sample(p)).abs() < 2e-5, "2D huge x {p:?}");
            }
        }
    }
    let mut out1 = vec![0.0; 9];
    batch::fill_par(&f, [0.25], [0.5], [9], &mut out1).unwrap();
    assert_eq!(out1[7], f.sample([0.25 + 7.0 * 0.5]));
    let mut out4 = vec![0.0; 2 * 3 * 2 * 2];
    batch::fill_par(&f, [0.0; 4], [0.5; 4], [2, 3, 2, 2], &mut out4).unwrap();
    assert_eq!(out4[23], f.sample([0.5, 1.0, 0.5, 0.5]));
}

/// The same statistics as the `noise` crate's fBm over the benchmark's grid (6 octaves,
/// lacunarity 2, persistence 0.5, 64³ samples with step 1/16).
#[test]
fn statistics_match_the_noise_crate() {
    use noise::{MultiFractal, NoiseFn};
    let n = 64usize;
    let step = 1.0f32 / 16.0;
    let ours = Fractal::new(Perlin::new(7), FractalParams::new(6, 1.0, 2.0, 0.5).unwrap(), FractalKind::Fbm);
    let theirs = noise::Fbm::<noise::Perlin>::new(7)
        .set_octaves(6)
        .set_frequency(1.0)
        .set_lacunarity(2.0)
        .set_persistence(0.5);
    let mut a = vec![0.0f32; n * n * n];
    batch::fill(&ours, [0.0; 3], [step; 3], [n; 3], &mut a).unwrap();
    let b: Vec<f32> = grid_points([n; 3], [0.0; 3], [step; 3])
        .map(|p| theirs.get([f64::from(p[0]), f64::from(p[1]), f64::from(p[2])]) as f32)
        .collect();
    let stats = |v: &[f32]| {
        let m = v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len() as f64;
        let sd = (v.iter().map(|&x| (f64::from(x) - m).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
        let lo = v.iter().copied().fold(f32::INFINITY, f32::min);
        let hi = v.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        (m, sd, lo, hi)
    };
    let (sa, sb) = (stats(&a), stats(&b));
    println!("renderlab-noise: mean {:.4} std {:.4} range [{:.4}, {:.4}]", sa.0, sa.1, sa.2, sa.3);
    println!("noise crate:     mean {:.4} std {:.4} range [{:.4}, {:.4}]", sb.0, sb.1, sb.2, sb.3);
    assert!(sa.0.abs() < 0.05 && sb.0.abs() < 0.05, "means {} {}", sa.0, sb.0);
    assert!((sa.1 / sb.1 - 1.0).abs() < 0.35, "std {} vs {}", sa.1, sb.1);
    assert!(sa.2 < 0.0 && sa.3 > 0.0 && sa.2 > -1.0 && sa.3 < 1.0);
    assert!(sb.2 < 0.0 && sb.3 > 0.0);
}

proptest! {
    #[test]
    fn any_coordinates_give_a_finite_bounded_value(x in any::<f32>(), y in any::<f32>(), z in any::<f32>(), w in any::<f32>()) {
        let p = Perlin::new(3);
        for v in [p.noise1(x), p.noise2(x, y), p.noise3(x, y, z), p.noise4(x, y, z, w)] {
            prop_assert!(v.is_finite() && v.abs() <= 1.0 + 1e-5);
        }
        let (v, d) = p.noise_with_derivative([x, y, z]);
        prop_assert!(v.is_finite() && d.iter().all(|g| g.is_finite()));
        let f = Fractal::new(p, FractalParams::new(8, 1.0, 2.0, 0.5).unwrap(), FractalKind::Fbm);
        prop_assert!(f.sample([x, y, z]).is_finite());
    }
}
