//! The test field, its maps, view directions and the error measure shared by the relief
//! integration tests.

#![allow(dead_code)]

use glam::{Vec2, Vec3};
use renderlab_core::counter::NoCount;
use renderlab_core::Image;
use renderlab_relief::maps::complexity::{complexity_map, ComplexityCodes, ComplexityParams};
use renderlab_relief::maps::cone::{ConeKind, ConeMap};
use renderlab_relief::maps::packed::PackedRelief;
use renderlab_relief::maps::pyramid::DepthPyramid;
use renderlab_relief::march::exact::exact_hit;
use renderlab_relief::{HeightField, ReliefInputs, ReliefTechnique};

/// Relief depth of the test field (UV units per unit depth).
pub const SCALE: f32 = 0.06;

/// A bumpy, bricky height map with sharp edges (mortar) and smooth domes (bricks).
pub fn heights(w: u32, h: u32) -> Image<f32> {
    Image::from_fn(w, h, |x, y| {
        let bx = (x + if (y / 8) % 2 == 0 { 0 } else { 8 }) % 16;
        let by = y % 8;
        if bx == 0 || by == 0 {
            0.1
        } else {
            let fx = (x as f32 * 0.3).sin() * 0.5 + 0.5;
            let fy = (y as f32 * 0.45).cos() * 0.5 + 0.5;
            0.6 + 0.35 * fx * fy
        }
    })
}

/// The field with every map a technique may read.
pub struct Fixture {
    pub field: HeightField,
    pub complexity: Image<f32>,
    pub codes: Option<ComplexityCodes>,
    pub cone: ConeMap,
    pub packed: Option<PackedRelief>,
    pub pyramid: DepthPyramid,
}

impl Fixture {
    /// A `w × h` field, a relaxed cone map of `cone_size`, and the packed map when `packed`.
    pub fn new(w: u32, h: u32, cone_size: u32, packed: bool) -> Fixture {
        let img = heights(w, h);
        let field = HeightField::from_height(&img);
        let cone = ConeMap::build(&field, ConeKind::Relaxed, cone_size);
        let packed = packed.then(|| PackedRelief::build(&field, Some(&cone)));
        let pyramid = DepthPyramid::build(&field);
        let complexity = complexity_map(&img, &ComplexityParams::default());
        Fixture { codes: ComplexityCodes::new(&complexity), complexity, field, cone, packed, pyramid }
    }

    /// The technique inputs over this fixture.
    pub fn inputs(&self) -> ReliefInputs<'_> {
        ReliefInputs {
            height: &self.field,
            height_scale: SCALE,
            complexity: &self.complexity,
            complexity_codes: self.codes.as_ref(),
            cone: Some(&self.cone),
            packed: self.packed.as_ref(),
            pyramid: Some(&self.pyramid),
        }
    }
}

/// The tangent-space view direction `theta_deg` from the normal, at azimuth `phi` (radians).
pub fn view(theta_deg: f32, phi: f32) -> Vec3 {
    let a = theta_deg.to_radians();
    Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos())
}

/// Mean UV error in texels (of a 64-texel-wide field) of `t` against the exact hit, over `n`
/// fixed rays at polar angle `theta` (degrees).
pub fn mean_error<T: ReliefTechnique>(fx: &Fixture, t: &T, theta: f32, n: usize) -> f32 {
    let inp = fx.inputs();
    let mut sum = 0.0;
    for i in 0..n {
        let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.754_877).fract());
        let v = view(theta, i as f32 * 2.4);
        let got = t.trace(&inp, uv, v, &mut NoCount).uv;
        let (exact, _) = exact_hit(&fx.field, SCALE, uv, v);
        sum += ((got - exact) * 64.0).length();
    }
    sum / n as f32
}
