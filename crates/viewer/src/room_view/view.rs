//! The room view: the room on the window's device: the GPU renderer draws each frame straight into a texture
//! that a paint callback copies into egui's pass ([`crate::blit`]; the texture is also
//! registered with egui as an image, for the tests' and other views), so a frame never
//! crosses the CPU. The layer-count heat map (key B) is the renderer's debug
//! target, read back and coloured on the CPU (a debug view, not a timed one). The split
//! screen's two pictures are drawn by `split_draw` ([`RoomView::draw_split`]).

use super::targets::{display_texture, Scratch, Target, DISPLAY_FORMAT};
use crate::blit::PictureBlit;
use crate::compose::ErrorCompose;
use crate::error::ViewerError;
use crate::look_and_feel::Backdrops;
use crate::techniques::MAX_LAYERS;
use glam::Vec3;
use renderlab_core::{Camera, Image, Material, Scene};
use renderlab_gpu::{GpuContext, ReliefRenderer};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{Map, ReliefMaterial, Technique};

/// The room's scene, its prepared materials and the renderer drawing them on the window's
/// device.
pub struct RoomView {
    pub(super) ctx: &'static GpuContext,
    scene: Scene,
    complexity: ComplexityParams,
    materials: Vec<ReliefMaterial>,
    with_cone: bool,
    pub(super) renderer: ReliefRenderer<'static>,
    pub(super) target: Option<Target>,
    /// The split screen's error mode: the technique's and the reference's pictures.
    pub(super) scratch: Option<Scratch>,
    pub(super) compose: Option<ErrorCompose>,
    /// The copy of the picture into egui's pass, for the window's format.
    blit: Option<PictureBlit>,
    /// The HUD panels whose backgrounds the copy paints this frame.
    backdrops: Backdrops,
    /// Whether cone maps are built on another thread (the window) or at once (scripts, tests).
    background: bool,
    /// The cone-map build in flight.
    cone_build: Option<ConeBuild>,
    /// Counts replacements of the materials, so that a build started from older ones is
    /// dropped.
    generation: u64,
}

/// Materials with cone maps being prepared on another thread.
struct ConeBuild {
    rx: std::sync::mpsc::Receiver<Vec<ReliefMaterial>>,
    generation: u64,
    started: std::time::Instant,
}

impl RoomView {
    /// Prepares `scene` for the device of `render_state`. The context over that device lives
    /// as long as the process (the renderer borrows it; a viewer opens one).
    pub fn new(render_state: &egui_wgpu::RenderState, scene: Scene) -> Result<Self, ViewerError> {
        let ctx = GpuContext::from_parts(
            &render_state.adapter,
            render_state.device.clone(),
            render_state.queue.clone(),
        )?;
        let ctx: &'static GpuContext = Box::leak(Box::new(ctx));
        let complexity = ComplexityParams::default();
        let materials = prepare(&scene.materials, &complexity, false);
        let renderer = ReliefRenderer::new(ctx, &scene, &materials)?;
        Ok(Self {
            ctx,
            scene,
            complexity,
            materials,
            with_cone: false,
            renderer,
            target: None,
            scratch: None,
            compose: None,
            blit: None,
            backdrops: Backdrops::default(),
            background: false,
            cone_build: None,
            generation: 0,
        })
    }

    /// What the device is (for the HUD).
    pub fn context(&self) -> &'static GpuContext {
        self.ctx
    }

    /// The scene shown.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Builds cone maps on another thread from now on (the window), so that the first cone
    /// technique does not stop the window for the seconds the build takes; until they are
    /// there, frames that need them fail with [`ViewerError::Pending`].
    pub fn build_maps_in_background(&mut self, on: bool) {
        self.background = on;
    }

    /// Makes sure the materials have the maps `technique` reads: the cone map is computed on
    /// the first use of a cone technique, at once or on another thread (see
    /// [`RoomView::build_maps_in_background`]).
    pub(super) fn ensure_maps(&mut self, technique: Technique) -> Result<(), ViewerError> {
        if !technique.needs_map(Map::Cone) || self.with_cone {
            return Ok(());
        }
        if !self.background {
            let materials = prepare(&self.scene.materials, &self.complexity, true);
            return self.install_cone_materials(materials);
        }
        if let Some(build) = &self.cone_build {
            match build.rx.try_recv() {
                Ok(materials) if build.generation == self.generation => {
                    self.cone_build = None;
                    return self.install_cone_materials(materials);
                }
                Err(std::sync::mpsc::TryRecvError::Empty) => {
                    return Err(ViewerError::Pending(format!(
                        "building the relaxed cone maps for {} ({:.0} s)…",
                        technique.name(),
                        build.started.elapsed().as_secs_f64()
                    )));
                }
                // Built from materials replaced since, or the thread failed: start again.
                _ => self.cone_build = None,
            }
        }
        let (tx, rx) = std::sync::mpsc::channel();
        let (materials, params) = (self.scene.materials.clone(), self.complexity);
        std::thread::Builder::new()
            .name("cone maps".into())
            .spawn(move || {
                let _ = tx.send(prepare(&materials, &params, true));
            })
            .map_err(|e| ViewerError::Message(format!("cannot start the cone-map build: {e}")))?;
        self.cone_build =
            Some(ConeBuild { rx, generation: self.generation, started: std::time::Instant::now() });
        Err(ViewerError::Pending(format!("building the relaxed cone maps for {}…", technique.name())))
    }

    /// Takes `materials` (prepared with cone maps) with the height scales now in force.
    fn install_cone_materials(&mut self, mut materials: Vec<ReliefMaterial>) -> Result<(), ViewerError> {
        for (m, old) in materials.iter_mut().zip(&self.materials) {
            m.height_scale = old.height_scale;
        }
        self.materials = materials;
        self.with_cone = true;
        self.generation += 1;
        self.rebuild()
    }

    /// Uploads the scene and materials again (after a change of light, height or maps).
    fn rebuild(&mut self) -> Result<(), ViewerError> {
        let offset = self.renderer.pixel_depth_offset();
        self.renderer = ReliefRenderer::new(self.ctx, &self.scene, &self.materials)?;
        self.renderer.set_pixel_depth_offset(offset);
        Ok(())
    }

    /// Whether the displaced depth goes into the depth buffer (the pixel-depth offset; see
    /// `ReliefRenderer::set_pixel_depth_offset`). Kept across rebuilds.
    pub fn set_pixel_depth_offset(&mut self, on: bool) {
        self.renderer.set_pixel_depth_offset(on);
    }

    /// Whether the pixel-depth offset is on.
    pub fn pixel_depth_offset(&self) -> bool {
        self.renderer.pixel_depth_offset()
    }

    /// Draws `technique` from `camera` into the display texture (resized to the camera) and
    /// returns its egui id and the pass's GPU time where the device has timestamps.
    pub fn draw(
        &mut self,
        render_state: &egui_wgpu::RenderState,
        camera: &Camera,
        technique: Technique,
    ) -> Result<(egui::TextureId, Option<f64>), ViewerError> {
        self.ensure_maps(technique)?;
        let target = self.target(render_state, camera)?;
        let (view, id) = (target.view.clone(), target.id);
        let gpu_ms = self.renderer.render_to_view(&view, DISPLAY_FORMAT, camera, technique)?;
        Ok((id, gpu_ms))
    }

    /// The paint callback that copies the last picture drawn into egui's pass over `rect`
    /// (the window's format from `render_state`); `None` before a picture is drawn.
    pub fn picture_callback(
        &mut self,
        render_state: &egui_wgpu::RenderState,
        rect: egui::Rect,
    ) -> Option<egui::PaintCallback> {
        let format = render_state.target_format;
        if self.blit.as_ref().is_none_or(|b| b.format() != format) {
            self.blit = Some(PictureBlit::new(&self.ctx.device, format));
            if let Some(t) = &mut self.target {
                t.blit_group = None;
            }
        }
        let blit = self.blit.as_ref()?;
        let target = self.target.as_mut()?;
        let group = target
            .blit_group
            .get_or_insert_with(|| blit.bind_group(&self.ctx.device, &target.view, &target.codes))
            .clone();
        self.backdrops.begin(true);
        Some(blit.callback(rect, group, self.backdrops.clone()))
    }

    /// The HUD panels whose backgrounds the picture's copy paints (see
    /// [`crate::look_and_feel`]); the room starts each frame with `begin(false)`, and making
    /// the copy's callback turns it on.
    pub fn backdrops(&self) -> &Backdrops {
        &self.backdrops
    }

    /// The display texture at the camera's size (made, or remade and registered with egui
    /// again, when the size changes). egui gets the texture's code view: egui blends in
    /// gamma space and takes what it samples as sRGB codes, so the sRGB view (which decodes
    /// to linear on sampling) would show the picture too dark.
    pub(super) fn target(
        &mut self,
        render_state: &egui_wgpu::RenderState,
        camera: &Camera,
    ) -> Result<&Target, ViewerError> {
        let (w, h) = (camera.width, camera.height);
        self.ctx.check_size("the window", w, h)?;
        let resized = self.target.as_ref().is_none_or(|t| (t.texture.width(), t.texture.height()) != (w, h));
        if resized {
            let (texture, view, codes) = display_texture(self.ctx, "room display", w, h);
            let mut egui_renderer = render_state.renderer.write();
            let id = match self.target.take() {
                Some(old) => {
                    egui_renderer.update_egui_texture_from_wgpu_texture(
                        &self.ctx.device,
                        &codes,
                        wgpu::FilterMode::Linear,
                        old.id,
                    );
                    old.id
                }
                None => {
                    egui_renderer.register_native_texture(&self.ctx.device, &codes, wgpu::FilterMode::Linear)
                }
            };
            self.target = Some(Target { texture, view, codes, id, blit_group: None });
        }
        self.target.as_ref().ok_or_else(|| ViewerError::Message("no display target".into()))
    }

    /// The planned layer count per pixel of `technique` from `camera`, coloured from blue (one
    /// layer) through green and yellow to red ([`MAX_LAYERS`] or more); the background dark.
    pub fn heat_map(
        &mut self,
        camera: &Camera,
        technique: Technique,
    ) -> Result<egui::ColorImage, ViewerError> {
        self.ensure_maps(technique)?;
        let frame = self.renderer.render(camera, technique)?;
        let mut rgba = Vec::with_capacity(frame.layers.pixels().len() * 4);
        for (&l, &covered) in frame.layers.pixels().iter().zip(frame.mask.pixels()) {
            let c = if covered { heat(l as u32) } else { [20, 20, 20] };
            rgba.extend_from_slice(&[c[0], c[1], c[2], 255]);
        }
        Ok(egui::ColorImage::from_rgba_unmultiplied([camera.width as usize, camera.height as usize], &rgba))
    }

    /// The last frame drawn into the display texture, as 8-bit sRGB.
    pub fn read_frame(&self) -> Result<Image<[u8; 3]>, ViewerError> {
        let target = self.target.as_ref().ok_or_else(|| ViewerError::Message("no frame drawn yet".into()))?;
        let bytes = renderlab_gpu::read_rgba8(self.ctx, &target.texture)?;
        let rgb = bytes.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect();
        Image::from_vec(target.texture.width(), target.texture.height(), rgb)
            .map_err(|e| ViewerError::Message(e.to_string()))
    }

    /// Sets every material's height scale (the relief's depth in units of a texture repeat).
    pub fn set_height_scale(&mut self, scale: f32) -> Result<(), ViewerError> {
        if !scale.is_finite() || !(0.0..=1.0).contains(&scale) {
            return Err(ViewerError::Message(format!("height scale {scale} is outside 0..=1")));
        }
        for m in &mut self.materials {
            m.height_scale = scale;
        }
        self.rebuild()
    }

    /// The mean height scale of the materials (the slider's starting value).
    pub fn height_scale(&self) -> f32 {
        self.materials.iter().map(|m| m.height_scale).sum::<f32>() / self.materials.len().max(1) as f32
    }

    /// Points the light along `to_light` (toward the light; normalised here).
    pub fn set_light(&mut self, to_light: Vec3) -> Result<(), ViewerError> {
        let dir = to_light.normalize_or_zero();
        if dir == Vec3::ZERO || !dir.is_finite() {
            return Err(ViewerError::Message("the light direction must be a non-zero vector".into()));
        }
        self.scene.light.to_light = dir;
        self.rebuild()
    }

    /// Recomputes the complexity maps with `params` (the adaptive techniques' input).
    pub fn set_complexity(&mut self, params: ComplexityParams) -> Result<(), ViewerError> {
        let scales: Vec<f32> = self.materials.iter().map(|m| m.height_scale).collect();
        self.complexity = params;
        self.materials = prepare(&self.scene.materials, &self.complexity, self.with_cone);
        self.generation += 1;
        for (m, s) in self.materials.iter_mut().zip(scales) {
            m.height_scale = s;
        }
        self.rebuild()
    }

    /// Puts `material` on every surface of the room (a user's own maps).
    pub fn set_material(&mut self, material: Material) -> Result<(), ViewerError> {
        let mut scene = self.scene.clone();
        for m in &mut scene.materials {
            *m = material.clone();
        }
        let materials = prepare(&scene.materials, &self.complexity, self.with_cone);
        let mut renderer = ReliefRenderer::new(self.ctx, &scene, &materials)?;
        renderer.set_pixel_depth_offset(self.renderer.pixel_depth_offset());
        (self.scene, self.materials, self.renderer) = (scene, materials, renderer);
        self.generation += 1;
        Ok(())
    }
}

/// The relief inputs of each material.
fn prepare(materials: &[Material], params: &ComplexityParams, with_cone: bool) -> Vec<ReliefMaterial> {
    materials.iter().map(|m| ReliefMaterial::new(m, params, with_cone)).collect()
}

/// The heat-map colour of `layers`: blue → cyan → green → yellow → red over 1..=MAX_LAYERS.
pub fn heat(layers: u32) -> [u8; 3] {
    if layers == 0 {
        return [0, 0, 0];
    }
    let t = ((layers - 1) as f32 / (MAX_LAYERS - 1) as f32).clamp(0.0, 1.0) * 4.0;
    let stops = [[0.0, 0.0, 1.0], [0.0, 1.0, 1.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
    let i = (t.floor() as usize).min(3);
    let f = t - i as f32;
    let c: [f32; 3] = std::array::from_fn(|k| stops[i][k] * (1.0 - f) + stops[i + 1][k] * f);
    c.map(|v| (v * 255.0).round() as u8)
}
