//! Composite parts shared by the built-in scenes: columns, vases, bowls, bollards, lamp
//! glasses and hulls, each one mesh in its own object space resting on y = 0.

use crate::shapes::{cuboid, lathe, translated, CuboidUv, MeshBuilder};
use glam::{Vec2, Vec3};
use renderlab_core::Mesh;

/// A column of total height `height` and shaft radius `r`: square plinth, a rounded base
/// moulding, a shaft tapering by a sixth (fluted with `flutes` channels when non-zero),
/// a flared capital and a square abacus. `segments` around and `rings` along the shaft
/// set its tessellation (the budget of the scene).
pub fn column(height: f32, r: f32, flutes: u32, segments: u32, rings: u32) -> Mesh {
    let p = Vec2::new;
    let plinth_h = 0.06 * height;
    let abacus_h = 0.05 * height;
    let base_h = 0.04 * height;
    let cap_h = 0.06 * height;
    let shaft0 = plinth_h + base_h;
    let shaft1 = height - abacus_h - cap_h;
    let mut b = MeshBuilder::default();
    b.append(&cuboid(
        Vec3::new(0.0, plinth_h * 0.5, 0.0),
        Vec3::new(1.35 * r, plinth_h * 0.5, 1.35 * r),
        CuboidUv::Repeat(0.5),
    ));
    // Base moulding: a half-round torus profile from the plinth to the shaft.
    let torus_profile: Vec<Vec2> = (0..=8)
        .map(|i| {
            let a = std::f32::consts::PI * (i as f32 / 8.0 - 0.5);
            p(r * 1.05 + 0.15 * r * a.cos(), plinth_h + base_h * 0.5 + base_h * 0.5 * a.sin())
        })
        .collect();
    // Shaft with entasis (a slight swelling) and taper.
    let shaft: Vec<Vec2> = (0..=rings)
        .map(|i| {
            let t = i as f32 / rings as f32;
            let radius = r * (1.0 - t / 6.0 + 0.03 * (std::f32::consts::PI * t).sin());
            p(radius, shaft0 + t * (shaft1 - shaft0))
        })
        .collect();
    let top_r = shaft.last().map_or(r, |s| s.x);
    let capital: Vec<Vec2> = (0..=6)
        .map(|i| {
            let t = i as f32 / 6.0;
            p(top_r + (1.3 * r - top_r) * t.powf(0.6), shaft1 + t * cap_h)
        })
        .collect();
    let pieces = vec![
        vec![p(0.0, plinth_h), torus_profile[0]],
        torus_profile.clone(),
        vec![torus_profile[8], shaft[0]],
        shaft,
        capital.clone(),
        vec![capital[6], p(0.0, shaft1 + cap_h)],
    ];
    let flute = (flutes > 0).then_some((flutes, 0.06, &[3usize][..]));
    b.append(&lathe(&pieces, segments, flute));
    b.append(&cuboid(
        Vec3::new(0.0, height - abacus_h * 0.5, 0.0),
        Vec3::new(1.4 * r, abacus_h * 0.5, 1.4 * r),
        CuboidUv::Repeat(0.5),
    ));
    b.finish()
}

/// A closed solid vase of height `h` (an amphora profile), for glass or bronze.
pub fn vase(h: f32, segments: u32, rings: u32) -> Mesh {
    let profile: Vec<Vec2> = (0..=rings)
        .map(|i| {
            let t = i as f32 / rings as f32;
            // Belly at 40 % height, neck at 80 %, lip at the top.
            let belly = (-((t - 0.4) / 0.25).powi(2)).exp();
            let lip = (-((t - 0.97) / 0.05).powi(2)).exp();
            let r = h * (0.12 + 0.22 * belly + 0.06 * lip);
            Vec2::new(r, t * h)
        })
        .collect();
    let bottom = vec![Vec2::new(0.0, 0.0), profile[0]];
    let top = vec![profile[rings as usize], Vec2::new(0.0, h)];
    lathe(&[bottom, profile, top], segments, None)
}

/// A closed shallow bowl on a short foot (a brazier or fountain dish): outer radius `r`.
pub fn bowl(r: f32, segments: u32) -> Mesh {
    let p = Vec2::new;
    let outer: Vec<Vec2> = (0..=8)
        .map(|i| {
            let a = std::f32::consts::FRAC_PI_2 * i as f32 / 8.0;
            p(0.3 * r + 0.7 * r * a.sin(), 0.15 * r + 0.35 * r * (1.0 - a.cos()))
        })
        .collect();
    let rim = p(r * 0.92, 0.5 * r);
    let inner: Vec<Vec2> = (0..=8)
        .rev()
        .map(|i| {
            let a = std::f32::consts::FRAC_PI_2 * i as f32 / 8.0;
            p(0.85 * r * a.sin(), 0.25 * r + 0.25 * r * (1.0 - a.cos()))
        })
        .collect();
    let pieces = vec![
        vec![p(0.0, 0.0), p(0.3 * r, 0.0)],
        vec![p(0.3 * r, 0.0), outer[0]],
        outer.clone(),
        vec![outer[8], rim, inner[0]],
        inner,
    ];
    // The profile ends on the axis inside the dish: the solid is closed.
    lathe(&pieces, segments, None)
}

/// A mooring bollard of height `h`: a waisted post with a domed cap.
pub fn bollard(h: f32, segments: u32) -> Mesh {
    let p = Vec2::new;
    let body: Vec<Vec2> = (0..=10)
        .map(|i| {
            let t = i as f32 / 10.0;
            p(h * (0.22 - 0.06 * (std::f32::consts::PI * t).sin()), t * 0.8 * h)
        })
        .collect();
    let cap: Vec<Vec2> = (0..=6)
        .map(|i| {
            let a = std::f32::consts::FRAC_PI_2 * i as f32 / 6.0;
            p(0.26 * h * a.cos(), 0.8 * h + 0.2 * h * a.sin())
        })
        .map(|q| p(if q.x < 1e-5 { 0.0 } else { q.x }, q.y))
        .collect();
    lathe(&[vec![p(0.0, 0.0), body[0]], body.clone(), vec![body[10], cap[0]], cap], segments, None)
}

/// A lamp post of height `h` (a slim cylinder with a collar) without its glass.
pub fn lamp_post(h: f32, segments: u32) -> Mesh {
    let p = Vec2::new;
    lathe(
        &[
            vec![p(0.0, 0.0), p(0.12, 0.0)],
            vec![p(0.12, 0.0), p(0.12, 0.3)],
            vec![p(0.12, 0.3), p(0.05, 0.4)],
            vec![p(0.05, 0.4), p(0.05, h - 0.1)],
            vec![p(0.05, h - 0.1), p(0.1, h - 0.1)],
            vec![p(0.1, h - 0.1), p(0.1, h)],
            vec![p(0.1, h), p(0.0, h)],
        ],
        segments,
        None,
    )
}

/// A boat hull: a half-ellipsoid closed by a flat deck, `length` along X.
pub fn hull(length: f32, beam: f32, depth: f32, segments: u32, rings: u32) -> Mesh {
    // A lathe of the unit half-sphere under y = 0 (with deck), then stretched.
    let bottom: Vec<Vec2> = (0..=rings)
        .map(|i| {
            let a = std::f32::consts::FRAC_PI_2 * i as f32 / rings as f32;
            Vec2::new(if i == 0 { 0.0 } else { a.sin() }, -a.cos())
        })
        .collect();
    let deck = vec![Vec2::new(1.0, 0.0), Vec2::new(0.0, 0.0)];
    let mut m = lathe(&[bottom, deck], segments, None);
    let s = Vec3::new(length * 0.5, depth, beam * 0.5);
    for v in &mut m.vertices {
        v.position *= s;
        v.normal = (v.normal / s).normalize_or_zero();
    }
    m.compute_tangents();
    translated(m, Vec3::ZERO)
}
