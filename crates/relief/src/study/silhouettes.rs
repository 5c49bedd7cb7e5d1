//! The silhouette study: for analytic shapes carrying relief (a sphere, a cylinder side-on and
//! oblique, a finite patch at a grazing view) at several height scales, each method's coverage
//! against the exact reference's mask, its UV error where both cover, its frame time and its
//! height fetches.
//!
//! Coverage is counted in pixels: *false covered* where the method shows the surface and the
//! reference does not, *false empty* the other way round, both also as a share of the
//! *silhouette band*, the pixels where the reference's coverage differs from the base shape's
//! (what a method with the flat outline of its mesh gets wrong). UV error is the mean distance
//! between the method's hit UV and the reference's on the pixels both cover, in texels along
//! the surface: each UV component scaled by the mapping's stretch at the reference's hit
//! (so a UV step near a sphere's pole, where u shrinks, counts as the distance it spans).
//! Depth error is the frame's view depth (its pixel-depth offset) against the reference's
//! distance from the eye, in texels' world length, on the same pixels.
//! Methods run on the scalar kernel (the silhouette technique has only that one), so their
//! times compare the methods, not the kernels.

use crate::curved::any_shape::AnyShape;
use crate::curved::cylinder::Cylinder;
use crate::curved::frame::{shape_frame, stretch, surface_point, ShapeFrame};
use crate::curved::patch::Patch;
use crate::curved::reference::{reference_frame, ShapeHit};
use crate::curved::shape::ReliefShape;
use crate::curved::sphere::Sphere;
use crate::error::ReliefError;
use crate::kernel::Kernel;
use crate::render::material::ReliefMaterial;
use crate::render::shade::{Frame, FrameInput};
use crate::render::{render, render_into};
use crate::techniques::Technique;
use glam::{DVec2, DVec3, Vec2, Vec3};
use renderlab_core::scene::Lighting;
use renderlab_core::{Camera, Image, SurfacePoint};
use std::time::Instant;

/// One view of the study: a shape, the camera and the light.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Short name for tables and files.
    pub name: &'static str,
    /// The shape.
    pub shape: AnyShape,
    /// The camera.
    pub camera: Camera,
    /// Unit direction toward the light (world space).
    pub light: Vec3,
}

/// The study's views at `width × height`: a unit sphere whose pole leans 25° from the view
/// toward the top (so its outline runs within 25° of the equator, where its mapping is
/// isometric within 10%), a cylinder side-on and seen obliquely from above (its ends out of
/// the frame), and a 1.4 × 2.3 patch on the floor seen at a grazing angle, running from below
/// the frame's bottom (as a room's floor or wall runs past the view) to its far and side
/// edges in view.
pub fn cases(width: u32, height: u32) -> Vec<Case> {
    let light = Vec3::new(0.4, 0.7, 0.6).normalize();
    let lean = 25f64.to_radians();
    let sphere = Sphere {
        centre: DVec3::ZERO,
        radius: 1.0,
        axis: DVec3::new(0.0, lean.sin(), lean.cos()),
        tiles: 2.0,
    };
    let cylinder =
        Cylinder { base: DVec3::new(0.0, -3.0, 0.0), axis: DVec3::Y, radius: 0.6, length: 6.0, tiles: 4.0 };
    let patch = Patch {
        origin: DVec3::new(-0.7, 0.0, 1.8),
        tangent: DVec3::X,
        bitangent: DVec3::NEG_Z,
        world_per_uv: 1.0,
        uv_min: DVec2::ZERO,
        uv_max: DVec2::new(1.4, 2.3),
    };
    vec![
        Case {
            name: "sphere",
            shape: AnyShape::Sphere(sphere),
            camera: Camera::look_at(Vec3::new(0.0, 0.0, 3.2), Vec3::ZERO, width, height),
            light,
        },
        Case {
            name: "cylinder-side",
            shape: AnyShape::Cylinder(cylinder),
            camera: Camera::look_at(Vec3::new(0.0, 0.0, 2.4), Vec3::ZERO, width, height),
            light,
        },
        Case {
            name: "cylinder-oblique",
            shape: AnyShape::Cylinder(cylinder),
            camera: Camera::look_at(Vec3::new(0.0, 1.5, 2.0), Vec3::new(0.0, -0.2, 0.0), width, height),
            light,
        },
        Case {
            name: "patch-grazing",
            shape: AnyShape::Patch(patch),
            camera: Camera::look_at(Vec3::new(0.0, 0.22, 2.0), Vec3::new(0.0, -0.05, -0.1), width, height),
            light,
        },
    ]
}

/// What the study measures and where it writes images.
#[derive(Clone, Debug)]
pub struct StudyConfig {
    /// The methods, each on the scalar kernel.
    pub methods: Vec<Technique>,
    /// Height scales (UV per unit depth) the material is rendered at.
    pub height_scales: Vec<f32>,
    /// Timed frames per method (the median is reported).
    pub repeats: usize,
}

/// One row of the study's table.
#[derive(Clone, Debug, PartialEq)]
pub struct SilhouetteRow {
    /// The case's name.
    pub case: String,
    /// The height scale.
    pub height_scale: f32,
    /// The method's canonical name (`reference` for the reference itself).
    pub method: String,
    /// Pixels of the silhouette band (reference coverage differing from the base shape's).
    pub band: usize,
    /// Pixels the method covers and the reference does not.
    pub false_covered: usize,
    /// Pixels the reference covers and the method does not.
    pub false_empty: usize,
    /// Of those, the pixels where the base shape is absent (the ray meets the relief through
    /// a patch's side): out of reach of every method that starts at the base surface.
    pub beside: usize,
    /// Pixels both cover.
    pub both: usize,
    /// Mean UV error on the pixels both cover, in texels.
    pub uv_error_texels: f64,
    /// Mean error of the frame's view depth (the pixel-depth offset) against the reference's
    /// distance from the eye on the pixels both cover, in texels' world length.
    pub depth_error_texels: f64,
    /// Median frame time, milliseconds.
    pub frame_ms: f64,
    /// Height fetches per pixel showing the base shape.
    pub fetches_per_pixel: f64,
}

impl SilhouetteRow {
    /// `n` as a percentage of the band (0 for an empty band).
    pub fn percent_of_band(&self, n: usize) -> f64 {
        if self.band == 0 {
            0.0
        } else {
            100.0 * n as f64 / self.band as f64
        }
    }
}

/// The lighting and background of the study's frames.
const BACKGROUND: Vec3 = Vec3::new(0.08, 0.09, 0.12);

/// One case at one height scale, prepared: the frame input and the reference.
pub struct Prepared {
    /// The base shape's frame input.
    pub frame: ShapeFrame,
    /// The reference per pixel.
    pub reference: Vec<ShapeHit>,
    /// The material at the case's height scale.
    pub material: ReliefMaterial,
    /// Milliseconds the reference took (one run).
    pub reference_ms: f64,
}

/// Builds the frame input and the reference of `case` with `material` at `height_scale`.
pub fn prepare(case: &Case, material: &ReliefMaterial, height_scale: f32) -> Prepared {
    let mut material = material.clone();
    material.height_scale = height_scale;
    let frame = shape_frame(&case.shape, &case.camera, case.light);
    let hints: Vec<Option<Vec2>> = frame.points.iter().map(|p| p.map(|sp| sp.uv)).collect();
    let start = Instant::now();
    let reference = reference_frame(&case.shape, &material.height, height_scale, &case.camera, &hints);
    let reference_ms = start.elapsed().as_secs_f64() * 1e3;
    Prepared { frame, reference, material, reference_ms }
}

impl Prepared {
    fn input(&self) -> FrameInput<'_> {
        FrameInput::new(self.frame.width, self.frame.height, &self.frame.points)
            .with_patches(&self.frame.patches)
    }

    /// Renders `method` (scalar kernel), counting fetches.
    pub fn render(&self, method: Technique) -> Result<Frame, ReliefError> {
        let mats = std::slice::from_ref(&self.material);
        render(self.input(), mats, method, Kernel::Scalar, Lighting::default(), BACKGROUND, true)
    }

    /// The reference shaded by the frame's own code: each covered pixel's surface point with
    /// the reference's hit UV (the base point's frame where the pixel shows the base shape,
    /// the frame at the hit's foot where the ray entered the relief through a patch's side),
    /// lit with normal mapping there; its depth and view depth are the reference's.
    pub fn reference_image(&self, case: &Case) -> Result<Frame, ReliefError> {
        let w = self.frame.width as usize;
        let points: Vec<Option<SurfacePoint>> = self
            .reference
            .iter()
            .zip(&self.frame.points)
            .enumerate()
            .map(|(i, (hit, base))| {
                hit.covered.then(|| match base {
                    Some(sp) => SurfacePoint { uv: hit.uv, ..*sp },
                    None => {
                        let (px, py) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                        let (d, ddx, ddy) =
                            crate::curved::frame::ray_with_differentials(&case.camera, px, py);
                        let light = case.light.as_dvec3();
                        let (sp, _) = surface_point(
                            &case.shape,
                            hit.uv.as_dvec2(),
                            hit.distance as f64,
                            d,
                            ddx,
                            ddy,
                            light,
                        );
                        sp
                    }
                })
            })
            .collect();
        let input = FrameInput::new(self.frame.width, self.frame.height, &points);
        let normal = Technique::parse("normal").expect("a registry technique");
        let mats = std::slice::from_ref(&self.material);
        let mut frame = render(input, mats, normal, Kernel::Scalar, Lighting::default(), BACKGROUND, false)?;
        // The reference's own depths: below the base surface, and from the eye.
        for (i, hit) in self.reference.iter().enumerate().filter(|(_, h)| h.covered) {
            frame.depth.pixels_mut()[i] = hit.depth;
            frame.view_depth.pixels_mut()[i] = hit.distance;
        }
        Ok(frame)
    }

    /// The row of `method`'s `frame` against the reference.
    pub fn compare(&self, case: &Case, method: &str, frame: &Frame, frame_ms: f64) -> SilhouetteRow {
        let texels = Vec2::new(self.material.height.width() as f32, self.material.height.height() as f32);
        let (mut band, mut fc, mut fe, mut beside, mut both, mut err) = (0, 0, 0, 0, 0, 0.0f64);
        let mut depth_err = 0.0f64;
        let texel_world = case.shape.world_per_uv() / texels.x.max(texels.y) as f64;
        for (i, (r, base)) in self.reference.iter().zip(&self.frame.points).enumerate() {
            let shown = frame.mask.pixels()[i];
            band += (r.covered != base.is_some()) as usize;
            fc += (shown && !r.covered) as usize;
            fe += (!shown && r.covered) as usize;
            beside += (!shown && r.covered && base.is_none()) as usize;
            if shown && r.covered {
                both += 1;
                let s = stretch(&case.shape, &case.shape.geometry(r.uv.as_dvec2())).as_vec2();
                err += ((frame.uv.pixels()[i] - r.uv) * texels * s).length() as f64;
                depth_err += (frame.view_depth.pixels()[i] as f64 - r.distance as f64).abs() / texel_world;
            }
        }
        let entries = self.frame.points.iter().flatten().count().max(1);
        SilhouetteRow {
            case: case.name.to_string(),
            height_scale: self.material.height_scale,
            method: method.to_string(),
            band,
            false_covered: fc,
            false_empty: fe,
            beside,
            both,
            uv_error_texels: if both > 0 { err / both as f64 } else { 0.0 },
            depth_error_texels: if both > 0 { depth_err / both as f64 } else { 0.0 },
            frame_ms,
            fetches_per_pixel: frame.fetches as f64 / entries as f64,
        }
    }

    /// The median time of `repeats` frames of `method` (scalar kernel, not counting).
    pub fn time(&self, method: Technique, repeats: usize) -> Result<f64, ReliefError> {
        let mats = std::slice::from_ref(&self.material);
        let mut frame = Frame::blank(self.frame.width, self.frame.height, BACKGROUND);
        let mut times = Vec::with_capacity(repeats);
        // One frame unmeasured first: caches and the thread pool warm.
        for k in 0..=repeats {
            let start = Instant::now();
            render_into(
                self.input(),
                mats,
                method,
                Kernel::Scalar,
                Lighting::default(),
                BACKGROUND,
                false,
                &mut frame,
            )?;
            if k > 0 {
                times.push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
        Ok(renderlab_core::stats::median(&mut times))
    }
}

/// Runs the study over `cases`: per case and height scale, a `reference` row (its own time,
/// one run) and one row per method. Each frame's image goes to `on_image` with a file name
/// for it, `CASE_SCALE_METHOD.png` (the reference and every method).
pub fn silhouette_study(
    cases: &[Case],
    material: &ReliefMaterial,
    config: &StudyConfig,
    mut on_image: impl FnMut(String, &Image<Vec3>),
) -> Result<Vec<SilhouetteRow>, ReliefError> {
    let mut rows = Vec::new();
    let name =
        |case: &str, scale: f32, method: &str| format!("{case}_{scale}_{}.png", method.replace(':', "-"));
    for case in cases {
        for &scale in &config.height_scales {
            let prepared = prepare(case, material, scale);
            let reference = prepared.reference_image(case)?;
            rows.push(prepared.compare(case, "reference", &reference, prepared.reference_ms));
            on_image(name(case.name, scale, "reference"), &reference.image);
            for &method in &config.methods {
                let frame = prepared.render(method)?;
                let ms = prepared.time(method, config.repeats.max(1))?;
                rows.push(prepared.compare(case, &method.name(), &frame, ms));
                on_image(name(case.name, scale, &method.name()), &frame.image);
            }
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::complexity::ComplexityParams;

    fn bricks(size: u32) -> ReliefMaterial {
        let m = renderlab_texture::materials::material("bricks", size).expect("built-in material");
        ReliefMaterial::new(&m, &ComplexityParams::default(), false)
    }

    fn tech(name: &str) -> Technique {
        Technique::parse(name).expect("a registry technique")
    }

    /// Through the frame, on a flat patch without bounds, the silhouette technique's frame is
    /// POM's on the scalar kernel, pixel for pixel (image, UV, depth, view depth, mask) and
    /// fetch for fetch.
    #[test]
    fn the_frame_equals_pom_on_a_flat_unbounded_patch() {
        let patch = Patch {
            origin: DVec3::ZERO,
            tangent: DVec3::X,
            bitangent: DVec3::NEG_Z,
            world_per_uv: 1.0,
            uv_min: DVec2::NEG_INFINITY,
            uv_max: DVec2::INFINITY,
        };
        let case = Case {
            name: "flat",
            shape: AnyShape::Patch(patch),
            camera: Camera::look_at(Vec3::new(0.3, 0.6, 2.0), Vec3::new(0.0, 0.0, -1.0), 64, 48),
            light: Vec3::new(0.3, 0.8, 0.5).normalize(),
        };
        let p = prepare(&case, &bricks(64), 0.06);
        for layers in [8, 24, 32] {
            let a = p.render(tech(&format!("pom:{layers}"))).unwrap();
            let b = p.render(tech(&format!("silhouette:{layers}"))).unwrap();
            assert_eq!(a.image, b.image);
            assert_eq!(a.uv, b.uv);
            assert_eq!(a.depth, b.depth);
            assert_eq!(a.view_depth, b.view_depth);
            assert_eq!(a.mask, b.mask);
            assert_eq!(a.fetches, b.fetches);
        }
    }

    /// On the sphere at 64 layers, the silhouette technique's wrong pixels (false covered and
    /// false empty) stay within 10% of the silhouette band, where POM, with the flat outline,
    /// gets the whole band wrong. The bound: the quadric sag under-estimates the sphere's by
    /// its quartic term and the layers step over contacts thinner than a layer, each costing
    /// a pixel here and there along the outline, never a band of them.
    #[test]
    fn the_sphere_outline_is_right_where_pom_is_wrong() {
        let case = cases(128, 96)[0];
        let p = prepare(&case, &bricks(128), 0.08);
        let pom = p.compare(&case, "pom", &p.render(tech("pom:32")).unwrap(), 0.0);
        let sil = p.compare(&case, "silhouette", &p.render(tech("silhouette:64")).unwrap(), 0.0);
        assert!(pom.band > 100, "a band to measure: {}", pom.band);
        assert_eq!((pom.false_covered, pom.false_empty), (pom.band, 0), "POM keeps the flat outline");
        let wrong = sil.false_covered + sil.false_empty;
        assert!(wrong * 10 <= sil.band, "{wrong} wrong pixels of a band of {}", sil.band);
        assert!(
            sil.uv_error_texels < pom.uv_error_texels,
            "{} vs {}",
            sil.uv_error_texels,
            pom.uv_error_texels
        );
    }

    /// The finite patch seen at a grazing angle: rays that leave its far and side edges are
    /// misses, so POM's wrongly covered pixels there mostly go.
    #[test]
    fn the_patch_edges_are_cut() {
        let case = cases(128, 96)[3];
        let p = prepare(&case, &bricks(64), 0.08);
        let pom = p.compare(&case, "pom", &p.render(tech("pom:32")).unwrap(), 0.0);
        let sil = p.compare(&case, "silhouette", &p.render(tech("silhouette:64")).unwrap(), 0.0);
        assert!(pom.false_covered > 50, "{}", pom.false_covered);
        assert!(
            sil.false_covered * 10 <= pom.false_covered,
            "{} vs {}",
            sil.false_covered,
            pom.false_covered
        );
        assert!(sil.false_covered + sil.false_empty < pom.false_covered + pom.false_empty);
    }

    /// Hostile pixels through the frame (NaN and infinite UVs and view directions, grazing
    /// views, NaN and huge curvatures, empty and NaN rectangles): no panic, and each pixel
    /// shows a hit in range or the background.
    #[test]
    fn hostile_pixels_render_as_hits_or_background() {
        use crate::render::shade::PatchInfo;
        let bad = [f32::NAN, f32::INFINITY, -1e30, 0.0, 1e-7];
        let mut points = Vec::new();
        let mut patches = Vec::new();
        for (i, &a) in bad.iter().enumerate() {
            for (j, &b) in bad.iter().enumerate() {
                points.push(Some(SurfacePoint {
                    uv: Vec2::new(a, 0.5),
                    view_ts: Vec3::new(1.0, b, 1e-6),
                    light_ts: Vec3::Z,
                    ..SurfacePoint::default()
                }));
                points.push(Some(SurfacePoint {
                    uv: Vec2::new(0.25, 0.5),
                    view_ts: Vec3::new(a, b, 0.3),
                    light_ts: Vec3::Z,
                    ..SurfacePoint::default()
                }));
                for _ in 0..2 {
                    patches.push(PatchInfo {
                        curvature: Vec2::new(bad[(i + j) % 5], 1e30),
                        uv_min: Vec2::splat(bad[j]),
                        uv_max: Vec2::splat(bad[(i * 3 + 1) % 5].abs()),
                        world_per_uv: bad[i],
                    });
                }
            }
        }
        let n = points.len() as u32;
        let mats = [bricks(16)];
        let input = FrameInput::new(n, 1, &points).with_patches(&patches);
        let f = render(
            input,
            &mats,
            tech("silhouette:16"),
            Kernel::Scalar,
            Lighting::default(),
            BACKGROUND,
            true,
        )
        .expect("renders");
        for i in 0..n as usize {
            if f.mask.pixels()[i] {
                assert!((0.0..=1.0 + 1e-6).contains(&f.depth.pixels()[i]), "pixel {i}");
            } else {
                assert_eq!(f.image.pixels()[i], BACKGROUND, "pixel {i}");
            }
        }
    }
}
