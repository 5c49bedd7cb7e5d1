//! The thesis's 3D paths (Fig. 3.2–3.4): points whose x, y and z are three 1D noise
//! functions of one parameter, and how far a path strays from the diagonal x = y = z.

use crate::error::Result;
use renderlab_noise::{batch, Fractal, FractalKind, FractalParams, NoiseError, Perlin};
use serde::Serialize;

/// Points per path in the thesis's experiments.
pub const PATH_POINTS: usize = 1000;
/// Largest path accepted (points), so that a typo cannot allocate without bound.
pub const MAX_PATH_POINTS: usize = 1 << 24;
/// One coordinate of a path: a 1D noise function with its own frequency and seed (the Python
/// package's `PerlinNoise(octaves=frequency, seed=seed)`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AxisNoise {
    /// Lattice cells per unit of `t` (the Python package's "octaves").
    pub frequency: f32,
    /// Seed of this axis's permutation table.
    pub seed: u32,
}

/// One of the thesis's 3D-path experiments.
#[derive(Clone, Debug, PartialEq)]
pub struct PathExperiment {
    /// Short file-name-safe key (e.g. `fig3_2`).
    pub key: &'static str,
    /// Human-readable title with the thesis's figure number.
    pub title: &'static str,
    /// The noise function of x, y and z.
    pub axes: [AxisNoise; 3],
    /// Number of points (`t = i / points`).
    pub points: usize,
}

/// The thesis's three path experiments: Fig. 3.2 (frequency 10, seed 100 on every axis),
/// Fig. 3.3 (seeds 100, 101, 102) and Fig. 3.4 (frequencies 1, 2, 3 with seeds 100, 200, 300).
pub fn thesis_paths() -> Vec<PathExperiment> {
    let ax = |frequency, seed| AxisNoise { frequency, seed };
    vec![
        PathExperiment {
            key: "fig3_2",
            title: "Fig. 3.2: frequency 10, seed 100 on every axis",
            axes: [ax(10.0, 100), ax(10.0, 100), ax(10.0, 100)],
            points: PATH_POINTS,
        },
        PathExperiment {
            key: "fig3_3",
            title: "Fig. 3.3: frequency 10, seeds 100 / 101 / 102",
            axes: [ax(10.0, 100), ax(10.0, 101), ax(10.0, 102)],
            points: PATH_POINTS,
        },
        PathExperiment {
            key: "fig3_4",
            title: "Fig. 3.4: frequencies 1 / 2 / 3, seeds 100 / 200 / 300",
            axes: [ax(1.0, 100), ax(2.0, 200), ax(3.0, 300)],
            points: PATH_POINTS,
        },
    ]
}

/// Samples one 1D noise function at `t = origin + i·step` for `i < n`.
pub(super) fn sample_line(fractal: &Fractal, origin: f32, step: f32, n: usize) -> Result<Vec<f32>> {
    let mut out = vec![0.0f32; n];
    batch::fill(fractal, [origin], [step], [n], &mut out)?;
    Ok(out)
}

/// One noise layer (a single octave) at `frequency` with `seed` on every axis.
pub(super) fn layer(seed: u32, frequency: f32) -> Result<Fractal> {
    Ok(Fractal::new(Perlin::new(seed), FractalParams::new(1, frequency, 2.0, 0.5)?, FractalKind::Thesis))
}

/// The path of `axes` at `t = i / points`, `i < points`: point `i` is
/// `(x(t), y(t), z(t))`. Errors for a frequency that is not finite and positive or too high,
/// and for 0 or more than [`MAX_PATH_POINTS`] points.
pub fn noise_path(axes: &[AxisNoise; 3], points: usize) -> Result<Vec<[f32; 3]>> {
    if points == 0 || points > MAX_PATH_POINTS {
        return Err(
            NoiseError::Size { dims: vec![points], reason: "path points must lie in 1..=2^24" }.into()
        );
    }
    let step = 1.0 / points as f32;
    let mut coords = Vec::with_capacity(3);
    for a in axes {
        coords.push(sample_line(&layer(a.seed, a.frequency)?, 0.0, step, points)?);
    }
    Ok((0..points).map(|i| [coords[0][i], coords[1][i], coords[2][i]]).collect())
}

/// Largest distance of a path's points from the diagonal line x = y = z through the origin:
/// exactly 0 when the path lies on that line.
pub fn max_distance_from_diagonal(path: &[[f32; 3]]) -> f64 {
    path.iter()
        .map(|p| {
            let p = p.map(f64::from);
            let m = (p[0] + p[1] + p[2]) / 3.0;
            ((p[0] - m).powi(2) + (p[1] - m).powi(2) + (p[2] - m).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}
