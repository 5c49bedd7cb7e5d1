//! The projective matrix of Heckbert's mapping in `f64` ([`Projective`]), its `f32`
//! coefficients for the scanline kernels ([`Coeffs`]) and the square↔quad maps.

// `!(x > t)` is deliberate throughout: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::error::MappingError;
use glam::{DVec2, DVec3};

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

/// Relative tolerance below which a determinant, a parallelogram's defect or a depth counts
/// as zero (relative to the size of the entries or of the quad).
pub(super) const REL_EPS: f64 = 1e-9;

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
