//! The footprint Jacobian `∂(u,v)/∂(x,y)` of one pixel (Heckbert's `U_x, V_x, U_y, V_y`) and
//! its principal axes: the singular values of `J`, from the eigenvalues of the second moments
//! `J·Jᵀ`, the semi-axes of the image of the unit pixel circle.

use glam::Vec2;

/// The footprint Jacobian `∂(u,v)/∂(x,y)` at one pixel (Heckbert's `U_x, V_x, U_y, V_y`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jacobian {
    /// ∂u/∂x.
    pub du_dx: f32,
    /// ∂v/∂x.
    pub dv_dx: f32,
    /// ∂u/∂y.
    pub du_dy: f32,
    /// ∂v/∂y.
    pub dv_dy: f32,
}

impl Jacobian {
    /// The x column `(∂u/∂x, ∂v/∂x)`, as the filters take it.
    pub fn duv_dx(&self) -> Vec2 {
        Vec2::new(self.du_dx, self.dv_dx)
    }

    /// The y column `(∂u/∂y, ∂v/∂y)`.
    pub fn duv_dy(&self) -> Vec2 {
        Vec2::new(self.du_dy, self.dv_dy)
    }

    /// Whether all four entries are finite.
    pub fn is_finite(&self) -> bool {
        self.du_dx.is_finite() && self.dv_dx.is_finite() && self.du_dy.is_finite() && self.dv_dy.is_finite()
    }

    /// Largest absolute entry-wise difference to `other`.
    pub fn max_abs_diff(&self, other: &Jacobian) -> f32 {
        (self.du_dx - other.du_dx)
            .abs()
            .max((self.dv_dx - other.dv_dx).abs())
            .max((self.du_dy - other.du_dy).abs())
            .max((self.dv_dy - other.dv_dy).abs())
    }

    /// Largest absolute entry.
    pub fn max_abs(&self) -> f32 {
        self.du_dx.abs().max(self.dv_dx.abs()).max(self.du_dy.abs()).max(self.dv_dy.abs())
    }

    /// The principal axes of the footprint: the singular values and the major direction of
    /// the Jacobian, i.e. the semi-axes of the image of the unit pixel circle. Unlike
    /// [`Ellipse::from_jacobian`](super::Ellipse::from_jacobian) this never fails on a zero-area footprint (the minor axis
    /// is then 0); non-finite input gives non-finite lengths, which callers must check.
    pub fn axes(&self) -> Axes {
        let (ux, vx, uy, vy) = (self.du_dx, self.dv_dx, self.du_dy, self.dv_dy);
        // Second moments J·Jᵀ of the footprint: [[m00, m01], [m01, m11]].
        let m00 = ux * ux + uy * uy;
        let m01 = ux * vx + uy * vy;
        let m11 = vx * vx + vy * vy;
        let half_tr = 0.5 * (m00 + m11);
        let half_diff = 0.5 * (m00 - m11);
        let l1 = half_tr + (half_diff * half_diff + m01 * m01).sqrt();
        // λ₂ = det²/λ₁ keeps its precision when the footprint is very eccentric, where
        // `half_tr − root` would cancel.
        let det = ux * vy - uy * vx;
        let l2 = if l1 > 0.0 { (det * det / l1).min(l1) } else { 0.0 };
        // Eigenvector of λ₁ from whichever row of (Σ − λ₁·I) is better conditioned; no
        // trigonometry, so it stays cheap enough for a per-lookup filter.
        let e1 = Vec2::new(l1 - m11, m01);
        let e2 = Vec2::new(m01, l1 - m00);
        let e = if e1.length_squared() >= e2.length_squared() { e1 } else { e2 };
        let len2 = e.length_squared();
        let dir = if len2 > 0.0 && len2.is_finite() { e / len2.sqrt() } else { Vec2::X };
        Axes { major: l1.sqrt(), minor: l2.sqrt(), dir }
    }
}

/// Principal axes of a footprint ellipse, from [`Jacobian::axes`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axes {
    /// Major semi-axis length (the larger singular value).
    pub major: f32,
    /// Minor semi-axis length (the smaller singular value, ≥ 0).
    pub minor: f32,
    /// Unit vector along the major axis (`(1, 0)` for a circle).
    pub dir: Vec2,
}
