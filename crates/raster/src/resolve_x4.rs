//! [`resolve_shade`](crate::resolve::resolve_shade) for four neighbouring pixels of one
//! triangle at once, in AVX2 lanes (f64 where the scalar resolve computes in f64, f32 where
//! it computes in f32), for triangles whose tangent frame is constant. Every lane performs
//! the scalar resolve's operations in the same order, without fused multiply-adds, so the
//! points are bit-identical to it (tested through the streaming raster's equality with the
//! G-buffer).

use crate::resolve::FrameConstants;
use crate::setup::{TriangleSetup, INV_W, POSITION, UV};
use glam::{Mat3, Vec2, Vec3};
use renderlab_core::ShadePoint;
use std::arch::x86_64::*;

/// What is constant over a flat-framed triangle for [`resolve_x4`]: the frame's transpose
/// (world → tangent) and the light in tangent space.
pub(crate) struct FlatConstants {
    to_tangent: Mat3,
    light_ts: Vec3,
}

impl FlatConstants {
    /// For a triangle with the constant frame `tbn`.
    pub fn new(tbn: Mat3, frame: &FrameConstants) -> Self {
        let to_tangent = tbn.transpose();
        Self { to_tangent, light_ts: to_tangent * frame.to_light }
    }
}

/// Pixels `x0 .. x0 + 4` of row `y` on triangle `s` (whose frame is constant): each lane's
/// point, `None` where the scalar resolve gives none.
///
/// # Safety
///
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn resolve_x4(
    s: &TriangleSetup,
    k: &FlatConstants,
    x0: u32,
    y: u32,
    frame: &FrameConstants,
) -> [Option<ShadePoint>; 4] {
    let px = _mm256_add_pd(
        _mm256_set_pd(x0 as f64 + 3.0, x0 as f64 + 2.0, x0 as f64 + 1.0, x0 as f64),
        _mm256_set1_pd(0.5),
    );
    let py = _mm256_set1_pd(y as f64 + 0.5);
    let splat = _mm256_set1_pd;
    let plane = |i: usize| {
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(splat(s.dx[i]), px), _mm256_mul_pd(splat(s.dy[i]), py)), splat(s.c[i]))
    };
    let q = plane(INV_W);
    let valid_q = _mm256_cmp_pd::<_CMP_GT_OQ>(q, _mm256_setzero_pd());
    let w = _mm256_div_pd(splat(1.0), q);
    let u = _mm256_mul_pd(plane(UV), w);
    let v = _mm256_mul_pd(plane(UV + 1), w);
    let d = |a: usize| {
        // (∂h − a·∂q)·w for the x or y derivative table `t`.
        move |t: &[f64; crate::setup::PLANES], val| _mm256_mul_pd(_mm256_sub_pd(splat(t[a]), _mm256_mul_pd(val, splat(t[INV_W]))), w)
    };
    let (du, dv) = (d(UV), d(UV + 1));
    let (dudx, dvdx) = (du(&s.dx, u), dv(&s.dx, v));
    let (dudy, dvdy) = (du(&s.dy, u), dv(&s.dy, v));
    let pos = [0, 1, 2].map(|c| _mm256_mul_pd(plane(POSITION + c), w));
    let eye = [frame.eye.x, frame.eye.y, frame.eye.z];
    let to_eye = [0, 1, 2].map(|c| _mm256_cvtpd_ps(_mm256_sub_pd(splat(eye[c]), pos[c])));
    let sq = |a: __m128| _mm_mul_ps(a, a);
    let depth = _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(sq(to_eye[0]), sq(to_eye[1])), sq(to_eye[2])));
    let recip = _mm_div_ps(_mm_set1_ps(1.0), depth);
    let view = to_eye.map(|c| _mm_mul_ps(c, recip));
    let t = &k.to_tangent;
    let view_ts = [0, 1, 2].map(|c| {
        let col = |m: Vec3| _mm_set1_ps(m[c]);
        _mm_add_ps(
            _mm_add_ps(_mm_mul_ps(col(t.x_axis), view[0]), _mm_mul_ps(col(t.y_axis), view[1])),
            _mm_mul_ps(col(t.z_axis), view[2]),
        )
    });
    let f32s = |a: __m128| {
        let mut o = [0.0f32; 4];
        _mm_storeu_ps(o.as_mut_ptr(), a);
        o
    };
    let f64s = |a: __m256d| {
        let mut o = [0.0f32; 4];
        _mm_storeu_ps(o.as_mut_ptr(), _mm256_cvtpd_ps(a));
        o
    };
    let (u, v, dudx, dvdx, dudy, dvdy) = (f64s(u), f64s(v), f64s(dudx), f64s(dvdx), f64s(dudy), f64s(dvdy));
    let pos = pos.map(f64s);
    let (vt, depth) = (view_ts.map(f32s), f32s(depth));
    let ok_q = _mm256_movemask_pd(valid_q);
    std::array::from_fn(|i| {
        let p = ShadePoint {
            uv: Vec2::new(u[i], v[i]),
            duv_dx: Vec2::new(dudx[i], dvdx[i]),
            duv_dy: Vec2::new(dudy[i], dvdy[i]),
            view_ts: Vec3::new(vt[0][i], vt[1][i], vt[2][i]),
            light_ts: k.light_ts,
            material: s.material,
        };
        let finite = ok_q & (1 << i) != 0
            && p.uv.is_finite()
            && p.duv_dx.is_finite()
            && p.duv_dy.is_finite()
            && Vec3::new(pos[0][i], pos[1][i], pos[2][i]).is_finite()
            && p.view_ts.is_finite()
            && depth[i].is_finite();
        finite.then_some(p)
    })
}
