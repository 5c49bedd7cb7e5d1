//! One test scene built for a frame ([`TestScene`]), and its rendering through a filter: the
//! per-pixel surface ([`Surface`]), the image at the pixels' centres and the texel fetches.

use super::catalogue::Parts;
use super::catalogue::SceneKind;
use super::surface::{Surface, SurfacePixel};
use super::view::{Crop, PlanarView};
use crate::error::{size_error, SceneError};
use crate::filter::{Filter, FilterSpec, FilterVisitor};
use crate::mip::{Texture, Wrap};
use glam::{DVec2, Vec3, Vec4};
use rayon::prelude::*;
use renderlab_core::counter::{NoCount, Tally};
use renderlab_core::image::check_dimensions;
use renderlab_core::Image;

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

impl TestScene {
    /// Builds `kind` at `width × height` (each side 8..=4096). The textures: checker 256² with
    /// 8×8 checks, bricks 256², zone plate 512².
    pub fn new(kind: SceneKind, width: u32, height: u32) -> Result<TestScene, SceneError> {
        check_dimensions("frame", width as u64, height as u64)
            .map_err(|e| size_error("frame", e.to_string()))?;
        if !(8..=4096).contains(&width) || !(8..=4096).contains(&height) {
            return Err(size_error("frame", format!("{width}x{height}: each side must lie in 8..=4096")));
        }
        let Parts { description, view, texture, uv_scale, background, horizon_crop } =
            kind.build(width, height)?;
        Ok(TestScene { kind, description, width, height, view, texture, uv_scale, background, horizon_crop })
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
