//! The Perlin-noise lab: the texturing thesis's noise experiments (its §3.1, Fig. 3.2–3.5)
//! reproduced as figures, with the statistics the thesis did not give.
//!
//! * **3D paths** (Fig. 3.2–3.4): 1000 points whose x, y and z are three 1D noise functions of
//!   one parameter `t ∈ [0, 1)`. The thesis's Python package (`perlin-noise`) calls its
//!   *frequency* "octaves", so "octaves = 10" is one noise layer with 10 lattice cells per unit
//!   (see [`renderlab_noise::fractal`]). With the same seed and frequency on every axis the
//!   three functions are the same function, so every point has x = y = z and the "path" is a
//!   straight line along the diagonal; distinct seeds give distinct gradient tables and a path
//!   that wanders in 3D. The paths are drawn as x–y and x–z projections.
//! * **Octaves**: the Fig. 3.4 axes (frequencies 1, 2, 3) as functions of `t`, beside the
//!   thesis's own octave sum `P_i = P_{i−1} + noise(2^i·x)/2^i` for 1, 2, 4 and 10 octaves.
//! * **Clouds** (Fig. 3.5): four independently seeded 2D layers at frequencies 3, 6, 12, 24,
//!   weighted 1, ½, ¼, ⅛, summed on a 100×100 grid and min–max normalised to [0, 1]; written
//!   as grey PNGs with each layer beside it.
//! * **Water** (§3.2) and **smoke** (§3.3): animations (APNG) and stills, from
//!   [`motion`], with the per-frame measurements that separate the two ways of
//!   animating smoke.
//!
//! Everything is a pure function of the seeds and sizes, so the figures are identical on every
//! run and thread count. The animations ([`MotionConfig`]) take nearly all of the lab's time.
//!
//! The run ([`run_noise_lab_with`]) computes and writes each experiment; the page shows them
//! through `templates/noise.html`.

mod clouds;
pub mod motion;
mod page;
mod paths;
mod run;
mod stats;

pub use clouds::{clouds, clouds_streamed, Clouds, CloudsConfig, MAX_CLOUDS_SIZE};
pub use motion::{correlation, water_and_smoke, MotionConfig, MotionSummary, SmokeFrameStats, THESIS_FACTOR};
pub use paths::{
    max_distance_from_diagonal, noise_path, thesis_paths, AxisNoise, PathExperiment, MAX_PATH_POINTS,
    PATH_POINTS,
};
pub use run::{run_noise_lab, run_noise_lab_with, NoiseLabConfig, NoiseSummary};
pub use stats::{StatRow, Stats};
