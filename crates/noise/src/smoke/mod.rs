//! Volumetric smoke: the texturing thesis's §3.3 smoke algorithm (3D Perlin noise → Gaussian or
//! median filter → `scale(noise) = noise·scale_factor` → `animate(noise, t)` → display), made
//! into a rising plume rendered by ray marching.
//!
//! # Density, once per frame
//!
//! [`build_density`] fills a flat `n³` grid over the box `[−1, 1]³` (y up), z-slices in
//! parallel. Each voxel centre `p` gets
//!
//! ```text
//! ρ(p, t) = density · plume(p) · clamp(BIAS + CONTRAST · fBm(q), 0, 1)      (Advect)
//! ρ(p, t) = density · plume(p) · clamp(BIAS + CONTRAST · fBm(p) + k·t, 0, 1) (ThesisLiteral)
//! ```
//!
//! * [`Animation::Advect`] moves *through the noise domain*: `q = p − (0, rise·t, 0) +
//!   swirl · curl ψ`, the noise advected backward by the rise velocity plus a displacement by
//!   curl noise (the curl of a 3-component noise vector potential ψ, evaluated from analytic
//!   derivatives, so the swirl is divergence-free and needs no finite differences). ψ itself
//!   rises and evolves along a fourth noise axis, so the swirls change shape over time.
//! * [`Animation::ThesisLiteral`] is the thesis's formula `animate(noise, t) = noise + k·t`
//!   taken literally: a spatially uniform offset, which only brightens (or fades) the field
//!   while its pattern stays frozen. It is kept so that the difference can be measured.
//! * `plume(p)` ([`plume_shape`]) is a radial Gaussian around the vertical axis whose radius
//!   widens with height, cut to compact support, fading smoothly to 0 over the top `falloff`
//!   of `plume_height` and at the floor. With Advect it is evaluated at `p` shifted by the
//!   horizontal part of the curl displacement (growing with height), so the column sways.
//! * The curl displacement is smooth, so the grid builder evaluates it on a coarse
//!   [`CURL_GRID`]³ grid and interpolates it (the exact [`SmokeField::density`] evaluates it
//!   per point).
//!
//! The filter ([`SmokeFilter`]) is then applied to the grid: separable Gaussian with σ in
//! voxels ([`gaussian_filter`]) or a 3×3×3 median ([`median_filter`]), both clamp-to-edge.
//!
//! # Light, once per frame
//!
//! Single scattering needs, at every march sample, the transmittance toward the light. Instead
//! of a shadow ray per sample (cost ∝ pixels × samples × shadow steps), [`SmokeVolume`]
//! precomputes a *light-transmittance grid* once per frame, at half the density resolution
//! per side (shadows are smooth): at every light-voxel centre a shadow ray of `shadow_steps`
//! midpoint samples to the box exit toward the light gives `T_light = exp(−σt ∫ρ ds)`.
//! Rendering then reads it by trilinear lookup, so the shadow cost is `(n/2)³ · shadow_steps`
//! (8 M density lookups for n = 128 and 32 steps), independent of the image size and the
//! march length. The price: no self-shadowing detail finer than two voxels.
//!
//! # Cost
//!
//! Per frame, the density (fBm only where the plume is not empty) and its filter take about
//! half the time, the light grid and the ray march share the rest (BENCHMARKS.md has the
//! figures).
//!
//! # Rendering
//!
//! Per pixel the camera ray is clipped to the box and marched with step `step` voxels (the
//! first step jittered by a fixed per-pixel hash to hide banding). At each sample with density
//! ρ, Beer–Lambert over the segment gives `e = exp(−σt ρ Δs)`; the segment adds
//! `T · (σs/σt) · (1 − e) · (light · phase · T_light + ambient)` and `T *= e`, with a
//! Henyey–Greenstein phase function. The pixel is `L + T · background`. Marching stops when
//! `T < 10⁻³`.
//!
//! Every voxel and pixel is a pure function of the parameters and `t`, and the filters and
//! light grid read only finished buffers, so frames are bit-identical for any thread count.
//!
//! The code follows that order: [`params`] (parameters, limits and constants), [`grid`] (the
//! density grid and its filters), [`field`] (the density field and [`build_density`]) and
//! [`render`] (light grid, ray march, frames).

pub mod field;
pub mod grid;
pub mod params;
pub mod render;

pub use field::{build_density, plume_shape, SmokeField};
pub use grid::{gaussian_filter, median_filter, DensityGrid};
pub use params::{
    Animation, SmokeFilter, SmokeParams, BIAS, CONTRAST, CURL_EVOLUTION, CURL_GRID, ENVELOPE_CUT,
    ENVELOPE_SWAY, MAX_GRID, MAX_SIGMA, MAX_SMOKE_OCTAVES, MAX_SMOKE_SIDE, MAX_SMOKE_TIME, MIN_GRID,
    MIN_TRANSMITTANCE, PLUME_WIDENING,
};
pub use render::{box_interval, henyey_greenstein, render_smoke_frame, render_smoke_sequence, SmokeVolume};
