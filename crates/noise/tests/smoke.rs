//! The smoke renderer: Beer–Lambert on known densities, the empty volume, the filters, the
//! difference between moving through the noise (Advect) and the thesis's literal `noise + k·t`,
//! determinism across thread counts, and validation messages.

use renderlab_core::glam::Vec3;
use renderlab_noise::smoke::{
    box_interval, build_density, gaussian_filter, median_filter, plume_shape, render_smoke_frame, Animation,
    DensityGrid, SmokeFilter, SmokeParams, SmokeVolume,
};

fn small() -> SmokeParams {
    SmokeParams { width: 40, height: 32, grid: 32, ..SmokeParams::default() }
}

fn error_of(p: SmokeParams) -> String {
    p.validate().expect_err("should be rejected").to_string()
}

/// Pearson correlation of two equally long slices.
fn correlation(a: &[f32], b: &[f32]) -> f64 {
    let n = a.len() as f64;
    let ma = a.iter().map(|&v| f64::from(v)).sum::<f64>() / n;
    let mb = b.iter().map(|&v| f64::from(v)).sum::<f64>() / n;
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (&x, &y) in a.iter().zip(b) {
        let (dx, dy) = (f64::from(x) - ma, f64::from(y) - mb);
        sab += dx * dy;
        saa += dx * dx;
        sbb += dy * dy;
    }
    sab / (saa * sbb).sqrt()
}

fn variance(v: &[f32]) -> f64 {
    let n = v.len() as f64;
    let m = v.iter().map(|&x| f64::from(x)).sum::<f64>() / n;
    v.iter().map(|&x| (f64::from(x) - m).powi(2)).sum::<f64>() / n
}

#[test]
fn empty_volume_shows_the_background_exactly() {
    let p = SmokeParams { density: 0.0, ..small() };
    let img = render_smoke_frame(&p, 0.5).unwrap();
    assert!(img.pixels().iter().all(|&c| c == p.background), "an empty volume must be the background");
    let volume = SmokeVolume::from_density(&p, DensityGrid::new(16, 0.0).unwrap()).unwrap();
    let (l, t) = volume.march(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z, 0.3);
    assert_eq!((l, t), (Vec3::ZERO, 1.0));
    assert!(volume.light_transmittance().values().iter().all(|&v| v == 1.0));
    // Non-finite rays are defined: nothing scattered, nothing absorbed.
    assert_eq!(volume.march(Vec3::NAN, Vec3::Z, 0.0), (Vec3::ZERO, 1.0));
    assert_eq!(volume.march(Vec3::ZERO, Vec3::new(f32::INFINITY, 0.0, 0.0), f32::NAN), (Vec3::ZERO, 1.0));
}

#[test]
fn uniform_slab_follows_beer_lambert() {
    let p = SmokeParams { absorption: 0.8, scattering: 1.7, ..small() };
    let rho = 0.6;
    let volume = SmokeVolume::from_density(&p, DensityGrid::new(32, rho).unwrap()).unwrap();
    let sigma_t = p.extinction();
    let rays = [
        (Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z),
        (Vec3::new(-3.0, 0.4, 2.5), Vec3::new(1.0, -0.1, -0.8).normalize()),
        (Vec3::new(0.2, -4.0, 0.1), Vec3::new(0.05, 1.0, 0.02).normalize()),
    ];
    for (o, d) in rays {
        let (t0, t1) = box_interval(o, d).expect("ray hits the box");
        for offset in [0.0, 0.37, 0.99] {
            let (l, t) = volume.march(o, d, offset);
            let want = (-sigma_t * rho * (t1 - t0)).exp();
            assert!((t - want).abs() <= 1e-4 * want.max(1e-3), "{o} {d}: T = {t}, Beer–Lambert {want}");
            assert!(l.is_finite() && l.min_element() > 0.0, "a lit slab scatters light: {l}");
        }
    }
    // The light grid: light straight down from above, so a voxel at height y sees 1 − y of slab.
    let p_up = SmokeParams { light_direction: Vec3::Y, ..p };
    let volume = SmokeVolume::from_density(&p_up, DensityGrid::new(32, rho).unwrap()).unwrap();
    let light = volume.light_transmittance();
    for (i, j, k) in [(0, 0, 0), (3, 7, 2), (8, 15, 9)] {
        let c = light.centre(i, j, k);
        let want = (-sigma_t * rho * (1.0 - c.y)).exp();
        let got = light.get(i, j, k);
        assert!((got - want).abs() < 1e-4, "light at {c}: {got} vs {want}");
    }
}

/// A deterministic pseudo-random field in [0, 1) with a zero margin of `margin` voxels.
fn speckled(n: u32, margin: usize) -> DensityGrid {
    let nn = n as usize;
    let mut g = DensityGrid::new(n, 0.0).unwrap();
    for (idx, v) in g.values_mut().iter_mut().enumerate() {
        let (i, j, k) = (idx % nn, (idx / nn) % nn, idx / (nn * nn));
        let inside = [i, j, k].iter().all(|&c| c >= margin && c < nn - margin);
        let h = (idx as u32).wrapping_mul(2_654_435_761).rotate_left(13).wrapping_mul(0x85EB_CA77);
        *v = if inside { (h >> 8) as f32 / (1u32 << 24) as f32 } else { 0.0 };
    }
    g
}

#[test]
fn gaussian_filter_keeps_the_total_and_lowers_the_variance() {
    let g = speckled(24, 4);
    let f = gaussian_filter(&g, 1.2).unwrap();
    let (s0, s1) = (g.sum(), f.sum());
    assert!(((s1 - s0) / s0).abs() < 1e-5, "sum {s0} → {s1}");
    let (v0, v1) = (variance(g.values()), variance(f.values()));
    assert!(v1 < 0.5 * v0, "variance {v0} → {v1}");
    // A constant field stays constant (the kernel is normalised, edges are clamped).
    let c = gaussian_filter(&DensityGrid::new(8, 0.25).unwrap(), 2.0).unwrap();
    assert!(c.values().iter().all(|&v| (v - 0.25).abs() < 1e-6));
    assert!(gaussian_filter(&g, f32::NAN).unwrap_err().to_string().contains("sigma"));
    assert!(gaussian_filter(&g, 0.0).unwrap_err().to_string().contains("sigma"));
}

#[test]
fn median_filter_removes_specks_and_keeps_plateaus() {
    let mut g = DensityGrid::new(9, 0.0).unwrap();
    g.values_mut()[(4 * 9 + 4) * 9 + 4] = 5.0; // one bright voxel
    let m = median_filter(&g);
    assert!(m.values().iter().all(|&v| v == 0.0), "a lone speck is removed");
    let c = median_filter(&DensityGrid::new(6, 0.5).unwrap());
    assert!(c.values().iter().all(|&v| v == 0.5));
    let s = speckled(16, 2);
    assert!(variance(median_filter(&s).values()) < variance(s.values()));
}

/// Density divided by the plume envelope (the animated noise part), where the envelope is
/// large enough to divide by.
fn pattern(p: &SmokeParams, g: &DensityGrid) -> Vec<Option<f32>> {
    let n = g.resolution() as usize;
    let mut out = Vec::with_capacity(n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let s = plume_shape(p, g.centre(i, j, k));
                out.push((s > 0.05).then(|| g.get(i, j, k) / (s * p.density)));
            }
        }
    }
    out
}

#[test]
fn advection_changes_the_shape_while_the_thesis_formula_only_brightens() {
    let (t0, t1) = (0.0, 1.5);
    // The thesis's literal animate(noise, t) = noise + k·t.
    let k = 0.1;
    let lit = SmokeParams {
        filter: SmokeFilter::None,
        animation: Animation::ThesisLiteral { animation_factor: k },
        ..small()
    };
    let (a, b) = (build_density(&lit, t0).unwrap(), build_density(&lit, t1).unwrap());
    let (pa, pb) = (pattern(&lit, &a), pattern(&lit, &b));
    let mut unclamped = 0;
    for (x, y) in pa.iter().zip(&pb) {
        if let (Some(x), Some(y)) = (x, y) {
            if *x > 1e-3 && *y < 1.0 - 1e-3 {
                // Neither clamped: the pattern is identical up to the uniform offset k·Δt.
                assert!((y - x - k * (t1 - t0)).abs() < 1e-4, "{x} → {y}");
                unclamped += 1;
            }
        }
    }
    assert!(unclamped > 1000, "too few unclamped voxels ({unclamped})");
    assert!(b.sum() > a.sum(), "noise + k·t with k > 0 only brightens");
    let c_lit = correlation(a.values(), b.values());
    assert!(c_lit > 0.95, "literal frames should correlate: {c_lit}");

    // Moving through the noise domain changes the shape.
    let adv = SmokeParams { filter: SmokeFilter::None, animation: Animation::Advect, ..small() };
    let (a, b) = (build_density(&adv, t0).unwrap(), build_density(&adv, t1).unwrap());
    let c_adv = correlation(a.values(), b.values());
    assert!(c_adv < 0.8 && c_adv < c_lit - 0.1, "advected frames should decorrelate: {c_adv} vs {c_lit}");
    // …and the pattern is not the old one plus a constant.
    let diffs: Vec<f32> = pattern(&adv, &a)
        .iter()
        .zip(&pattern(&adv, &b))
        .filter_map(|(x, y)| Some(y.as_ref()? - x.as_ref()?))
        .collect();
    assert!(variance(&diffs).sqrt() > 0.1, "advection should move the pattern, not offset it");
    // Close frames stay coherent (smooth motion, no flicker).
    let c = build_density(&adv, t0 + 1.0 / 24.0).unwrap();
    assert!(correlation(a.values(), c.values()) > 0.9);
}

#[test]
fn frames_are_bit_identical_for_any_thread_count() {
    let p = SmokeParams { width: 36, height: 28, grid: 24, ..SmokeParams::default() };
    let render = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_smoke_frame(&p, 0.75).unwrap())
    };
    let one = render(1);
    assert_eq!(one, render(3));
    let med = SmokeParams { filter: SmokeFilter::Median3, ..p };
    let r = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| build_density(&med, 0.2))
    };
    assert_eq!(r(1).unwrap(), r(4).unwrap());
}

#[test]
fn the_plume_is_visible_and_the_corners_are_background() {
    let p = small();
    let img = render_smoke_frame(&p, 0.0).unwrap();
    let (w, h) = img.size();
    for (x, y) in [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)] {
        assert_eq!(img.get(x, y), p.background, "corner ({x}, {y})");
    }
    let lit = img.pixels().iter().filter(|c| (**c - p.background).max_element() > 0.05).count();
    assert!(lit > (w * h / 20) as usize, "only {lit} smoke pixels");
    assert!(img.pixels().iter().all(|c| c.is_finite()));
}

#[test]
fn validation_names_the_parameter() {
    let p = small();
    assert!(p.validate().is_ok());
    assert!(error_of(SmokeParams { width: 0, ..p }).contains("grid size"));
    assert!(error_of(SmokeParams { grid: 2, ..p }).contains("grid ="));
    assert!(error_of(SmokeParams { grid: 100_000, ..p }).contains("grid ="));
    assert!(error_of(SmokeParams { octaves: 0, ..p }).contains("octaves"));
    assert!(error_of(SmokeParams { frequency: f32::NAN, ..p }).contains("frequency"));
    assert!(error_of(SmokeParams { density: f32::INFINITY, ..p }).contains("density"));
    assert!(error_of(SmokeParams { plume_radius: 0.0, ..p }).contains("plume_radius"));
    assert!(error_of(SmokeParams { swirl: -1.0, ..p }).contains("swirl"));
    assert!(error_of(SmokeParams { filter: SmokeFilter::Gaussian { sigma: 100.0 }, ..p }).contains("sigma"));
    assert!(error_of(SmokeParams { absorption: f32::NAN, ..p }).contains("absorption"));
    assert!(error_of(SmokeParams { scattering: -1.0, ..p }).contains("scattering"));
    assert!(error_of(SmokeParams { light_direction: Vec3::ZERO, ..p }).contains("light_direction"));
    assert!(error_of(SmokeParams { light_direction: Vec3::NAN, ..p }).contains("light_direction"));
    assert!(error_of(SmokeParams { step: 0.0, ..p }).contains("step"));
    assert!(error_of(SmokeParams { shadow_steps: 0, ..p }).contains("shadow_steps"));
    let k = Animation::ThesisLiteral { animation_factor: f32::NAN };
    assert!(error_of(SmokeParams { animation: k, ..p }).contains("animation_factor"));
    assert!(error_of(SmokeParams { time_step: 0.0, ..p }).contains("time_step"));
    assert!(render_smoke_frame(&p, f32::NAN).unwrap_err().to_string().starts_with("t ="));
    assert!(render_smoke_frame(&p, 1e9).unwrap_err().to_string().starts_with("t ="));
    assert!(DensityGrid::new(1 << 20, 0.0).unwrap_err().to_string().contains("grid"));
}
