//! Heckbert's projective (perspective-correct) texture mapping of a planar quadrilateral seen
//! from an eye point, and every way the thesis evaluates it along a scanline.
//!
//! In Heckbert's row-vector convention a screen point `(x, y)` maps to the texture point
//! `(u, v)` through one 3×3 matrix:
//!
//! ```text
//! [u·q  v·q  q] = [x  y  1] · | A  D  G |      u = (A·x + B·y + C) / (G·x + H·y + I)
//!                             | B  E  H |      v = (D·x + E·y + F) / (G·x + H·y + I)
//!                             | C  F  I |
//! ```
//!
//! The matrix is built in double precision ([`Projective`]); the scanline kernels in
//! [`modes`] work in `f32` on its nine coefficients ([`Coeffs`]) so that their drift is
//! the drift a renderer would see. [`QuadScene`] holds the thesis's default scene and turns
//! any planar quad plus eye into the screen→texture matrix, rejecting degenerate input with
//! a [`MappingError`].

// `!(x > t)` is deliberate throughout: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod modes;
pub mod ops;

use glam::{DVec2, DVec3};

pub use modes::{eval_row, eval_spans, Mode, Span};
pub use ops::{NoOps, OpCounter, OpRate, OpTally, RowCost};

/// Why a quad, an eye or a matrix cannot give a usable perspective mapping.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MappingError {
    /// A coordinate or coefficient is NaN or infinite.
    #[error("{what} is NaN or infinite")]
    NonFinite {
        /// The offending input.
        what: &'static str,
    },
    /// A corner is on or behind the plane through the eye facing the screen (depth ≤ 0), so
    /// it has no image on the screen plane.
    #[error("corner P{index} is not in front of the eye (depth {depth})")]
    BehindEye {
        /// Corner number, 1 to 4 as in the thesis.
        index: usize,
        /// Its depth `P.z − eye.z`.
        depth: f64,
    },
    /// The screen plane is not in front of the eye.
    #[error("screen plane z = {screen_z} is not in front of the eye (eye z = {eye_z})")]
    ScreenBehindEye {
        /// Screen-plane z.
        screen_z: f64,
        /// Eye z.
        eye_z: f64,
    },
    /// Three corners lie on one line (or two coincide): the quad has no area.
    #[error("corners P{}, P{}, P{} are collinear", .0[0], .0[1], .0[2])]
    Collinear([usize; 3]),
    /// The four corners do not lie in one plane, so no single projective map covers them.
    #[error("the quad is not planar (P3 is {0:.3e} of the quad's size off the plane of P1, P2, P4)")]
    NonPlanar(f64),
    /// The eye lies in the quad's plane: the quad is seen edge-on and projects to a line.
    #[error("the eye lies in the quad's plane: the quad is seen edge-on")]
    EyeInPlane,
    /// The (projected) quad is not convex, so no projective map from the unit square reaches it.
    #[error("the quad is not convex")]
    NotConvex,
    /// The 3×3 matrix has (relatively) zero determinant and cannot be inverted.
    #[error("the projective matrix is singular (relative determinant {0:.3e})")]
    Singular(f64),
    /// A k-stride evaluation was asked for with an unsupported stride.
    #[error("k-stride evaluation needs 1 <= k <= {max}, got {k}")]
    BadStride {
        /// Stride asked for.
        k: usize,
        /// Largest stride supported.
        max: usize,
    },
}

/// The nine mapping coefficients in `f32`, named as in Heckbert and the thesis, for the
/// scanline kernels.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(missing_docs)] // the letters are the formula's; see the module docs
pub struct Coeffs {
    pub a: f32,
    pub b: f32,
    pub c: f32,
    pub d: f32,
    pub e: f32,
    pub f: f32,
    pub g: f32,
    pub h: f32,
    pub i: f32,
}

/// A 2D projective mapping as a 3×3 matrix in Heckbert's row-vector convention:
/// `[x' w, y' w, w] = [x, y, 1] · m`. Used for screen→texture (`A…I`) and its inverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projective {
    /// Rows of the matrix: `m[0] = [A, D, G]`, `m[1] = [B, E, H]`, `m[2] = [C, F, I]`.
    pub m: [[f64; 3]; 3],
}

const REL_EPS: f64 = 1e-9;

impl Projective {
    /// The mapping from the nine coefficients `u = (Ax+By+C)/(Gx+Hy+I)`, `v = (Dx+Ey+F)/(…)`.
    #[allow(clippy::too_many_arguments)]
    pub fn from_coeffs(a: f64, b: f64, c: f64, d: f64, e: f64, f: f64, g: f64, h: f64, i: f64) -> Self {
        Projective { m: [[a, d, g], [b, e, h], [c, f, i]] }
    }

    /// The identity mapping.
    pub fn identity() -> Self {
        Projective { m: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] }
    }

    /// The coefficients rounded to `f32` for the scanline kernels.
    pub fn coeffs(&self) -> Coeffs {
        let m = &self.m;
        Coeffs {
            a: m[0][0] as f32,
            b: m[1][0] as f32,
            c: m[2][0] as f32,
            d: m[0][1] as f32,
            e: m[1][1] as f32,
            f: m[2][1] as f32,
            g: m[0][2] as f32,
            h: m[1][2] as f32,
            i: m[2][2] as f32,
        }
    }

    /// The determinant of the matrix.
    pub fn determinant(&self) -> f64 {
        let m = &self.m;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// The adjugate (transposed cofactor) matrix: `m · adj = det · I`. Because a projective
    /// mapping is defined only up to scale, the adjugate *is* the inverse mapping, with no
    /// division — the reason Heckbert uses it. In the thesis's letters its rows are
    /// `[EI−FH, FG−DI, DH−EG]`, `[CH−BI, AI−CG, BG−AH]`, `[BF−CE, CD−AF, AE−BD]`.
    pub fn adjugate(&self) -> Projective {
        let m = &self.m;
        let c = |r0: usize, c0: usize, r1: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
        Projective {
            m: [
                [c(1, 1, 2, 2), -c(0, 1, 2, 2), c(0, 1, 1, 2)],
                [-c(1, 0, 2, 2), c(0, 0, 2, 2), -c(0, 0, 1, 2)],
                [c(1, 0, 2, 1), -c(0, 0, 2, 1), c(0, 0, 1, 1)],
            ],
        }
    }

    /// The inverse mapping (the adjugate), or [`MappingError::Singular`] when the determinant
    /// is zero relative to the size of the entries, or [`MappingError::NonFinite`].
    pub fn inverse(&self) -> Result<Projective, MappingError> {
        if self.m.iter().flatten().any(|v| !v.is_finite()) {
            return Err(MappingError::NonFinite { what: "matrix entry" });
        }
        let norm = self.m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
        if norm == 0.0 {
            return Err(MappingError::Singular(0.0));
        }
        let rel = self.determinant() / (norm * norm * norm);
        if !(rel.abs() > REL_EPS) {
            return Err(MappingError::Singular(rel));
        }
        Ok(self.adjugate())
    }

    /// Composition: first `self`, then `next` (row vectors multiply on the right).
    pub fn then(&self, next: &Projective) -> Projective {
        let mut out = [[0.0; 3]; 3];
        for (r, row) in out.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = (0..3).map(|k| self.m[r][k] * next.m[k][c]).sum();
            }
        }
        Projective { m: out }
    }

    /// Homogeneous image `[x' w, y' w, w]` of `(x, y)`.
    pub fn map_homogeneous(&self, x: f64, y: f64) -> DVec3 {
        let m = &self.m;
        DVec3::new(
            x * m[0][0] + y * m[1][0] + m[2][0],
            x * m[0][1] + y * m[1][1] + m[2][1],
            x * m[0][2] + y * m[1][2] + m[2][2],
        )
    }

    /// Image of `(x, y)`, or `None` where `w = 0` (the point maps to infinity: the horizon).
    pub fn map(&self, x: f64, y: f64) -> Option<DVec2> {
        let p = self.map_homogeneous(x, y);
        if p.z == 0.0 || !p.z.is_finite() {
            return None;
        }
        let r = DVec2::new(p.x / p.z, p.y / p.z);
        r.is_finite().then_some(r)
    }

    /// Heckbert's square-to-quad mapping: the projective map taking the unit square's corners
    /// `(0,0), (1,0), (1,1), (0,1)` to `quad[0..4]`, in closed form (affine when the quad is a
    /// parallelogram). Rejects non-finite, collinear and non-convex corners.
    pub fn square_to_quad(quad: [DVec2; 4]) -> Result<Projective, MappingError> {
        if quad.iter().any(|p| !p.is_finite()) {
            return Err(MappingError::NonFinite { what: "quad corner" });
        }
        check_convex(&quad)?;
        let [p0, p1, p2, p3] = quad;
        let sx = p0.x - p1.x + p2.x - p3.x;
        let sy = p0.y - p1.y + p2.y - p3.y;
        let scale = quad.iter().map(|p| (*p - p0).length()).fold(0.0, f64::max);
        let (g, h) = if sx.abs() <= REL_EPS * scale && sy.abs() <= REL_EPS * scale {
            (0.0, 0.0)
        } else {
            let (dx1, dx2) = (p1.x - p2.x, p3.x - p2.x);
            let (dy1, dy2) = (p1.y - p2.y, p3.y - p2.y);
            let den = dx1 * dy2 - dx2 * dy1;
            if den == 0.0 {
                return Err(MappingError::Collinear([2, 3, 4]));
            }
            ((sx * dy2 - dx2 * sy) / den, (dx1 * sy - sx * dy1) / den)
        };
        // Row-vector form: [x w, y w, w] = [u, v, 1] · m.
        Ok(Projective {
            m: [
                [p1.x - p0.x + g * p1.x, p1.y - p0.y + g * p1.y, g],
                [p3.x - p0.x + h * p3.x, p3.y - p0.y + h * p3.y, h],
                [p0.x, p0.y, 1.0],
            ],
        })
    }

    /// The inverse of [`Projective::square_to_quad`]: screen quad → unit texture square.
    pub fn quad_to_square(quad: [DVec2; 4]) -> Result<Projective, MappingError> {
        Self::square_to_quad(quad)?.inverse()
    }
}

/// Signed area test: every turn of the closed polygon has the same sign and none is
/// (relatively) zero.
fn check_convex(q: &[DVec2; 4]) -> Result<(), MappingError> {
    let scale = (0..4).map(|k| (q[(k + 1) % 4] - q[k]).length_squared()).fold(0.0, f64::max);
    if !(scale > 0.0) {
        return Err(MappingError::Collinear([1, 2, 3]));
    }
    let mut sign = 0.0;
    for k in 0..4 {
        let a = q[(k + 1) % 4] - q[k];
        let b = q[(k + 2) % 4] - q[(k + 1) % 4];
        let cross = a.perp_dot(b);
        if cross.abs() <= 1e-12 * scale {
            return Err(MappingError::Collinear([k + 1, (k + 1) % 4 + 1, (k + 2) % 4 + 1]));
        }
        if sign == 0.0 {
            sign = cross.signum();
        } else if cross.signum() != sign {
            return Err(MappingError::NotConvex);
        }
    }
    Ok(())
}

/// A textured planar quad `P1…P4` in 3D seen from the eye `O1` through the screen plane
/// `z = screen_z`, as in the thesis's MFC program. Texture coordinates are the unit square:
/// `P1 → (0,0)`, `P2 → (1,0)`, `P3 → (1,1)`, `P4 → (0,1)`. The eye looks along +z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadScene {
    /// Corners `P1…P4`, in order around the quad.
    pub corners: [DVec3; 4],
    /// The eye (centre of projection) `O1`.
    pub eye: DVec3,
    /// z of the screen plane; screen coordinates are the plane's x and y.
    pub screen_z: f64,
}

impl QuadScene {
    /// Screen-plane z used by [`QuadScene::thesis_default`]. The thesis never states it; 1000
    /// puts the quad's image at about 150×155 px, inside the program's 232×400 output box.
    pub const THESIS_SCREEN_Z: f64 = 1000.0;

    /// The thesis's scene (Fig. 4.1): P1(80,50,1600), P2(240,80,1500), P3(200,280,1100),
    /// P4(40,250,1200), eye O1(130,240,0). The four corners are exactly coplanar and form a
    /// parallelogram (P1 + P3 = P2 + P4), which supports the OCR reading "280" for P3.y.
    pub fn thesis_default() -> Self {
        QuadScene {
            corners: [
                DVec3::new(80.0, 50.0, 1600.0),
                DVec3::new(240.0, 80.0, 1500.0),
                DVec3::new(200.0, 280.0, 1100.0),
                DVec3::new(40.0, 250.0, 1200.0),
            ],
            eye: DVec3::new(130.0, 240.0, 0.0),
            screen_z: Self::THESIS_SCREEN_Z,
        }
    }

    /// Checks the scene: finite, in front of the eye, no three corners collinear, planar,
    /// eye off the plane.
    pub fn validate(&self) -> Result<(), MappingError> {
        if self.corners.iter().any(|p| !p.is_finite()) {
            return Err(MappingError::NonFinite { what: "quad corner" });
        }
        if !self.eye.is_finite() {
            return Err(MappingError::NonFinite { what: "eye" });
        }
        if !self.screen_z.is_finite() {
            return Err(MappingError::NonFinite { what: "screen plane z" });
        }
        if !(self.screen_z > self.eye.z) {
            return Err(MappingError::ScreenBehindEye { screen_z: self.screen_z, eye_z: self.eye.z });
        }
        let p = &self.corners;
        let size = (0..4).map(|k| (p[(k + 1) % 4] - p[k]).length()).fold(0.0, f64::max);
        for (k, c) in p.iter().enumerate() {
            let depth = c.z - self.eye.z;
            if !(depth > REL_EPS * size.max(1.0)) {
                return Err(MappingError::BehindEye { index: k + 1, depth });
            }
        }
        for tri in [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]] {
            let n = (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]);
            if !(n.length() > REL_EPS * size * size) {
                return Err(MappingError::Collinear([tri[0] + 1, tri[1] + 1, tri[2] + 1]));
            }
        }
        let n = (p[1] - p[0]).cross(p[3] - p[0]).normalize();
        let off = (p[2] - p[0]).dot(n).abs() / size;
        if !(off <= 1e-6) {
            return Err(MappingError::NonPlanar(off));
        }
        let eye_off = (self.eye - p[0]).dot(n).abs();
        if !(eye_off > REL_EPS * size.max((self.eye - p[0]).length())) {
            return Err(MappingError::EyeInPlane);
        }
        Ok(())
    }

    /// The corners' images on the screen plane, `S = O1 + (z − O1.z)/(P.z − O1.z) · (P − O1)`.
    pub fn project(&self) -> Result<[DVec2; 4], MappingError> {
        self.validate()?;
        let o = self.eye;
        let t = self.screen_z - o.z;
        Ok(self.corners.map(|p| {
            let s = o + (p - o) * (t / (p.z - o.z));
            DVec2::new(s.x, s.y)
        }))
    }

    /// The screen→texture mapping (`A…I`): the inverse, by adjugate, of the unit square's
    /// projective map onto the projected quad. For a planar quad this is exact: the plane's
    /// projection is itself projective.
    pub fn mapping(&self) -> Result<Projective, MappingError> {
        let s = self.project()?;
        Projective::quad_to_square(s)
    }

    /// Depth `P.z − eye.z` of the quad's surface point seen at screen point `(x, y)`, or
    /// `None` off the plane's visible half (at or beyond the horizon).
    pub fn depth_at(&self, x: f64, y: f64) -> Option<f64> {
        self.validate().ok()?;
        let o = self.eye;
        let dir = DVec3::new(x, y, self.screen_z) - o;
        let p = &self.corners;
        let n = (p[1] - p[0]).cross(p[3] - p[0]);
        let den = dir.dot(n);
        if den == 0.0 {
            return None;
        }
        let t = (p[0] - o).dot(n) / den;
        (t > 0.0 && t.is_finite()).then_some(t * dir.z)
    }
}
