//! Parallax occlusion mapping whose layer count follows the pixel's footprint and the view
//! angle, fading to normal mapping where the relief's parallax is sub-pixel.
//!
//! # The maths
//!
//! A ray entering the top surface at `uv` reaches the bottom of the relief (depth 1) at
//! `uv − s·V.xy / V.z` (`s` the height scale, `V` toward the eye in tangent space, `V.z`
//! clamped to [`MIN_VIEW_Z`]). That full-depth parallax, `L = s·|V.xy| / V.z` in UV, spans
//!
//! `p = L / f` pixels and `q = L · N` texels,
//!
//! with `f` the footprint (UV per pixel, [`RayContext::footprint`]) and `N` the depth map's
//! larger side. `p` holds both the distance (through `f`) and the view angle (through
//! `|V.xy| / V.z`, the tangent of the angle from the normal). The footprint is the longer of
//! the two screen derivatives, so `p` is at most `√2` times the parallax's true screen length
//! (the longer derivative is within `√2` of the Jacobian's largest singular value) and may
//! fall short of it where the parallax runs along the footprint's short axis.
//!
//! * **Layers**: `n = max(MIN, min(MAX, ⌈max(p, q)⌉))`: a layer step moves the march by at
//!   most one pixel on screen *and* one texel of the depth map wherever `MAX` allows. The
//!   pixel bound keeps the interpolated hit within a pixel of the crossing the march finds;
//!   the texel bound makes it find the right crossing: a step longer than a texel can pass
//!   over a brick's edge and stop on a later brick, and that error shows wherever the parallax
//!   spans pixels, however many texels a pixel covers (the filtered colour still moves with
//!   the bricks). So a head-on surface (`|V.xy|` small) pays only for the few layers its short
//!   parallax needs, a magnified one (`f` below a texel) for one per pixel, and a far, oblique
//!   one for one per texel until its parallax is sub-pixel, where the fade takes over. `n`
//!   never decreases as `p` or `q` grows. A `MIN` above `MAX` makes every count `MIN`.
//! * **Fade**: with the threshold `T` (`FADE` tenths of a pixel), a pixel with `p ≤ T` gets
//!   the undisplaced UV at depth 0 (normal mapping: no march, no fetch). Above it, the march's
//!   hit `(uv_h, d_h)` is pulled toward the entry by the weight `w = min(1, (p − T) / T)`:
//!   `(uv + w·(uv_h − uv), w·d_h)`, a point on the same straight ray (so the depth stays
//!   consistent with the UV for shadows and depth offsets). `w` rises linearly from 0 at `T`
//!   to 1 at `2T`, so the displacement has no jump at the threshold: with `n` fixed, the hit's
//!   screen displacement `w·d_h·p` changes by at most `3·Δp` pixels when `p` changes by `Δp`
//!   (`d_h ≤ 1`, `p ≤ 2T` in the band). `T = 0` turns the fade off (only `p = 0`, where every
//!   march stays at its entry, is left undisplaced).
//! * **March length**: the march covers the whole depth range `[0, 1]` (the built-in
//!   materials' depths span exactly that, so any shorter march could miss the hit); what
//!   follows the footprint is the step and, through the fade, the displacement.
//!
//! Where `max(p, q) ≥ MAX`, `p ≥ 2T` and `p > 0` the result is POM with `MAX` layers, bit for bit. A
//! frame that does not know the footprint (0, negative or NaN) gets exactly that; an infinite
//! footprint (or a zero height scale) gives normal mapping.

use super::descriptor::{Descriptor, Entry, Param, ParamKind, WithTracer, MAX_COUNT};
use crate::kernel::Kernel;
use crate::maps::height::HeightField;
use crate::march::layered::{interpolate, layer_step, layered_march};
use crate::trace::{RayContext, ReliefHit, ReliefInputs, ReliefTechnique, Shading, MIN_VIEW_Z};
use glam::{Vec2, Vec3};
use renderlab_core::counter::Counter;

/// POM with its layer count and displacement following the parallax's screen length.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PomLod {
    /// Most layers (where the parallax spans `MAX` pixels or texels or more).
    pub max: u32,
    /// Fewest layers of a displaced pixel.
    pub min: u32,
    /// Parallax below which the relief is left out, in tenths of a pixel; the fade spans from
    /// it to twice it.
    pub fade: u32,
}

/// The screen length in pixels of the full-depth parallax, `s·|V.xy| / V.z / f` (see the
/// module docs); +∞ where the footprint is unknown (0, negative or NaN), NaN where `view_ts`
/// is.
#[inline]
pub fn parallax_px(view_ts: Vec3, height_scale: f32, footprint: f32) -> f32 {
    if footprint.is_nan() || footprint <= 0.0 {
        return f32::INFINITY;
    }
    let vz = view_ts.z.max(MIN_VIEW_Z);
    height_scale * Vec2::new(view_ts.x, view_ts.y).length() / vz / footprint
}

/// The full-depth parallax in texels of `height`'s larger side, `s·|V.xy| / V.z · N`.
#[inline]
pub fn parallax_texels(view_ts: Vec3, height_scale: f32, height: &HeightField) -> f32 {
    let texels = height.width().max(height.height()) as f32;
    let vz = view_ts.z.max(MIN_VIEW_Z);
    height_scale * Vec2::new(view_ts.x, view_ts.y).length() / vz * texels
}

impl PomLod {
    /// The fade's threshold `T` in pixels.
    #[inline]
    pub fn threshold(&self) -> f32 {
        self.fade as f32 / 10.0
    }

    /// The layer count `max(MIN, min(MAX, ⌈p⌉))` for a parallax of `p` pixels or texels,
    /// whichever is more (NaN counts as 0).
    #[inline]
    pub fn layer_count(&self, p: f32) -> u32 {
        let n = if p >= self.max as f32 { self.max } else { p.ceil().max(0.0) as u32 };
        n.max(self.min).max(1)
    }

    /// The fade weight `min(1, (p − T) / T)` for `p > T` (1 when `T = 0`).
    #[inline]
    pub fn weight(&self, p: f32) -> f32 {
        let t = self.threshold();
        if t > 0.0 {
            ((p - t) / t).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }
}

impl ReliefTechnique for PomLod {
    const USES_CONTEXT: bool = true;

    /// Without a context the footprint is unknown: POM with `MAX` layers.
    #[inline]
    fn trace<C: Counter>(&self, inp: &ReliefInputs, uv: Vec2, v: Vec3, counter: &mut C) -> ReliefHit {
        self.trace_in(inp, uv, v, &RayContext::default(), counter)
    }

    fn trace_in<C: Counter>(
        &self,
        inp: &ReliefInputs,
        uv: Vec2,
        v: Vec3,
        ctx: &RayContext,
        counter: &mut C,
    ) -> ReliefHit {
        let p = parallax_px(v, inp.height_scale, ctx.footprint);
        if p.is_nan() || p <= self.threshold() {
            return ReliefHit { uv, depth: 0.0, layers: 0 };
        }
        let n = self.layer_count(p.max(parallax_texels(v, inp.height_scale, inp.height)));
        let m = layered_march(inp.height, uv, layer_step(v, inp.height_scale, n), n, counter);
        let (hit_uv, depth) = interpolate(&m);
        let w = self.weight(p);
        if w >= 1.0 {
            return ReliefHit { uv: hit_uv, depth, layers: n };
        }
        ReliefHit { uv: uv + (hit_uv - uv) * w, depth: depth * w, layers: n }
    }
}

impl Entry for PomLod {
    const DESCRIPTOR: Descriptor = Descriptor {
        name: "pom-lod",
        summary: "POM with layers that follow the parallax's length in pixels (footprint and view angle) and texels, fading to normal mapping where it is sub-pixel",
        params: &[
            Param::count(
                "MAX",
                32,
                "most layers, reached where the parallax spans MAX pixels or texels (default: POM-32, the thesis's baseline)",
            ),
            Param::count(
                "MIN",
                4,
                "fewest layers of a displaced pixel (default 4, the thesis's adaptive minimum: steps of at most a quarter of the relief's depth)",
            ),
            Param {
                name: "FADE",
                doc: "parallax in tenths of a pixel below which the relief is left out, faded in up to twice it (default 5: under half a pixel the shift stays inside the pixel's own filter footprint; 0: no fade)",
                kind: ParamKind::Count { default: 5, min: 0, max: MAX_COUNT },
            },
        ],
        needs: &[],
        kernels: &[Kernel::Scalar],
        shading: Shading::Lit,
    };

    fn from_params(v: &[u32]) -> Result<Self, String> {
        Ok(PomLod { max: v[0], min: v[1], fade: v[2] })
    }

    fn params(&self) -> Vec<u32> {
        vec![self.max, self.min, self.fade]
    }

    fn layers(&self) -> u32 {
        self.max.max(self.min)
    }

    const WGSL: Option<&'static str> = Some(include_str!("pom_lod.wgsl"));

    fn dispatch<A: WithTracer>(&self, _: Kernel, action: A) -> A::Output {
        action.run(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::complexity::ComplexityParams;
    use crate::render::material::ReliefMaterial;
    use crate::techniques::pom::Pom;
    use crate::techniques::Technique;
    use proptest::prelude::*;
    use renderlab_core::counter::Tally;

    const LOD: PomLod = PomLod { max: 32, min: 4, fade: 5 };

    fn bricks() -> ReliefMaterial {
        let m = renderlab_texture::materials::material("bricks", 64).expect("built-in material");
        ReliefMaterial::new(&m, &ComplexityParams::default(), false)
    }

    /// The unit vector `theta` degrees from the normal, turned `phi` radians about it.
    fn view(theta: f32, phi: f32) -> Vec3 {
        let t = theta.to_radians();
        Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
    }

    fn at(footprint: f32) -> RayContext {
        RayContext { footprint, ..RayContext::default() }
    }

    #[test]
    fn parses_with_its_defaults() {
        let t = Technique::parse("pom-lod").expect("in the registry");
        assert_eq!(t, Technique::PomLod(LOD));
        assert_eq!(t.name(), "pom-lod:32:4:5");
        assert_eq!(Technique::parse("pom-lod:16:2:0").unwrap(), Technique::PomLod(PomLod { max: 16, min: 2, fade: 0 }));
        assert!(Technique::parse("pom-lod:0").is_err());
    }

    /// The count never falls as the parallax grows, stays in MIN..=MAX, is MAX from MAX
    /// pixels on and ⌈p⌉ between the bounds; a MIN above MAX fixes it at MIN.
    #[test]
    fn layer_count_is_monotone_and_clamped() {
        for t in [LOD, PomLod { max: 64, min: 1, fade: 0 }, PomLod { max: 8, min: 8, fade: 5 }] {
            let mut last = 0;
            for i in 0..=40_000 {
                let p = i as f32 * 0.005;
                let n = t.layer_count(p);
                assert!(n >= last, "{t:?}: {n} after {last} at p = {p}");
                assert!((t.min..=t.max).contains(&n), "{t:?}: {n} at p = {p}");
                if p >= t.max as f32 {
                    assert_eq!(n, t.max);
                } else if p.ceil() as u32 >= t.min {
                    assert_eq!(n, p.ceil() as u32);
                }
                last = n;
            }
            assert_eq!(t.layer_count(f32::INFINITY), t.max);
            assert_eq!(t.layer_count(f32::NAN), t.min);
            assert_eq!(t.layer_count(-5.0), t.min);
        }
        let odd = PomLod { max: 4, min: 9, fade: 5 };
        assert!([0.0, 3.0, 50.0, f32::INFINITY].iter().all(|&p| odd.layer_count(p) == 9));
    }

    /// Traced: as the footprint shrinks (the parallax grows), the planned layers never fall.
    #[test]
    fn traced_layers_follow_the_footprint() {
        let mat = bricks();
        let inp = mat.inputs();
        let uv = Vec2::new(0.3, 0.7);
        for theta in [10.0, 45.0, 80.0] {
            let v = view(theta, 0.4);
            let mut last = 0;
            for k in 0..200 {
                let f = 0.5 * 0.95f32.powi(k);
                let hit = LOD.trace_in(&inp, uv, v, &at(f), &mut Tally::default());
                assert!(hit.layers >= last && hit.layers <= LOD.max, "{theta}°: {} after {last}", hit.layers);
                last = hit.layers;
            }
            assert_eq!(last, LOD.max.max(LOD.layer_count(parallax_texels(v, inp.height_scale, inp.height))));
        }
    }

    /// At or below the threshold the hit is the entry point at depth 0, with no fetch.
    #[test]
    fn sub_threshold_parallax_is_normal_mapping_without_fetches() {
        let mat = bricks();
        let inp = mat.inputs();
        for (i, theta) in [0.0, 20.0, 60.0, 85.0, 89.99].into_iter().enumerate() {
            let v = view(theta, 0.3 + i as f32);
            let uv = Vec2::new(0.1 * i as f32, 0.55);
            let full = parallax_px(v, inp.height_scale, 1.0);
            for scale in [0.0, 0.25, 0.999, 1.0] {
                // A footprint that makes the parallax `scale · T` (infinite for scale 0).
                let f = if scale == 0.0 { f32::INFINITY } else { full / (scale * LOD.threshold()) };
                let p = parallax_px(v, inp.height_scale, f);
                if p > LOD.threshold() {
                    continue; // rounding put it just above: not this test's case
                }
                let mut tally = Tally::default();
                let hit = LOD.trace_in(&inp, uv, v, &at(f), &mut tally);
                assert_eq!(hit, ReliefHit { uv, depth: 0.0, layers: 0 }, "{theta}° at p = {p}");
                assert_eq!(tally.0, 0, "{theta}°: fetched at p = {p}");
            }
        }
        // No relief at all (a zero height scale) is never marched either.
        let flat = ReliefInputs { height_scale: 0.0, ..inp };
        let mut tally = Tally::default();
        let hit = LOD.trace_in(&flat, Vec2::splat(0.2), view(70.0, 1.0), &at(1e-3), &mut tally);
        assert_eq!((hit.uv, hit.depth, tally.0), (Vec2::splat(0.2), 0.0, 0));
    }

    /// Across the fade (n fixed), the displaced point moves on screen by at most `3·Δp`
    /// pixels for a change `Δp` of the parallax (see the module docs), starting from no
    /// displacement at the threshold and ending on POM's hit at twice it.
    #[test]
    fn the_fade_is_continuous_in_the_parallax() {
        let mat = bricks();
        let inp = mat.inputs();
        let t = PomLod { max: 32, min: 8, fade: 10 };
        for (k, theta) in [40.0, 65.0, 80.0].into_iter().enumerate() {
            let v = view(theta, 2.0 + k as f32);
            let uv = Vec2::new(0.37, 0.21 + 0.2 * k as f32);
            let full = parallax_px(v, inp.height_scale, 1.0);
            let pom = Pom { layers: t.layer_count(parallax_texels(v, inp.height_scale, inp.height)) };
            let target = pom.trace(&inp, uv, v, &mut Tally::default());
            let mut last: Option<(f32, f32)> = None;
            for i in 0..=3000 {
                let p = 3.0 * t.threshold() * i as f32 / 3000.0;
                let f = full / p;
                let p = parallax_px(v, inp.height_scale, f);
                let hit = t.trace_in(&inp, uv, v, &at(f), &mut Tally::default());
                let shift = (hit.uv - uv).length() / f; // pixels on screen
                if p > t.threshold() {
                    assert_eq!(hit.layers, pom.layers, "{theta}°: n changed at p = {p}");
                }
                if p >= 2.0 * t.threshold() {
                    assert_eq!(hit, target, "{theta}°: not POM's hit at p = {p}");
                }
                if let Some((p0, s0)) = last {
                    let bound = 3.0 * (p - p0).abs() + 1e-4;
                    assert!((shift - s0).abs() <= bound, "{theta}°: jump {} px over Δp {}", shift - s0, p - p0);
                }
                last = Some((p, shift));
            }
        }
    }

    /// Where the parallax is long (or the footprint unknown) the result is POM-MAX's, bit for
    /// bit, fetches included.
    #[test]
    fn long_parallax_is_pom_max() {
        let mat = bricks();
        let inp = mat.inputs();
        let pom = Pom { layers: LOD.max };
        for i in 0..300 {
            let v = view(30.0 + (i % 56) as f32, i as f32 * 2.4);
            let uv = Vec2::new((i as f32 * 0.618).fract(), (i as f32 * 0.382).fract());
            let mut want_tally = Tally::default();
            let want = pom.trace(&inp, uv, v, &mut want_tally);
            for f in [1e-7, 0.0, -1.0, f32::NAN] {
                let mut tally = Tally::default();
                assert_eq!(LOD.trace_in(&inp, uv, v, &at(f), &mut tally), want, "footprint {f}");
                assert_eq!(tally.0, want_tally.0);
            }
            assert_eq!(LOD.trace(&inp, uv, v, &mut Tally::default()), want);
        }
    }

    fn hostile_footprint() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(0.0f32),
            Just(-0.0f32),
            Just(f32::NAN),
            Just(f32::INFINITY),
            Just(f32::NEG_INFINITY),
            Just(-1.0f32),
            Just(f32::MIN_POSITIVE),
            Just(f32::MAX),
            any::<u32>().prop_map(f32::from_bits),
            (1e-6f32..1.0),
        ]
    }

    proptest! {
        /// Any footprint, grazing and below-horizon views, any parameters: bounded work, a
        /// depth in [0, 1] and a finite UV.
        #[test]
        fn hostile_inputs_stay_bounded(
            f in hostile_footprint(),
            theta in prop_oneof![0.0f32..90.5, Just(90.0f32), Just(89.999f32)],
            phi in 0.0f32..6.3,
            u in -4.0f32..4.0,
            w in -4.0f32..4.0,
            max in 1u32..64,
            min in 1u32..64,
            fade in 0u32..40,
        ) {
            let mat = bricks();
            let inp = mat.inputs();
            let t = PomLod { max, min, fade };
            let mut tally = Tally::default();
            let hit = t.trace_in(&inp, Vec2::new(u, w), view(theta, phi), &at(f), &mut tally);
            let most = max.max(min);
            prop_assert!(hit.layers <= most);
            prop_assert!(tally.0 <= most as u64 + 1, "{} fetches", tally.0);
            prop_assert!((0.0..=1.0).contains(&hit.depth), "depth {}", hit.depth);
            prop_assert!(hit.uv.is_finite(), "uv {:?}", hit.uv);
        }
    }
}
