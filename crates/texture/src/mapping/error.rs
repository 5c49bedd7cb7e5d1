//! Why a perspective mapping cannot be built: the one error of the quad, the matrix and the
//! scanline kernels.

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
