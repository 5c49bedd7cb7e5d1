//! The EWA footprint: each Jacobian method's error against the exact (f64) derivatives on the
//! thesis scene, operation counts against the thesis, ellipse coefficients and degenerate input.

use glam::DVec2;
use renderlab_texture::ellipse::{jacobian_block, Ellipse, EllipseError, Jacobian, JacobianMethod};
use renderlab_texture::mapping::ops::{measure_row_cost, NoOps, OpRate};
use renderlab_texture::mapping::{Projective, QuadScene};

/// Exact derivatives in f64 at pixel (x, y).
fn exact(p: &Projective, x: f64, y: f64) -> [f64; 4] {
    let m = &p.m;
    let (a, b, c) = (m[0][0], m[1][0], m[2][0]);
    let (d, e, f) = (m[0][1], m[1][1], m[2][1]);
    let (g, h, i) = (m[0][2], m[1][2], m[2][2]);
    let q = g * x + h * y + i;
    let nu = a * x + b * y + c;
    let nv = d * x + e * y + f;
    let q2 = q * q;
    [(a * q - g * nu) / q2, (d * q - g * nv) / q2, (b * q - h * nu) / q2, (e * q - h * nv) / q2]
}

/// Pixels of the thesis scene whose centres lie inside the projected quad, as (x0, y0, w, h,
/// mask) of the bounding block.
fn thesis_block() -> (Projective, i32, i32, usize, usize, Vec<bool>) {
    let s = QuadScene::thesis_default();
    let quad = s.project().unwrap();
    let p = s.mapping().unwrap();
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for q in quad {
        lo = lo.min(q);
        hi = hi.max(q);
    }
    let (x0, y0) = (lo.x.floor() as i32, lo.y.floor() as i32);
    let (w, h) = ((hi.x.ceil() as i32 - x0 + 1) as usize, (hi.y.ceil() as i32 - y0 + 1) as usize);
    let mut mask = Vec::with_capacity(w * h);
    for j in 0..h {
        for i in 0..w {
            let uv = p.map((x0 + i as i32) as f64, (y0 + j as i32) as f64).unwrap();
            mask.push((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y));
        }
    }
    (p, x0, y0, w, h, mask)
}

/// Per-entry maximum of |J − J_exact| relative to the largest exact entry at that pixel.
fn rel_errors(p: &Projective, js: &[Jacobian], x0: i32, y0: i32, w: usize, mask: &[bool]) -> [f64; 4] {
    let mut worst = [0.0f64; 4];
    for (k, (j, inside)) in js.iter().zip(mask).enumerate() {
        if !inside {
            continue;
        }
        let (x, y) = ((x0 + (k % w) as i32) as f64, (y0 + (k / w) as i32) as f64);
        let r = exact(p, x, y);
        let scale = r.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let got = [j.du_dx as f64, j.dv_dx as f64, j.du_dy as f64, j.dv_dy as f64];
        for n in 0..4 {
            worst[n] = worst[n].max((got[n] - r[n]).abs() / scale);
        }
    }
    worst
}

#[test]
fn jacobian_errors_against_exact_derivatives() {
    let (p, x0, y0, w, h, mask) = thesis_block();
    let c = p.coeffs();
    let mut results = Vec::new();
    println!("{:<22} {:>11} {:>11} {:>11} {:>11}", "method", "du/dx", "dv/dx", "du/dy", "dv/dy");
    for m in JacobianMethod::ALL {
        let mut js = vec![Jacobian::default(); w * h];
        jacobian_block(&c, m, x0, y0, w, &mut js, &mut NoOps).unwrap();
        let e = rel_errors(&p, &js, x0, y0, w, &mask);
        println!("{:<22} {:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e}", m.name(), e[0], e[1], e[2], e[3]);
        results.push((m, js, e));
    }
    let get = |m: JacobianMethod| results.iter().find(|r| r.0 == m).unwrap();
    let worst = |e: &[f64; 4]| e.iter().cloned().fold(0.0, f64::max);
    // Analytic: f32 rounding only.
    assert!(worst(&get(JacobianMethod::Analytic).2) < 1e-5);
    assert!(worst(&get(JacobianMethod::AnalyticParallel).2) < 1e-5);
    // Forward differences: the derivative at x + ½, a few per cent on this strongly
    // foreshortened quad (the thesis's scene is ~150 px across with a depth ratio of 1.45).
    let fd = worst(&get(JacobianMethod::ForwardDifference).2);
    assert!(fd > 1e-4 && fd < 0.05, "forward difference error {fd}");
    // The corrected incremental scheme reproduces forward differences up to rounding.
    let (fd_j, ci_j) =
        (&get(JacobianMethod::ForwardDifference).1, &get(JacobianMethod::CorrectedIncremental).1);
    for ((a, b), inside) in fd_j.iter().zip(ci_j).zip(&mask) {
        if *inside {
            assert!(a.max_abs_diff(b) <= 1e-4 * a.max_abs(), "{a:?} vs {b:?}");
        }
    }
    // The printed formulas are wrong in ∂v/∂x (sign) and in both y-derivatives (denominator):
    // their error is far above the forward differences they were meant to equal.
    let te = get(JacobianMethod::ThesisIncremental).2;
    assert!(te[0] < 2.0 * fd, "printed du/dx (2.12) is correct");
    assert!(te[1] > 10.0 * fd, "printed dv/dx sign error must show");
    // Against the analytic values the printed y-denominator (q)(q+G) happens to be no worse
    // than the true forward difference (q)(q+H) — on this scene |G| < |H| — so measure it
    // against what (2.14)/(2.15) claim to equal: the forward differences of (2.11).
    let th_j = &get(JacobianMethod::ThesisIncremental).1;
    let mut dev = [0.0f32; 2];
    for ((a, b), inside) in fd_j.iter().zip(th_j).zip(&mask) {
        if *inside {
            let s = a.max_abs();
            dev[0] = dev[0].max((a.du_dy - b.du_dy).abs() / s);
            dev[1] = dev[1].max((a.dv_dy - b.dv_dy).abs() / s);
        }
    }
    println!("printed (2.14)/(2.15) vs forward differences: {:.3e} {:.3e}", dev[0], dev[1]);
    assert!(dev[0].max(dev[1]) > 1e-3, "printed y-denominator error must show");
    assert!(te[2].max(te[3]) < 0.05);
}

fn rate_eq(r: OpRate, add: f64, sub: f64, mul: f64, div: f64) -> bool {
    (r.add - add).abs() < 1e-9
        && (r.sub - sub).abs() < 1e-9
        && (r.mul - mul).abs() < 1e-9
        && (r.div - div).abs() < 1e-9
}

/// Per-pixel counts (one row; per-row and per-polygon work goes to the set-up). The thesis
/// states 10 mul + 10 add + 4 div + 1 sub for (2.11) and 2 mul + 6 add + 4 div for (2.21).
#[test]
fn jacobian_operation_counts() {
    let c = QuadScene::thesis_default().mapping().unwrap().coeffs();
    println!(
        "{:<22} {:>5} {:>5} {:>5} {:>5}   set-up (add/sub/mul/div)",
        "method", "add", "sub", "mul", "div"
    );
    for m in JacobianMethod::ALL {
        let cost = measure_row_cost(512, 1024, |n, t| {
            let mut js = vec![Jacobian::default(); n];
            jacobian_block(&c, m, 60, 150, n, &mut js, t).unwrap();
        });
        let (p, s) = (cost.per_pixel, cost.setup);
        println!(
            "{:<22} {:>5} {:>5} {:>5} {:>5}   {}/{}/{}/{}",
            m.name(),
            p.add,
            p.sub,
            p.mul,
            p.div,
            s.add,
            s.sub,
            s.mul,
            s.div
        );
        let ok = match m {
            JacobianMethod::ForwardDifference => rate_eq(p, 12.0, 4.0, 12.0, 4.0),
            JacobianMethod::ThesisIncremental => rate_eq(p, 4.0, 0.0, 2.0, 4.0),
            JacobianMethod::CorrectedIncremental => rate_eq(p, 5.0, 0.0, 3.0, 4.0),
            JacobianMethod::Analytic => rate_eq(p, 3.0, 0.0, 5.0, 1.0),
            JacobianMethod::AnalyticParallel => rate_eq(p, 3.0, 0.0, 8.0, 1.0),
        };
        assert!(ok, "{}: {p:?}", m.name());
    }
}

#[test]
fn ellipse_coefficients() {
    let j = Jacobian { du_dx: 0.02, dv_dx: -0.005, du_dy: 0.007, dv_dy: 0.03 };
    let e = Ellipse::from_jacobian(&j).unwrap();
    assert!((e.a - (0.005f32 * 0.005 + 0.03 * 0.03)).abs() < 1e-9);
    assert!((e.b - (-2.0 * (0.02f32 * -0.005 + 0.007 * 0.03))).abs() < 1e-9);
    assert!((e.c - (0.02f32 * 0.02 + 0.007 * 0.007)).abs() < 1e-9);
    // Lagrange identity: AC − B²/4 = F.
    assert!(((e.a * e.c - e.b * e.b / 4.0) - e.f).abs() <= 1e-5 * e.f);
    // The images of the unit pixel circle lie on the ellipse.
    for k in 0..16 {
        let t = k as f32 * std::f32::consts::TAU / 16.0;
        let (du, dv) = (j.du_dx * t.cos() + j.du_dy * t.sin(), j.dv_dx * t.cos() + j.dv_dy * t.sin());
        assert!((e.q(du, dv) - e.f).abs() <= 1e-4 * e.f, "{} vs {}", e.q(du, dv), e.f);
        assert!(e.contains(0.5 * du, 0.5 * dv));
        let ext = e.half_extent();
        assert!(du.abs() <= ext.x * 1.0001 && dv.abs() <= ext.y * 1.0001);
    }
}

#[test]
fn degenerate_footprints_give_typed_errors() {
    let nan = Jacobian { du_dx: f32::NAN, ..Jacobian::default() };
    assert_eq!(Ellipse::from_jacobian(&nan), Err(EllipseError::NonFinite));
    let inf = Jacobian { dv_dy: f32::INFINITY, du_dx: 1.0, ..Jacobian::default() };
    assert_eq!(Ellipse::from_jacobian(&inf), Err(EllipseError::NonFinite));
    let overflow = Jacobian { du_dx: 1e30, dv_dx: 0.0, du_dy: 0.0, dv_dy: 1e30 };
    assert_eq!(Ellipse::from_jacobian(&overflow), Err(EllipseError::NonFinite));
    assert_eq!(Ellipse::from_jacobian(&Jacobian::default()), Err(EllipseError::Degenerate));
    let parallel = Jacobian { du_dx: 0.1, dv_dx: 0.2, du_dy: 0.3, dv_dy: 0.6 };
    assert_eq!(Ellipse::from_jacobian(&parallel), Err(EllipseError::Degenerate));
    // A block whose length is not whole rows, and an empty one.
    let c = QuadScene::thesis_default().mapping().unwrap().coeffs();
    let mut js = vec![Jacobian::default(); 10];
    assert_eq!(
        jacobian_block(&c, JacobianMethod::Analytic, 0, 0, 3, &mut js, &mut NoOps),
        Err(EllipseError::BadBlock { len: 10, width: 3 })
    );
    assert!(jacobian_block(&c, JacobianMethod::Analytic, 0, 0, 0, &mut [], &mut NoOps).is_ok());
    // Rows through the horizon: every method returns; non-finite pixels are rejected later.
    let mut nan_c = c;
    nan_c.i = f32::NAN;
    for coeffs in [c, nan_c] {
        for m in JacobianMethod::ALL {
            let mut js = vec![Jacobian::default(); 64 * 8];
            jacobian_block(&coeffs, m, -5000, -700, 64, &mut js, &mut NoOps).unwrap();
            for j in &js {
                let _ = Ellipse::from_jacobian(j);
            }
        }
    }
}
