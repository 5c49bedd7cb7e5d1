//! Perlin gradient noise for renderlab: the thesis's noise (chapter 3 of the texturing
//! thesis, summary §2.6) done properly and measured.
//!
//! * [`Perlin`]: Ken Perlin's improved gradient noise in 1D–4D with the quintic fade
//!   `6t⁵ − 15t⁴ + 10t³`, a seeded permutation table per axis, and analytic derivatives.
//! * [`Period`]: tileable noise (the lattice wraps after a whole number of cells).
//! * [`HashedPerlin`]: the same 2D gradient noise on a hashed lattice (no tables, any
//!   period), for textures generated texel by texel such as the built-in relief materials.
//! * [`Fractal`] with validated [`FractalParams`]: the thesis's octave sum
//!   `P_i = P_{i−1} + noise(2^i·x)/2^i` with min–max normalisation ([`normalize_min_max`]),
//!   fBm with lacunarity and gain, turbulence and ridged sums.
//! * [`smoke`]: a rising smoke plume (filtered noise density, curl-noise advection, ray
//!   marching with single scattering), beside the thesis's literal `noise + k·t`.
//! * [`water`]: an animated sea (fBm height field, analytic normals, Fresnel sky reflection).
//! * [`batch`]: whole rows, planes and volumes at once, hoisting per-row work; this is the
//!   fast path (see `benches/noise.rs`, which compares it with the `noise` crate).
//!
//! Every function is a pure function of seeds, parameters and coordinates: results are
//! identical for any thread count. Bad parameters give a [`NoiseError`]; non-finite
//! coordinates give 0, never a panic.
//!
//! ```
//! use renderlab_noise::{batch, Fractal, FractalKind, FractalParams, Perlin};
//!
//! // One generator with its own seed per axis, as in the thesis's Fig. 3.3.
//! let perlin = Perlin::with_axis_seeds([100, 101, 102, 0]);
//! assert_eq!(perlin.noise3(1.0, 2.0, 3.0), 0.0); // zero on the lattice
//! let (n, grad) = perlin.noise_with_derivative([0.3, 0.6, 0.9]);
//! assert!(n.abs() <= 1.0 && grad.iter().all(|g| g.is_finite()));
//!
//! // Six octaves of fBm over a 64×64 image, in one call.
//! let params = FractalParams::new(6, 4.0, 2.0, 0.5)?;
//! let fbm = Fractal::new(perlin, params, FractalKind::Fbm);
//! let mut image = vec![0.0f32; 64 * 64];
//! batch::fill(&fbm, [0.0, 0.0], [1.0 / 64.0; 2], [64, 64], &mut image)?;
//!
//! // Bad parameters are errors that name the parameter.
//! assert!(FractalParams::new(0, 1.0, 2.0, 0.5).unwrap_err().to_string().contains("octaves"));
//! # Ok::<(), renderlab_noise::NoiseError>(())
//! ```

#![warn(missing_docs)]

pub mod batch;
pub mod error;
pub mod fractal;
pub mod hashed;
pub mod periodic;
pub mod perlin;
pub mod smoke;
pub mod water;
mod wrap;

pub use error::{NoiseError, Result};
pub use fractal::{normalize_min_max, Fractal, FractalKind, FractalParams, MAX_FREQUENCY, MAX_OCTAVES};
pub use hashed::HashedPerlin;
pub use periodic::{Period, MAX_PERIOD};
pub use perlin::{fade, fade_derivative, Perlin};
pub use smoke::{
    build_density, render_smoke_frame, Animation, DensityGrid, SmokeFilter, SmokeParams, SmokeVolume,
};
pub use water::{render_water_frame, WaterParams, WaterSurface};

/// Largest number of samples a batch call accepts (2^31), so that a size typo fails fast
/// instead of allocating or looping for hours.
pub const MAX_SAMPLES: usize = 1 << 31;
