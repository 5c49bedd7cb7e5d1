//! Screen-space reflections.
//!
//! For each opaque pixel no rougher than `max_roughness`, the view direction is mirrored
//! about the shading normal and the reflected ray (from the surface, up to `max_distance`,
//! cut at the near plane and at the screen's edges) is projected to the screen. It is marched linearly in steps of
//! `stride_px` pixels, its depth along the view axis interpolated perspective-correctly (its
//! reciprocal is affine on the screen). The first step at which the ray lies behind the
//! depth buffer by less than `thickness` (and meets a surface facing it) is refined by `refine_steps` bisections; the hit
//! pixel's radiance in the lit opaque image (emitted + direct + ambient·AO) is the
//! reflection. Rays that leave the screen or find nothing, and pixels rougher than
//! `max_roughness`, see the sky: the environment fallback.
//!
//! The reflected radiance is weighted by the split-sum specular weight `F0·A + B`, with
//! `(A, B)` from Karis's analytic fit of the pre-integrated GGX environment BRDF (a function
//! of roughness and `n·v`): about F0 for a mirror seen head-on, rising toward 1 at grazing
//! angles, lower for rough surfaces.

use crate::deferred::geometry::view_depth;
use crate::deferred::settings::SsrSettings;
use crate::deferred::weights::specular_weight;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_scene::GBuffer;

/// `specular_indirect` by screen-space reflections of `lit` (the lit opaque image,
/// row-major, the sky where no surface is), the sky as the fallback.
pub fn screen_space_reflections(
    gbuffer: &GBuffer,
    lit: &[Vec3],
    sky: Vec3,
    settings: &SsrSettings,
) -> Vec<Vec3> {
    let depth = view_depth(gbuffer);
    let marcher = Marcher::new(gbuffer, &depth, settings);
    gbuffer
        .opaque
        .par_iter()
        .enumerate()
        .map(|(i, sp)| {
            let Some(sp) = sp else { return Vec3::ZERO };
            let v = -gbuffer.view_dir(i);
            let n_dot_v = sp.normal.dot(v);
            let weight = specular_weight(sp, n_dot_v);
            if sp.roughness > settings.max_roughness {
                return weight * sky;
            }
            let r = (2.0 * n_dot_v * sp.normal - v).normalize_or_zero();
            match marcher.march(sp.offset_origin(r), r) {
                Some(hit) => weight * lit[hit],
                None => weight * sky,
            }
        })
        .collect()
}

/// What a march needs of the frame.
struct Marcher<'a> {
    gbuffer: &'a GBuffer,
    depth: &'a [f32],
    view_projection: glam::Mat4,
    settings: &'a SsrSettings,
}

impl<'a> Marcher<'a> {
    fn new(gbuffer: &'a GBuffer, depth: &'a [f32], settings: &'a SsrSettings) -> Self {
        Self { gbuffer, depth, view_projection: gbuffer.camera.view_projection(), settings }
    }

    /// Pixel position and reciprocal view depth of a world point in front of the camera.
    fn project(&self, p: Vec3) -> (Vec2, f32) {
        let c = self.view_projection * p.extend(1.0);
        let cam = &self.gbuffer.camera;
        let s = Vec2::new(
            (c.x / c.w + 1.0) * 0.5 * cam.width as f32,
            (1.0 - c.y / c.w) * 0.5 * cam.height as f32,
        );
        (s, 1.0 / c.w)
    }

    /// Depth-buffer index at pixel position `s`, if on screen.
    fn index(&self, s: Vec2) -> Option<usize> {
        let cam = &self.gbuffer.camera;
        (s.x >= 0.0 && s.y >= 0.0 && s.x < cam.width as f32 && s.y < cam.height as f32)
            .then(|| s.y as usize * cam.width as usize + s.x as usize)
    }

    /// The largest `t` in [0, 1] for which `s0 + delta·t` is still inside `[0, size]`
    /// (`s0` inside).
    fn screen_exit(s0: Vec2, delta: Vec2, size: Vec2) -> f32 {
        let mut t = 1.0f32;
        for axis in 0..2 {
            let d = delta[axis];
            if d > 0.0 {
                t = t.min((size[axis] - s0[axis]) / d);
            } else if d < 0.0 {
                t = t.min(-s0[axis] / d);
            }
        }
        t.max(0.0)
    }

    /// The pixel the ray from `o` along unit `r` meets first in the depth buffer.
    fn march(&self, o: Vec3, r: Vec3) -> Option<usize> {
        let cam = &self.gbuffer.camera;
        let st = self.settings;
        let z0 = (o - cam.position).dot(cam.forward);
        let dz = r.dot(cam.forward);
        let near = cam.near * 1.01;
        if z0 <= near {
            return None;
        }
        let mut len = st.max_distance;
        if z0 + dz * len < near {
            len = (near - z0) / dz;
        }
        let (s0, k0) = self.project(o);
        let (s1, k1) = self.project(o + r * len);
        if !(s0.is_finite() && s1.is_finite() && k0.is_finite() && k1.is_finite()) {
            return None;
        }
        // March only the on-screen part, so that no step is spent (and no stride is
        // stretched) off screen.
        let exit = Self::screen_exit(s0, s1 - s0, Vec2::new(cam.width as f32, cam.height as f32));
        let delta = (s1 - s0) * exit;
        let k1 = k0 + (k1 - k0) * exit;
        let steps = ((delta.abs().max_element() / st.stride_px).ceil() as u32).clamp(1, st.max_steps.max(1));
        // Depth of the ray and of the buffer at parameter t along the screen segment.
        let at = |t: f32| -> Option<(usize, f32)> {
            let s = s0 + delta * t;
            let k = self.index(s)?;
            Some((k, 1.0 / (k0 + (k1 - k0) * t)))
        };
        let mut prev = 0.0f32;
        for i in 1..=steps {
            let t = i as f32 / steps as f32;
            let (k, z) = at(t)?;
            if z >= self.depth[k] {
                // Crossed: bisect between prev (in front) and t (behind).
                let (mut a, mut b) = (prev, t);
                for _ in 0..st.refine_steps {
                    let m = 0.5 * (a + b);
                    match at(m) {
                        Some((km, zm)) if zm >= self.depth[km] => b = m,
                        _ => a = m,
                    }
                }
                let (kb, zb) = at(b)?;
                // A hit needs the ray within the thickness behind the surface and arriving
                // at its front (this rejects the depth buffer's own staircase on the
                // surface the ray leaves, sampled at pixel centres).
                let front = self.gbuffer.opaque[kb].is_some_and(|sp| sp.normal.dot(r) < 0.0);
                if front && zb - self.depth[kb] < st.thickness {
                    return Some(kb);
                }
                // Passed behind a thin surface or along one: keep marching.
            }
            prev = t;
        }
        None
    }
}
