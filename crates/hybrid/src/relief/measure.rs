//! How far the relief pass's G-buffer is from the exact relief, and what that does to the
//! stages that read it.
//!
//! The reference is the same pass with the exact tracer and the pixel-depth offset: its
//! position per pixel is the exact displaced hit on the camera ray. For each tracer, with the
//! offset off and on, over the pixels that show relief in both:
//! - depth error: `|‖P − eye‖ − ‖P_exact − eye‖|` in world units, and as a fraction of the
//!   relief's full depth there (`s · w`); mean and 99th percentile;
//! - shadow error: mean `|v − v_exact|` of the shadow stage's visibility (the raster shadow
//!   maps, averaged over the scene's lights, [`light_visibility`]);
//! - AO error: mean `|ao − ao_exact|` of SSAO.

use super::maps::ReliefMaps;
use super::pass::{relief_pass, ReliefSample};
use super::settings::{ReliefSettings, ReliefTracer};
use crate::deferred::geometry::{geometry_pass, GeometryPass, PreparedScene};
use crate::deferred::lighting::{light_sample_u, ShadowQuery, Visibility};
use crate::deferred::settings::RasterSettings;
use crate::stages::ao::ssao;
use crate::stages::shadows::maps::ShadowMaps;
use rayon::prelude::*;
use renderlab_core::Camera;
use renderlab_scene::{GBuffer, HybridScene};

/// One tracer with the pixel-depth offset off or on, against the exact relief.
#[derive(Clone, Debug, PartialEq)]
pub struct PdoRow {
    /// The tracer's canonical name.
    pub tracer: String,
    /// Whether the offset was on.
    pub pixel_depth_offset: bool,
    /// Pixels showing relief (the pixels every figure is over).
    pub pixels: usize,
    /// Mean depth error, world units.
    pub depth_mean: f64,
    /// 99th-percentile depth error, world units.
    pub depth_p99: f64,
    /// Mean depth error as a fraction of the relief's depth.
    pub depth_mean_rel: f64,
    /// 99th-percentile depth error as a fraction of the relief's depth.
    pub depth_p99_rel: f64,
    /// Mean |Δ| of the shadow stage's visibility.
    pub shadow_mean_abs: f64,
    /// Mean |Δ| of SSAO.
    pub ao_mean_abs: f64,
}

/// Per opaque pixel of `g`, the visibility `vis` gives each of `scene`'s lights, averaged over
/// the lights (one query per light, at its first sample; 1 where the sky shows or no light
/// is).
pub fn light_visibility(scene: &HybridScene, g: &GBuffer, vis: &dyn Visibility) -> Vec<f32> {
    g.opaque
        .par_iter()
        .enumerate()
        .map(|(pixel, sp)| {
            let Some(sp) = sp else { return 1.0 };
            if scene.lights.is_empty() {
                return 1.0;
            }
            let mut sum = 0.0;
            for (light_index, light) in scene.lights.iter().enumerate() {
                let ls = light.sample(sp.position, light_sample_u(0, 1));
                let q = ShadowQuery { light, light_index, pixel, sample: 0, point: sp, light_sample: &ls };
                sum += vis.visibility(&q);
            }
            sum / scene.lights.len() as f32
        })
        .collect()
}

/// The geometry pass of `camera` followed by the relief pass as `relief` says.
pub fn relief_geometry(
    prepared: &PreparedScene,
    camera: &Camera,
    raster: &RasterSettings,
    relief: &ReliefSettings,
    maps: &ReliefMaps,
) -> (GeometryPass, Vec<Option<ReliefSample>>) {
    let mut g = geometry_pass(prepared, camera, raster.translucent_layers);
    let samples = relief_pass(prepared, &mut g, relief, maps);
    (g, samples)
}

/// The table of this module's figures for each of `tracers`, offset off then on, seen by
/// `camera` with `raster`'s shadow maps and SSAO.
pub fn measure_pixel_depth_offset(
    prepared: &PreparedScene,
    camera: &Camera,
    raster: &RasterSettings,
    tracers: &[ReliefTracer],
    maps: &ReliefMaps,
) -> Vec<PdoRow> {
    let scene = prepared.scene;
    let shadows = ShadowMaps::build(prepared, &raster.shadows);
    let eye = camera.position;
    let exact = ReliefSettings::new(ReliefTracer::Exact, true);
    let (reference, ref_samples) = relief_geometry(prepared, camera, raster, &exact, maps);
    let ref_g = &reference.gbuffer;
    let ref_vis = light_visibility(scene, ref_g, &shadows);
    let ref_ao = ssao(ref_g, &raster.ssao);
    let mut rows = Vec::new();
    for &tracer in tracers {
        for pdo in [false, true] {
            let settings = ReliefSettings::new(tracer, pdo);
            let (geo, samples) = relief_geometry(prepared, camera, raster, &settings, maps);
            let g = &geo.gbuffer;
            let vis = light_visibility(scene, g, &shadows);
            let ao = ssao(g, &raster.ssao);
            let (mut abs, mut rel) = (Vec::new(), Vec::new());
            let (mut shadow, mut occlusion) = (0.0f64, 0.0f64);
            for i in 0..samples.len() {
                let (Some(s), Some(r)) = (&samples[i], &ref_samples[i]) else { continue };
                let (Some(p), Some(q)) = (&g.opaque[i], &ref_g.opaque[i]) else { continue };
                let e = ((p.position - eye).length() - (q.position - eye).length()).abs() as f64;
                abs.push(e);
                rel.push(e / (r.relief_world_depth.max(s.relief_world_depth) as f64).max(1e-12));
                shadow += (vis[i] - ref_vis[i]).abs() as f64;
                occlusion += (ao[i] - ref_ao[i]).abs() as f64;
            }
            let n = abs.len();
            let per = |x: f64| if n == 0 { 0.0 } else { x / n as f64 };
            rows.push(PdoRow {
                tracer: tracer.name(),
                pixel_depth_offset: pdo,
                pixels: n,
                depth_mean: per(abs.iter().sum()),
                depth_p99: percentile(&mut abs, 0.99),
                depth_mean_rel: per(rel.iter().sum()),
                depth_p99_rel: percentile(&mut rel, 0.99),
                shadow_mean_abs: per(shadow),
                ao_mean_abs: per(occlusion),
            });
        }
    }
    rows
}

/// The `q`-quantile of `values` (the smallest value at least a fraction `q` of them do not
/// exceed); 0 when empty.
pub fn percentile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let k = ((q * values.len() as f64).ceil() as usize).clamp(1, values.len()) - 1;
    values[k]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_pick_the_value_at_the_rank() {
        let mut v: Vec<f64> = (1..=100).rev().map(f64::from).collect();
        assert_eq!(percentile(&mut v, 0.99), 99.0);
        assert_eq!(percentile(&mut v, 1.0), 100.0);
        assert_eq!(percentile(&mut v, 0.0), 1.0);
        assert_eq!(percentile(&mut [], 0.5), 0.0);
    }
}
