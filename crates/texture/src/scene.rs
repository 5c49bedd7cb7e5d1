//! Test scenes for the texture lab: planar surfaces seen through a pinhole camera, each an
//! exact screen→texture mapping with an analytic UV Jacobian per pixel.
//!
//! Every scene is a plane, so its screen→surface map is one projective matrix ([`Projective`],
//! `f64`), and the Jacobian `∂(u,v)/∂(x,y)` follows in closed form from the rational map:
//! `∂u/∂x = (A·W − U·G)/W²` for `[U, V, W] = [x, y, 1]·m`. Pixel `(i, j)` covers the square
//! `[i, i+1) × [j, j+1)` of continuous screen coordinates; filters are evaluated at its centre.
//!
//! | scene | surface | texture |
//! |---|---|---|
//! | [`SceneKind::Checkerboard`] | infinite ground plane to the horizon, sky above | 8×8 checks, repeat |
//! | [`SceneKind::ThesisQuad`] | the thesis's quad ([`QuadScene::thesis_default`]) | checks (the thesis's chess-board.bmp) |
//! | [`SceneKind::ThesisCircuit`] | the thesis's quad | circuit board ([`crate::procedural`]) |
//! | [`SceneKind::ThesisEarth`] | the thesis's quad | earth-like map ([`crate::procedural`]) |
//! | [`SceneKind::TiltedQuad`] | a square tilted by an angle about the horizontal axis | bricks albedo |
//! | [`SceneKind::ZonePlate`] | the ground plane again | zone plate `½ + ½·cos(k·r²)` |
//!
//! **The horizon.** Towards the horizon a pixel's footprint grows without bound. The ground
//! plane is therefore clipped at the depth where one pixel's footprint (the major axis of its
//! Jacobian, at the image's centre column) spans [`FAR_CLIP_TILES`] texture tiles; beyond that
//! depth, up to the horizon and above it, pixels show the background (sky) and are excluded
//! from every metric. Pixels whose footprint is only partly on the surface (quad edges, the
//! clip line) are excluded too ([`crate::reference::Reference::mask`]), so that errors measure
//! filtering, not edge antialiasing, which no texture filter does.

// `!(x > t)` is deliberate: it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub use crate::error::SceneError;

use crate::error::size_error;
use crate::filter::{Filter, FilterSpec, FilterVisitor};
use crate::mapping::{MappingError, Projective, QuadScene};
use crate::mip::{Texture, Wrap};
use crate::procedural::{bricks_texture, checker_texture, zone_plate_texture};
use glam::{DVec2, DVec3, Vec2, Vec3, Vec4};
use rayon::prelude::*;
use renderlab_core::counter::{NoCount, Tally};
use renderlab_core::image::check_dimensions;
use renderlab_core::Image;

/// A ground-plane pixel is clipped once its footprint spans this many texture tiles.
pub const FAR_CLIP_TILES: f64 = 1.0;

/// Which part of the plane a scene shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Region {
    /// The unit square of surface coordinates (a quad).
    UnitSquare,
    /// The whole plane in front of the eye up to a camera depth `max_depth`. The plane is
    /// `n·p = c` in camera space; rays are `p = z·((x − cx)/f, (y − cy)/f, 1)`.
    Plane {
        /// Plane normal (camera space).
        n: DVec3,
        /// Plane offset.
        c: f64,
        /// Principal point x (pixels).
        cx: f64,
        /// Principal point y (pixels).
        cy: f64,
        /// Focal length (pixels).
        f: f64,
        /// Largest depth shown.
        max_depth: f64,
    },
}

/// A plane seen through a pinhole camera: the exact map from continuous pixel coordinates to
/// surface coordinates, and the part of the plane that exists.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarView {
    /// Pixel coordinates → surface coordinates.
    pub to_uv: Projective,
    /// What is surface.
    pub region: Region,
}

/// The mapped point of one pixel and its Jacobian (surface units per pixel).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    /// Surface coordinate.
    pub uv: DVec2,
    /// `∂(u,v)/∂x`.
    pub duv_dx: DVec2,
    /// `∂(u,v)/∂y`.
    pub duv_dy: DVec2,
}

impl PlanarView {
    /// A ground-like plane through camera-space point `origin` spanned by `eu`, `ev` (camera
    /// units per surface unit), seen by a camera with focal length `f` and principal point
    /// `(cx, cy)` (pixels; y down), shown up to depth `max_depth`. Errors for non-finite input,
    /// parallel axes, or an eye in the plane.
    pub fn plane(
        origin: DVec3,
        eu: DVec3,
        ev: DVec3,
        f: f64,
        (cx, cy): (f64, f64),
        max_depth: f64,
    ) -> Result<Self, MappingError> {
        let finite = origin.is_finite() && eu.is_finite() && ev.is_finite() && f.is_finite();
        if !(finite && cx.is_finite() && cy.is_finite()) || max_depth.is_nan() {
            return Err(MappingError::NonFinite { what: "plane or camera" });
        }
        if !(f > 0.0) {
            return Err(MappingError::NonFinite { what: "focal length" });
        }
        let n = eu.cross(ev);
        if !(n.length() > 1e-12 * eu.length() * ev.length()) {
            return Err(MappingError::Collinear([1, 2, 3]));
        }
        let c = n.dot(origin);
        if !(c.abs() > 1e-9 * n.length() * origin.length().max(1e-300)) || origin.length() == 0.0 {
            return Err(MappingError::EyeInPlane);
        }
        let k = |e: DVec3| [f * e.x + cx * e.z, f * e.y + cy * e.z, e.z];
        let uv_to_px = Projective { m: [k(eu), k(ev), k(origin)] };
        let to_uv = uv_to_px.inverse()?;
        Ok(PlanarView { to_uv, region: Region::Plane { n, c, cx, cy, f, max_depth } })
    }

    /// The thesis-style quad `scene` (validated: degenerate quads, an eye in the plane and
    /// corners behind the eye are errors), its screen plane mapped to pixels by
    /// `screen = a·pixel + b`.
    pub fn quad(scene: &QuadScene, a: f64, b: DVec2) -> Result<Self, MappingError> {
        if !(a.is_finite() && a > 0.0 && b.is_finite()) {
            return Err(MappingError::NonFinite { what: "pixel-to-screen transform" });
        }
        let screen_to_uv = scene.mapping()?;
        let px_to_screen = Projective { m: [[a, 0.0, 0.0], [0.0, a, 0.0], [b.x, b.y, 1.0]] };
        Ok(PlanarView { to_uv: px_to_screen.then(&screen_to_uv), region: Region::UnitSquare })
    }

    /// An axis-aligned view: pixel `(x, y)` ↦ `(x/w, y/h)` over the unit square, a 1:1 mapping
    /// of a `w × h` texture.
    pub fn screen_aligned(w: f64, h: f64) -> Self {
        PlanarView {
            to_uv: Projective { m: [[1.0 / w, 0.0, 0.0], [0.0, 1.0 / h, 0.0], [0.0, 0.0, 1.0]] },
            region: Region::UnitSquare,
        }
    }

    /// Surface coordinate seen at continuous pixel position `(x, y)`, or `None` where there is
    /// no surface (background, beyond the horizon or the clip depth, behind the eye).
    #[inline]
    pub fn hit(&self, x: f64, y: f64) -> Option<DVec2> {
        let uv = self.to_uv.map(x, y)?;
        match self.region {
            Region::UnitSquare => ((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)).then_some(uv),
            Region::Plane { n, c, cx, cy, f, max_depth } => {
                let d = DVec3::new((x - cx) / f, (y - cy) / f, 1.0);
                let z = c / n.dot(d);
                (z > 0.0 && z <= max_depth).then_some(uv)
            }
        }
    }

    /// The footprint at `(x, y)` (analytic Jacobian), or `None` where there is no surface.
    #[inline]
    pub fn footprint(&self, x: f64, y: f64) -> Option<Footprint> {
        let uv = self.hit(x, y)?;
        let m = &self.to_uv.m;
        let h = self.to_uv.map_homogeneous(x, y);
        let w2 = h.z * h.z;
        let d =
            |r: usize| DVec2::new((m[r][0] * h.z - h.x * m[r][2]) / w2, (m[r][1] * h.z - h.y * m[r][2]) / w2);
        let fp = Footprint { uv, duv_dx: d(0), duv_dy: d(1) };
        (fp.duv_dx.is_finite() && fp.duv_dy.is_finite()).then_some(fp)
    }
}

/// The built-in scenes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SceneKind {
    /// The classic aliasing test: an infinite checkerboard plane receding to the horizon.
    Checkerboard,
    /// The thesis's quad (Fig. 4.1) with a checker texture, scaled to fill the frame.
    ThesisQuad,
    /// The thesis's quad with the circuit-board texture ([`crate::procedural::circuit_texture`]).
    ThesisCircuit,
    /// The thesis's quad with the earth-like map ([`crate::procedural::earth_texture`]).
    ThesisEarth,
    /// A square tilted by this many degrees (0 = facing the camera) with the bricks texture.
    TiltedQuad(f64),
    /// A zone plate on the ground plane.
    ZonePlate,
}

impl SceneKind {
    /// The default set: checkerboard, the thesis's quad with its three textures (checker,
    /// circuit, earth), quads at 0°, 45°, 70° and 85°, zone plate.
    pub fn defaults() -> Vec<SceneKind> {
        vec![
            SceneKind::Checkerboard,
            SceneKind::ThesisQuad,
            SceneKind::ThesisCircuit,
            SceneKind::ThesisEarth,
            SceneKind::TiltedQuad(0.0),
            SceneKind::TiltedQuad(45.0),
            SceneKind::TiltedQuad(70.0),
            SceneKind::TiltedQuad(85.0),
            SceneKind::ZonePlate,
        ]
    }

    /// Short name: `checkerboard`, `thesis_quad`, `quad_tilt_45`, `zone_plate`.
    pub fn name(&self) -> String {
        match self {
            SceneKind::Checkerboard => "checkerboard".into(),
            SceneKind::ThesisQuad => "thesis_quad".into(),
            SceneKind::ThesisCircuit => "thesis_quad_circuit".into(),
            SceneKind::ThesisEarth => "thesis_quad_earth".into(),
            SceneKind::TiltedQuad(t) => format!("quad_tilt_{t}"),
            SceneKind::ZonePlate => "zone_plate".into(),
        }
    }

    /// Parses [`SceneKind::name`]'s form (`quad_tilt_DEG` with DEG in [0, 89.9]).
    pub fn parse(s: &str) -> Result<SceneKind, SceneError> {
        match s.trim() {
            "checkerboard" => Ok(SceneKind::Checkerboard),
            "thesis_quad" => Ok(SceneKind::ThesisQuad),
            "thesis_quad_circuit" => Ok(SceneKind::ThesisCircuit),
            "thesis_quad_earth" => Ok(SceneKind::ThesisEarth),
            "zone_plate" => Ok(SceneKind::ZonePlate),
            other => {
                let deg = other
                    .strip_prefix("quad_tilt_")
                    .and_then(|d| d.parse::<f64>().ok())
                    .ok_or_else(|| SceneError::UnknownScene(other.to_string()))?;
                if !(0.0..=89.9).contains(&deg) {
                    return Err(size_error("tilt", format!("{deg}° must lie in [0, 89.9]")));
                }
                Ok(SceneKind::TiltedQuad(deg))
            }
        }
    }

    /// Whether the scene shows the ground plane up to the horizon.
    pub fn has_horizon(&self) -> bool {
        matches!(self, SceneKind::Checkerboard | SceneKind::ZonePlate)
    }
}

/// A rectangle of pixels (for zoomed crops).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width.
    pub w: u32,
    /// Height.
    pub h: u32,
}

/// One test scene: geometry, texture and frame.
#[derive(Clone, Debug)]
pub struct TestScene {
    /// Which scene.
    pub kind: SceneKind,
    /// One line for reports.
    pub description: String,
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// The exact mapping.
    pub view: PlanarView,
    /// The texture with its pyramid.
    pub texture: Texture,
    /// Texture repeats per surface unit (texture UV = `uv_scale` · surface coordinate).
    pub uv_scale: f64,
    /// Colour where there is no surface (linear).
    pub background: Vec3,
    /// Region near the horizon worth zooming into.
    pub horizon_crop: Option<Crop>,
}

/// Ground-plane camera: height above the plane, field of view and horizon placement.
struct Ground {
    f: f64,
    cx: f64,
    cy: f64,
    origin: DVec3,
    eu: DVec3,
    ev: DVec3,
}

/// The ground plane (y up in the world, camera 1 unit above it, pitched down so that the
/// horizon sits 22% below the top of the frame, 60° horizontal field of view), one texture
/// tile per `period` world units.
fn ground(width: u32, height: u32, period: f64) -> Ground {
    let (w, h) = (width as f64, height as f64);
    let f = 0.5 * w / (30f64).to_radians().tan();
    let (cx, cy) = (0.5 * w, 0.5 * h);
    let pitch = ((cy - 0.22 * h) / f).atan();
    let (s, c) = pitch.sin_cos();
    // Camera axes in world coordinates: right (1,0,0), down (0,−c,−s), forward (0,−s,c).
    let to_cam = |p: DVec3| DVec3::new(p.x, -c * p.y - s * p.z, -s * p.y + c * p.z);
    let eye_h = 1.0;
    Ground {
        f,
        cx,
        cy,
        origin: to_cam(DVec3::new(0.37 * period, -eye_h, 0.0)),
        eu: to_cam(DVec3::new(period, 0.0, 0.0)),
        ev: to_cam(DVec3::new(0.0, 0.0, period)),
    }
}

/// The depth at which the footprint at the centre column spans `tiles` surface units, found
/// by walking up the centre column towards the horizon.
fn clip_depth(g: &Ground, height: u32, tiles: f64) -> Result<f64, MappingError> {
    let open = PlanarView::plane(g.origin, g.eu, g.ev, g.f, (g.cx, g.cy), f64::INFINITY)?;
    let Region::Plane { n, c, .. } = open.region else { unreachable!("plane region") };
    let depth = |y: f64| c / n.dot(DVec3::new(0.0, (y - g.cy) / g.f, 1.0));
    let mut y = height as f64;
    let mut last = depth(y);
    // 0.01-pixel steps: bounded by the frame height.
    let steps = (height as usize + 1) * 100;
    for _ in 0..steps {
        let Some(fp) = open.footprint(g.cx, y) else { break };
        let major = fp.duv_dx.length().max(fp.duv_dy.length());
        let z = depth(y);
        if !(major <= tiles) || !(z > 0.0) {
            break;
        }
        last = z;
        y -= 0.01;
    }
    Ok(last)
}

impl TestScene {
    /// Builds `kind` at `width × height` (each side 8..=4096). The textures: checker 256² with
    /// 8×8 checks, bricks 256², zone plate 512².
    pub fn new(kind: SceneKind, width: u32, height: u32) -> Result<TestScene, SceneError> {
        check_dimensions("frame", width as u64, height as u64)
            .map_err(|e| size_error("frame", e.to_string()))?;
        if !(8..=4096).contains(&width) || !(8..=4096).contains(&height) {
            return Err(size_error("frame", format!("{width}x{height}: each side must lie in 8..=4096")));
        }
        let (w, h) = (width as f64, height as f64);
        let sky = Vec3::new(0.55, 0.7, 0.9);
        let crop = || {
            let horizon = 0.22 * h;
            let cw = (width / 4).max(8);
            let ch = (height / 6).max(8);
            Some(Crop {
                x: (width - cw) / 2,
                y: ((horizon as i64 - 2).clamp(0, (height - ch) as i64)) as u32,
                w: cw,
                h: ch,
            })
        };
        match kind {
            SceneKind::Checkerboard | SceneKind::ZonePlate => {
                let (tex, period, what) = if kind == SceneKind::Checkerboard {
                    (checker_texture(256, 8)?, 2.0, "8×8-check 256² texture, one tile per 2 units")
                } else {
                    (zone_plate_texture(512)?, 4.0, "512² zone plate, one tile per 4 units")
                };
                let g = ground(width, height, period);
                let far = clip_depth(&g, height, FAR_CLIP_TILES)?;
                let view = PlanarView::plane(g.origin, g.eu, g.ev, g.f, (g.cx, g.cy), far)?;
                Ok(TestScene {
                    kind,
                    description: format!(
                        "ground plane, camera 1 unit up, 60° field of view, {what}; clipped at depth {far:.1} \
                         where a pixel spans {FAR_CLIP_TILES} tile(s); sky beyond"
                    ),
                    width,
                    height,
                    view,
                    texture: Texture::new(tex, Wrap::Repeat),
                    uv_scale: 1.0,
                    background: sky,
                    horizon_crop: crop(),
                })
            }
            SceneKind::ThesisQuad | SceneKind::ThesisCircuit | SceneKind::ThesisEarth => {
                let q = QuadScene::thesis_default();
                let s = q.project()?;
                let (lo, hi) =
                    s.iter().fold((DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)), |a, p| {
                        (a.0.min(*p), a.1.max(*p))
                    });
                let ext = hi - lo;
                // Fill 90% of the frame, centred.
                let a = (ext.x / (0.9 * w)).max(ext.y / (0.9 * h));
                let b = 0.5 * (lo + hi) - a * DVec2::new(0.5 * w, 0.5 * h);
                let (tex, uv_scale, what) = match kind {
                    SceneKind::ThesisCircuit => (
                        crate::procedural::circuit_texture(512, 1)?,
                        1.0,
                        "circuit-board texture (512², 32×32 routing cells) once",
                    ),
                    SceneKind::ThesisEarth => {
                        (crate::procedural::earth_texture(512, 1)?, 1.0, "earth-like map (512²) once")
                    }
                    _ => (checker_texture(256, 8)?, 2.0, "checker texture (256², 8×8 checks) repeated 2×2"),
                };
                Ok(TestScene {
                    kind,
                    description: format!(
                        "the thesis's quad P1(80,50,1600) P2(240,80,1500) P3(200,280,1100) P4(40,250,1200), \
                         eye (130,240,0), {what}"
                    ),
                    width,
                    height,
                    view: PlanarView::quad(&q, a, b)?,
                    texture: Texture::new(tex, Wrap::Repeat),
                    uv_scale,
                    background: Vec3::splat(0.18),
                    horizon_crop: None,
                })
            }
            SceneKind::TiltedQuad(tilt) => {
                if !(0.0..=89.9).contains(&tilt) {
                    return Err(size_error("tilt", format!("{tilt}° must lie in [0, 89.9]")));
                }
                let f = 0.9 * w.min(h);
                let (st, ct) = tilt.to_radians().sin_cos();
                let d = 1.0;
                let corner = |lx: f64, ly: f64| DVec3::new(lx, ly * ct, d - ly * st);
                let q = QuadScene {
                    corners: [corner(-0.5, -0.5), corner(0.5, -0.5), corner(0.5, 0.5), corner(-0.5, 0.5)],
                    eye: DVec3::ZERO,
                    screen_z: f,
                };
                // Screen coordinates are centred on the optical axis.
                let view = PlanarView::quad(&q, 1.0, DVec2::new(-0.5 * w, -0.5 * h))?;
                Ok(TestScene {
                    kind,
                    description: format!(
                        "unit square tilted {tilt}° about the horizontal axis, 1 unit from the eye, \
                         bricks albedo (256²) repeated 2×2"
                    ),
                    width,
                    height,
                    view,
                    texture: Texture::new(bricks_texture(256)?, Wrap::Repeat),
                    uv_scale: 2.0,
                    background: Vec3::splat(0.18),
                    horizon_crop: None,
                })
            }
        }
    }

    /// The same scene with the user's `texture` (linear RGBA, any size) in place of the
    /// built-in one, shown once per surface unit and repeated: the camera, the surface and the
    /// mapping stay as they are. `label` (the file name) goes into the description.
    pub fn with_texture(mut self, texture: Image<Vec4>, label: &str) -> TestScene {
        self.description = format!(
            "{}; texture replaced by {label} ({}×{}) once per surface unit",
            self.description,
            texture.width(),
            texture.height()
        );
        self.texture = Texture::new(texture, Wrap::Repeat);
        self.uv_scale = 1.0;
        self
    }

    /// A scene from its parts (for tests and user experiments).
    pub fn custom(view: PlanarView, texture: Texture, uv_scale: f64, width: u32, height: u32) -> TestScene {
        TestScene {
            kind: SceneKind::TiltedQuad(0.0),
            description: "custom".into(),
            width,
            height,
            view,
            texture,
            uv_scale,
            background: Vec3::ZERO,
            horizon_crop: None,
        }
    }

    /// Texture coordinate of a surface coordinate, reduced to one period for repeat textures
    /// (in `f64`, so that the `f32` result keeps its precision far out on the plane).
    #[inline]
    pub fn tex_uv(&self, uv: DVec2) -> DVec2 {
        let t = uv * self.uv_scale;
        match self.texture.wrap() {
            Wrap::Repeat => t - t.floor(),
            Wrap::Clamp => t,
        }
    }

    /// Per pixel, the texture coordinate and its Jacobian at the pixel centre (`None` off the
    /// surface), computed exactly in `f64` and rounded to `f32`.
    pub fn surface(&self) -> Surface {
        let px = Image::from_fn_par(self.width, self.height, |x, y| {
            match self.view.footprint(x as f64 + 0.5, y as f64 + 0.5) {
                Some(fp) => {
                    let s = self.uv_scale;
                    let uv = self.tex_uv(fp.uv);
                    SurfacePixel {
                        uv: uv.as_vec2(),
                        duv_dx: (fp.duv_dx * s).as_vec2(),
                        duv_dy: (fp.duv_dy * s).as_vec2(),
                        hit: true,
                    }
                }
                None => SurfacePixel::default(),
            }
        });
        Surface { pixels: px }
    }

    /// The image of the scene through `filter` at the pixels' centres (background off the
    /// surface); rows in parallel.
    pub fn render<F: Filter>(&self, surface: &Surface, filter: &F) -> Image<Vec3> {
        let bg = self.background;
        let tex = &self.texture;
        Image::from_fn_par(self.width, self.height, |x, y| {
            let p = surface.pixels.get(x, y);
            if p.hit {
                filter.sample(tex, p.uv, p.duv_dx, p.duv_dy, &mut NoCount).truncate()
            } else {
                bg
            }
        })
    }

    /// [`TestScene::render`] through the filter a [`FilterSpec`] names.
    pub fn render_spec(&self, surface: &Surface, spec: &FilterSpec) -> Image<Vec3> {
        struct Render<'a>(&'a TestScene, &'a Surface);
        impl FilterVisitor for Render<'_> {
            type Output = Image<Vec3>;
            fn visit<F: Filter>(self, filter: &F) -> Image<Vec3> {
                self.0.render(self.1, filter)
            }
        }
        spec.visit(Render(self, surface))
    }

    /// [`TestScene::count_fetches`] of the filter a [`FilterSpec`] names.
    pub fn count_fetches_spec(&self, surface: &Surface, spec: &FilterSpec) -> (u64, u64) {
        struct Count<'a>(&'a TestScene, &'a Surface);
        impl FilterVisitor for Count<'_> {
            type Output = (u64, u64);
            fn visit<F: Filter>(self, filter: &F) -> (u64, u64) {
                self.0.count_fetches(self.1, filter)
            }
        }
        spec.visit(Count(self, surface))
    }

    /// Texel fetches of `filter` over the frame and the number of surface pixels (rows in
    /// parallel, summed in row order).
    pub fn count_fetches<F: Filter>(&self, surface: &Surface, filter: &F) -> (u64, u64) {
        let tex = &self.texture;
        let rows: Vec<(u64, u64)> = (0..self.height)
            .into_par_iter()
            .map(|y| {
                let mut t = Tally::default();
                let mut n = 0;
                for p in surface.pixels.row(y) {
                    if p.hit {
                        let _ = filter.sample(tex, p.uv, p.duv_dx, p.duv_dy, &mut t);
                        n += 1;
                    }
                }
                (t.0, n)
            })
            .collect();
        rows.iter().fold((0, 0), |a, r| (a.0 + r.0, a.1 + r.1))
    }
}

/// One pixel of a [`Surface`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfacePixel {
    /// Texture coordinate at the centre.
    pub uv: Vec2,
    /// `∂uv/∂x` in texture UV per pixel.
    pub duv_dx: Vec2,
    /// `∂uv/∂y`.
    pub duv_dy: Vec2,
    /// Whether the centre sees the surface.
    pub hit: bool,
}

/// Per-pixel texture coordinates and Jacobians of a scene: what a rasteriser would hand to
/// the texture filter.
#[derive(Clone, Debug)]
pub struct Surface {
    /// The pixels.
    pub pixels: Image<SurfacePixel>,
}

impl Surface {
    /// Number of pixels whose centre sees the surface.
    pub fn hits(&self) -> usize {
        self.pixels.pixels().iter().filter(|p| p.hit).count()
    }
}
