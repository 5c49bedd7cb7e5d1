//! The water renderer: Fresnel limits, the flat-sea mirror, analytic normals, the sky above
//! the horizon, determinism across thread counts, animation, and validation messages.

use renderlab_core::glam::Vec3;
use renderlab_core::Image;
use renderlab_noise::water::{
    fresnel_f0, fresnel_schlick, render_water_frame, sky, WaterParams, WaterSurface,
};

fn small() -> WaterParams {
    WaterParams { width: 48, height: 32, ..WaterParams::default() }
}

fn max_diff(a: &Image<Vec3>, b: &Image<Vec3>) -> f32 {
    a.pixels().iter().zip(b.pixels()).map(|(p, q)| (*p - *q).abs().max_element()).fold(0.0, f32::max)
}

#[test]
fn fresnel_is_f0_at_normal_incidence_and_one_at_grazing() {
    let f0 = fresnel_f0();
    assert!((f0 - 0.0201).abs() < 5e-4, "F0 = {f0}");
    assert!((fresnel_schlick(1.0) - f0).abs() < 1e-7);
    assert!((fresnel_schlick(0.0) - 1.0).abs() < 1e-6);
    assert!(fresnel_schlick(0.01) > 0.9);
    // Monotone: more grazing reflects more.
    let mut prev = 2.0;
    for i in 0..=100 {
        let f = fresnel_schlick(i as f32 / 100.0);
        assert!(f <= prev, "not decreasing at cos = {}", i as f32 / 100.0);
        prev = f;
    }
    assert_eq!(fresnel_schlick(f32::NAN), 1.0);
}

#[test]
fn flat_sea_is_a_mirror_of_the_sky() {
    // No waves, no body colour, no haze: every water pixel is F · sky(mirrored ray).
    let p = WaterParams {
        amplitude: 0.0,
        water_color: Vec3::ZERO,
        haze_distance: 1e30,
        pitch_deg: 20.0,
        ..small()
    };
    let img = render_water_frame(&p, 1.25).unwrap();
    let cam = p.camera();
    let mut water = 0;
    for y in 0..p.height {
        for x in 0..p.width {
            let d = cam.ray_direction(x as f32 + 0.5, y as f32 + 0.5);
            if d.z >= 0.0 {
                continue;
            }
            water += 1;
            let mirrored = Vec3::new(d.x, d.y, -d.z);
            let want = sky(&p, mirrored) * fresnel_schlick(-d.z);
            let got = img.get(x, y);
            assert!((got - want).abs().max_element() < 1e-5, "({x}, {y}): {got} vs {want}");
        }
    }
    assert!(water > 100, "the camera should see water");
}

#[test]
fn flat_sea_colour_depends_only_on_the_view_angle() {
    // Sun below the horizon: the sky has no azimuthal feature, so a flat sea's colour is a
    // function of the view elevation alone. With pitch 0 the image is left–right symmetric
    // and, along the centre column, the colour changes only with the row.
    let p =
        WaterParams { amplitude: 0.0, pitch_deg: 0.0, sun_direction: Vec3::new(0.0, 1.0, -0.5), ..small() };
    let a = render_water_frame(&p, 0.0).unwrap();
    let b = render_water_frame(&p, 3.0).unwrap();
    assert_eq!(a, b, "a flat sea does not change in time");
    let w = p.width;
    for y in 0..p.height {
        for x in 0..w / 2 {
            let (l, r) = (a.get(x, y), a.get(w - 1 - x, y));
            assert!((l - r).abs().max_element() < 1e-6, "row {y}: {l} vs {r}");
        }
    }
    // And with waves the symmetry breaks (the test can fail).
    let wavy = render_water_frame(&WaterParams { amplitude: 0.8, ..p }, 0.0).unwrap();
    let asym = (0..p.height)
        .flat_map(|y| (0..w / 2).map(move |x| (x, y)))
        .map(|(x, y)| (wavy.get(x, y) - wavy.get(w - 1 - x, y)).abs().max_element())
        .fold(0.0, f32::max);
    assert!(asym > 1e-3, "waves should break the mirror symmetry");
}

#[test]
fn normals_are_unit_and_tilt_against_the_gradient() {
    let s = WaterSurface::new(&WaterParams::default()).unwrap();
    let mut tilted = 0;
    for i in 0..200 {
        let (x, y, t) = (i as f32 * 0.37 - 20.0, (i * 7 % 50) as f32 * 0.41, i as f32 * 0.05);
        let (h, g) = s.height_and_gradient(x, y, t);
        let n = s.normal(x, y, t);
        assert!((n.length() - 1.0).abs() < 1e-5, "|n| = {}", n.length());
        assert!(n.z > 0.0);
        let gv = Vec3::new(g[0], g[1], 0.0);
        if gv.length() > 1e-3 {
            assert!(n.dot(gv) < 0.0, "normal leans uphill at ({x}, {y})");
            tilted += 1;
        }
        // The analytic gradient matches central differences of the height.
        let e = 1e-3;
        let fx = (s.height_and_gradient(x + e, y, t).0 - s.height_and_gradient(x - e, y, t).0) / (2.0 * e);
        let fy = (s.height_and_gradient(x, y + e, t).0 - s.height_and_gradient(x, y - e, t).0) / (2.0 * e);
        let tol = 2e-2 * (1.0 + g[0].abs().max(g[1].abs()));
        assert!(
            (fx - g[0]).abs() < tol && (fy - g[1]).abs() < tol,
            "({x}, {y}): {g:?} vs ({fx}, {fy}), h = {h}"
        );
    }
    assert!(tilted > 150, "most points should have a slope");
    assert_eq!(s.height_and_gradient(f32::NAN, 0.0, 0.0), (0.0, [0.0, 0.0]));
    assert_eq!(s.height_and_gradient(0.0, 0.0, f32::INFINITY), (0.0, [0.0, 0.0]));
}

#[test]
fn frames_are_deterministic_for_any_thread_count_and_move_in_time() {
    let p = small();
    let render = |threads: usize, t: f32| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_water_frame(&p, t).unwrap())
    };
    let one = render(1, 0.5);
    let three = render(3, 0.5);
    let bits = |img: &Image<Vec3>| {
        img.pixels().iter().flat_map(|c| c.to_array().map(f32::to_bits)).collect::<Vec<_>>()
    };
    assert_eq!(bits(&one), bits(&three));
    assert!(one.pixels().iter().all(|c| c.is_finite() && c.min_element() >= 0.0));
    let next = render(2, 0.5 + p.time_step);
    assert!(max_diff(&one, &next) > 1e-3, "consecutive frames should differ");
    // Waves travel: with evolution 0 the frame at t + dt is not the frame at t either.
    let rigid = WaterParams { evolution: 0.0, ..p };
    let a = render_water_frame(&rigid, 0.0).unwrap();
    let b = render_water_frame(&rigid, 0.25).unwrap();
    assert!(max_diff(&a, &b) > 1e-3, "the wind should move the waves");
}

#[test]
fn pixels_above_the_horizon_see_the_sky() {
    let p = WaterParams { pitch_deg: 2.0, ..small() };
    let img = render_water_frame(&p, 2.0).unwrap();
    let cam = p.camera();
    let mut above = 0;
    for y in 0..p.height {
        for x in 0..p.width {
            let d = cam.ray_direction(x as f32 + 0.5, y as f32 + 0.5);
            if d.z >= 0.0 {
                above += 1;
                assert_eq!(img.get(x, y), sky(&p, d), "({x}, {y})");
            }
        }
    }
    assert!(above > p.width as usize * 4, "the horizon should be in view");
    // The sea is darker than the sky overhead on average (it is not just sky).
    let bottom = img.row(p.height - 1).iter().map(|c| c.y).sum::<f32>();
    let top = img.row(0).iter().map(|c| c.y).sum::<f32>();
    assert!(bottom < top);
}

#[test]
fn validation_names_the_parameter() {
    let base = small();
    let cases: Vec<(WaterParams, &str)> = vec![
        (WaterParams { width: 0, ..base }, "grid size"),
        (WaterParams { height: 100_000, ..base }, "grid size"),
        (WaterParams { time_step: 0.0, ..base }, "time_step"),
        (WaterParams { time_step: f32::NAN, ..base }, "time_step"),
        (WaterParams { wind: [f32::INFINITY, 0.0], ..base }, "wind"),
        (WaterParams { evolution: -1.0, ..base }, "evolution"),
        (WaterParams { octaves: 0, ..base }, "octaves"),
        (WaterParams { octaves: 40, ..base }, "octaves"),
        (WaterParams { wavelength: 0.0, ..base }, "wavelength"),
        (WaterParams { amplitude: f32::NAN, ..base }, "amplitude"),
        (WaterParams { amplitude: -1.0, ..base }, "amplitude"),
        (WaterParams { choppiness: 0.9, ..base }, "choppiness"),
        (WaterParams { camera_height: 0.0, ..base }, "camera_height"),
        (WaterParams { pitch_deg: 95.0, ..base }, "pitch_deg"),
        (WaterParams { fov_y_deg: 0.0, ..base }, "fov_y_deg"),
        (WaterParams { sun_direction: Vec3::ZERO, ..base }, "sun_direction"),
        (WaterParams { sun_direction: Vec3::new(f32::NAN, 1.0, 1.0), ..base }, "sun_direction"),
        (WaterParams { water_color: Vec3::new(2.0, 0.0, 0.0), ..base }, "water_color"),
        (WaterParams { haze_distance: f32::INFINITY, ..base }, "haze_distance"),
    ];
    for (p, name) in cases {
        let e = p.validate().unwrap_err().to_string();
        assert!(e.contains(name), "expected '{name}' in: {e}");
        assert!(render_water_frame(&p, 0.0).is_err());
    }
    assert!(base.validate().is_ok());
    for t in [f32::NAN, f32::INFINITY, 1e9] {
        let e = render_water_frame(&base, t).unwrap_err().to_string();
        assert!(e.starts_with("t = "), "{e}");
    }
}
