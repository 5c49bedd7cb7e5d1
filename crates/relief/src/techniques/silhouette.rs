//! Silhouette POM: parallax occlusion mapping along a curved ray, so that relief on curved and
//! finite surfaces shows at the silhouette (the curved-ray relief mapping of Oliveira and
//! Policarpo, on POM's layered march).
//!
//! Near the entry point, the top surface lies below its tangent plane by the quadric sag
//! `½ κ ρ²` (UV units) at UV distance `ρ` along a direction of normal curvature `κ`
//! (Euler's formula on the principal directions T and B: `κ ρ² = κ_T Δu² + κ_B Δv²`). The
//! straight tangent-space ray at depth parameter `t` has moved `Δuv = t · dp` (`dp` POM's UV
//! offset per unit depth), so its depth below the curved top, in relief units, is
//! `r(t) = t − c t²` with `c = ½ (κ_T dp.x² + κ_B dp.y²) / height_scale`. The march takes `n`
//! equal steps of `t` over `[0, T]`: where `4c ≤ 1` the ray reaches the relief's bottom
//! (`r = 1`) at `T = 2 / (1 + √(1 − 4c))` and must hit; otherwise it comes back out of the
//! top surface at `T = 1/c`, and a ray that is still above the relief there is a miss (the
//! silhouette). A ray whose step leaves the patch's UV rectangle before it meets the relief,
//! or whose hit lies outside it, is a miss too. POM's interpolation then finishes the hit
//! between the last two samples, in `(uv, r)`.
//!
//! With no curvature (`c = 0`, `T = 1`) and an unbounded patch, every sample and the
//! interpolation are POM's own arithmetic, so the hit is POM's bit for bit.

use super::descriptor::{Descriptor, Entry, Param, WithTracer};
use crate::kernel::Kernel;
use crate::march::layered::{interpolate, March};
use crate::trace::{uv_per_depth, RayContext, ReliefHit, ReliefInputs, ReliefTechnique, Shading};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// POM along the ray bent by the surface's curvature, with misses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Silhouette {
    /// Number of layers (samples along the curved ray).
    pub layers: u32,
}

/// Whether `uv` lies in the context's UV rectangle (false for NaN).
#[inline]
fn contains(ctx: &RayContext, uv: Vec2) -> bool {
    uv.cmpge(ctx.uv_min).all() && uv.cmple(ctx.uv_max).all()
}

impl Silhouette {
    /// Traces the ray entering at `uv0` toward the eye `v` with the pixel's context `ctx`
    /// (its curvature and UV rectangle; the footprint is not read).
    #[inline]
    pub fn march<C: Counter>(
        &self,
        inp: &ReliefInputs,
        uv0: Vec2,
        v: Vec3,
        ctx: &RayContext,
        counter: &mut C,
    ) -> ReliefHit {
        if !(uv0.is_finite() && contains(ctx, uv0)) {
            return ReliefHit::miss();
        }
        let n = self.layers.max(1);
        let dp = uv_per_depth(v, inp.height_scale);
        let k = ctx.curvature;
        let c = 0.5 * (k.x * dp.x * dp.x + k.y * dp.y * dp.y) / inp.height_scale;
        let c = if c.is_finite() { c } else { 0.0 };
        // The march's length in t, and whether its end is where the ray leaves the top.
        let (span, exits) = if c == 0.0 {
            (1.0, false)
        } else if 4.0 * c <= 1.0 {
            (2.0 / (1.0 + (1.0 - 4.0 * c).sqrt()), false)
        } else {
            (1.0 / c, true)
        };
        // `span · (1/n)` rather than `span / n`: POM's layer depth when span is 1.
        let dt = span * (1.0 / n as f32);
        let step = dp * dt;
        let depth_at = |t: f32| t - c * t * t;
        let src = inp.height;
        let mut uv = uv0;
        let mut map = src.depth(uv, counter);
        let (mut prev_uv, mut prev_map) = (uv, map);
        let mut i = 0u32;
        let mut t = 0.0f32;
        let mut depth = depth_at(t);
        // POM's loop: stop at the first sample at or below the relief, or after n steps.
        while depth < map && i < n {
            prev_uv = uv;
            prev_map = map;
            i += 1;
            t = i as f32 * dt;
            uv = uv0 + step * i as f32;
            map = src.depth(uv, counter);
            depth = depth_at(t);
            if depth < map && !contains(ctx, uv) {
                return ReliefHit::miss();
            }
        }
        let crossed = i < n || depth >= map;
        if !crossed && exits {
            return ReliefHit::miss();
        }
        let prev_depth = if i == 0 { 0.0 } else { depth_at(t - dt) };
        let m = March { prev_uv, prev_map, prev_layer: prev_depth, uv, map, layer: depth };
        let (hit_uv, hit_depth) = interpolate(&m);
        if !(hit_uv.is_finite() && contains(ctx, hit_uv)) {
            return ReliefHit::miss();
        }
        ReliefHit { uv: hit_uv, depth: hit_depth, layers: n }
    }
}

impl ReliefTechnique for Silhouette {
    const USES_CONTEXT: bool = true;

    /// Without a context: a flat, unbounded patch, where the march is POM's.
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        self.march(inp, uv, v, &RayContext::default(), counter)
    }

    #[inline]
    fn trace_in<C: Counter>(
        &self,
        inp: &ReliefInputs,
        uv: Vec2,
        v: Vec3,
        ctx: &RayContext,
        counter: &mut C,
    ) -> ReliefHit {
        self.march(inp, uv, v, ctx, counter)
    }
}

impl Entry for Silhouette {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "silhouette",
        summary: "POM along the ray bent by the surface's curvature (quadric sag): misses where the \
                  ray leaves the top surface or the patch, so relief shows at the silhouette",
        params: &[Param::count("LAYERS", 32, "number of layers")],
        needs: &[],
        kernels: &[Kernel::Scalar],
        shading: Shading::Lit,
    };

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(Silhouette { layers: v[0] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.layers]
    }

    fn layers(&self) -> u32 {
        self.layers
    }

    const WGSL: Option<&'static str> = Some(include_str!("silhouette.wgsl"));

    fn dispatch<A: WithTracer>(&self, _kernel: Kernel, action: A) -> A::Output {
        action.run(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::complexity::ComplexityParams;
    use crate::render::material::ReliefMaterial;
    use crate::techniques::pom::Pom;
    use renderlab_core::counter::Tally;

    fn bricks() -> ReliefMaterial {
        let m = renderlab_texture::materials::material("bricks", 64).expect("built-in material");
        ReliefMaterial::new(&m, &ComplexityParams::default(), false)
    }

    fn rays() -> impl Iterator<Item = (Vec2, Vec3)> {
        (0..4000).map(|i| {
            let a = (i as f32 * 0.37).rem_euclid(std::f32::consts::FRAC_PI_2);
            let phi = i as f32 * 2.399;
            let v = Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos());
            (Vec2::new((i as f32 * 0.618).fract() * 3.0 - 1.0, (i as f32 * 0.377).fract()), v)
        })
    }

    /// On a flat, unbounded patch the march is POM's, bit for bit, fetch for fetch, at every
    /// layer count (powers of two and not).
    #[test]
    fn equals_pom_on_flat_unbounded_patches() {
        let m = bricks();
        let inp = m.inputs();
        for layers in [1, 3, 8, 24, 32, 64] {
            for (uv, v) in rays() {
                let (mut a, mut b) = (Tally::default(), Tally::default());
                let s = Silhouette { layers }.trace(&inp, uv, v, &mut a);
                let p = Pom { layers }.trace(&inp, uv, v, &mut b);
                assert_eq!(s, p, "layers {layers}, uv {uv}, v {v}");
                assert_eq!(a.0, b.0, "fetches");
            }
        }
    }

    /// On a sphere-like patch a ray leaving at a grazing angle comes back out of the top
    /// surface over a low spot: a miss; looking straight down it hits as POM does.
    #[test]
    fn curvature_makes_grazing_rays_miss_and_leaves_steep_ones_alone() {
        let inp_m = bricks();
        let mut inp = inp_m.inputs();
        inp.height_scale = 0.05;
        let curved = RayContext { curvature: Vec2::splat(2.0), ..RayContext::default() };
        let t = Silhouette { layers: 64 };
        let grazing = Vec3::new(0.999, 0.0, 0.045).normalize();
        let (mut misses, mut n) = (0, 0);
        for (uv, _) in rays().take(400) {
            n += 1;
            misses += t.march(&inp, uv, grazing, &curved, &mut Tally::default()).is_miss() as u32;
            let down = t.march(&inp, uv, Vec3::Z, &curved, &mut Tally::default());
            assert_eq!(down, Pom { layers: 64 }.trace(&inp, uv, Vec3::Z, &mut Tally::default()));
        }
        // Only rays entering where the relief sits at the very top can meet it so close.
        assert!(misses > n / 2, "{misses} of {n}");
    }

    /// A step leaving the UV rectangle before the ray meets the relief is a miss; a hit
    /// inside the rectangle is kept.
    #[test]
    fn leaving_the_rectangle_is_a_miss() {
        let m = bricks();
        let inp = m.inputs();
        let t = Silhouette { layers: 32 };
        let v = Vec3::new(0.8, 0.0, 0.6);
        let uv = Vec2::new(0.5, 0.5);
        let free = t.trace(&inp, uv, v, &mut Tally::default());
        assert!(free.depth > 0.0);
        // The hit lies at smaller u (the ray moves against V.xy): a rectangle ending just
        // past the entry keeps it; one ending short of the hit loses it.
        let keep = RayContext {
            uv_min: Vec2::new(free.uv.x - 0.01, 0.0),
            uv_max: Vec2::ONE,
            ..RayContext::default()
        };
        assert_eq!(t.march(&inp, uv, v, &keep, &mut Tally::default()), free);
        let cut = RayContext { uv_min: Vec2::new(free.uv.x + 0.01, 0.0), ..keep };
        assert!(t.march(&inp, uv, v, &cut, &mut Tally::default()).is_miss());
    }

    /// NaN, infinite and grazing inputs never panic and give a hit in range or a miss.
    #[test]
    fn hostile_rays_give_a_hit_or_a_miss() {
        let m = bricks();
        let inp = m.inputs();
        let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, -1.0, 1e-30, 1e30];
        let patches = [
            RayContext::default(),
            RayContext { curvature: Vec2::new(1e30, -3.0), ..RayContext::default() },
            RayContext {
                curvature: Vec2::splat(f32::NAN),
                uv_min: Vec2::ZERO,
                uv_max: Vec2::ONE,
                footprint: f32::NAN,
            },
            RayContext { curvature: Vec2::new(-50.0, 0.0), ..RayContext::default() },
        ];
        for &a in &bad {
            for &b in &bad {
                for p in &patches {
                    for (uv, v) in [
                        (Vec2::new(a, 0.5), Vec3::new(0.6, 0.0, 0.8)),
                        (Vec2::new(0.5, 0.5), Vec3::new(a, b, 1e-7)),
                        (Vec2::new(0.5, 0.5), Vec3::new(1.0, 0.0, b)),
                    ] {
                        let h = Silhouette { layers: 16 }.march(&inp, uv, v, p, &mut Tally::default());
                        let is_miss = h.is_miss();
                        assert!(
                            is_miss || (h.uv.is_finite() && (0.0..=1.0 + 1e-6).contains(&h.depth)),
                            "{h:?}"
                        );
                    }
                }
            }
        }
    }
}
