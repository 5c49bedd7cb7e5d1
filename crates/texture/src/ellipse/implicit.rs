//! Heckbert's implicit footprint ellipse `A·U² + B·U·V + C·V² = F` (2.9), the image of the
//! unit pixel circle under the Jacobian, with `A = V_x² + V_y²`, `B = −2(U_x·V_x + U_y·V_y)`,
//! `C = U_x² + U_y²`, `F = (U_x·V_y − U_y·V_x)² = A·C − B²/4`.

// `!(x > t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::error::EllipseError;
use super::jacobian::Jacobian;
use glam::Vec2;

/// Heckbert's implicit footprint ellipse `A·U² + B·U·V + C·V² = F` around the pixel's
/// texture point (`U = u − u₀`, `V = v − v₀`), the image of the unit pixel circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipse {
    /// `A = V_x² + V_y²`.
    pub a: f32,
    /// `B = −2(U_x·V_x + U_y·V_y)`.
    pub b: f32,
    /// `C = U_x² + U_y²`.
    pub c: f32,
    /// `F = (U_x·V_y − U_y·V_x)²`, which equals `A·C − B²/4`.
    pub f: f32,
}

impl Ellipse {
    /// The ellipse (2.9) of a Jacobian. Rejects non-finite input or overflow
    /// ([`EllipseError::NonFinite`]) and zero-area footprints ([`EllipseError::Degenerate`]:
    /// `F` is zero, or below `1e-12·A·C` — columns parallel to float precision).
    pub fn from_jacobian(j: &Jacobian) -> Result<Ellipse, EllipseError> {
        if !j.is_finite() {
            return Err(EllipseError::NonFinite);
        }
        let (ux, vx, uy, vy) = (j.du_dx, j.dv_dx, j.du_dy, j.dv_dy);
        let a = vx * vx + vy * vy;
        let b = -2.0 * (ux * vx + uy * vy);
        let c = ux * ux + uy * uy;
        let det = ux * vy - uy * vx;
        let f = det * det;
        if !(a.is_finite() && b.is_finite() && c.is_finite() && f.is_finite()) {
            return Err(EllipseError::NonFinite);
        }
        if !(f > 0.0) || f <= 1e-12 * a * c {
            return Err(EllipseError::Degenerate);
        }
        Ok(Ellipse { a, b, c, f })
    }

    /// The ellipse `{p : pᵀ·Σ⁻¹·p ≤ 1}` of a symmetric second-moment matrix
    /// `Σ = [[m00, m01], [m01, m11]]` (for a footprint, `Σ = J·Jᵀ`, plus `r²·I` for Heckbert's
    /// reconstruction term), in Heckbert's form: `A = m11`, `B = −2·m01`, `C = m00`,
    /// `F = det Σ`. Used by EWA after it has reshaped the footprint (eccentricity clamp, mip
    /// level); it does not validate, so `Σ` must be positive definite for a usable ellipse.
    pub fn from_moments(m00: f32, m01: f32, m11: f32) -> Ellipse {
        Ellipse { a: m11, b: -2.0 * m01, c: m00, f: m00 * m11 - m01 * m01 }
    }

    /// `A·U² + B·U·V + C·V²` at offset `(U, V)` from the centre; `< F` inside.
    pub fn q(&self, du: f32, dv: f32) -> f32 {
        self.a * du * du + self.b * du * dv + self.c * dv * dv
    }

    /// Whether the offset `(U, V)` lies inside or on the ellipse.
    pub fn contains(&self, du: f32, dv: f32) -> bool {
        self.q(du, dv) <= self.f
    }

    /// Half-widths of the axis-aligned bounding box. Heckbert's general bounds
    /// `√(4CF/(4AC−B²))` and `√(4AF/(4AC−B²))` reduce to `(√C, √A)` here because
    /// `4AC − B² = 4F`; the reduced form cannot go negative under rounding.
    pub fn half_extent(&self) -> Vec2 {
        Vec2::new(self.c.sqrt(), self.a.sqrt())
    }
}
