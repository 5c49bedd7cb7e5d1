//! The geometry pass: every instance rasterized into a visibility buffer (instance,
//! triangle, perspective-correct barycentrics), each visible pixel resolved once through
//! [`HybridScene::shading_point`] into the G-buffer.
//!
//! Opaque instances are drawn first, back faces culled, into the opaque layer. Translucent
//! instances (`PbrMaterial::is_translucent`) are then drawn two-sided against the opaque
//! depth: per pixel the `translucent_layers` nearest translucent surfaces in front of the
//! opaque one are kept, nearest first. The nearest goes to `GBuffer::translucent` (the
//! stage contract); all of them feed the sorted forward pass.

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use renderlab_core::{Camera, Mesh};
use renderlab_raster::visibility::{Source, VisFrame, NO_TRIANGLE};
use renderlab_scene::{GBuffer, HybridScene, ShadingPoint};

/// A scene made ready for rasterizing: every instance's world-space mesh built once, so
/// that repeated frames (and the shadow maps) do not rebuild them.
pub struct PreparedScene<'s> {
    /// The scene.
    pub scene: &'s HybridScene,
    /// World-space mesh of every instance, in instance order.
    pub world: Vec<Mesh>,
    /// Whether each instance's material is translucent.
    pub translucent: Vec<bool>,
    /// Bounds of every world-space vertex (`(min, max)`; an empty scene has min > max).
    pub bounds: (Vec3, Vec3),
}

impl<'s> PreparedScene<'s> {
    /// Builds the world meshes (in parallel). Call `scene.validate()` first: the scene's
    /// references are trusted here.
    pub fn new(scene: &'s HybridScene) -> Self {
        let world: Vec<Mesh> = scene.instances.par_iter().map(|i| scene.world_mesh(i)).collect();
        let translucent = scene
            .instances
            .iter()
            .map(|i| scene.materials.get(i.material as usize).is_some_and(|m| m.is_translucent()))
            .collect();
        let mut bounds = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for v in world.iter().flat_map(|m| &m.vertices) {
            bounds = (bounds.0.min(v.position), bounds.1.max(v.position));
        }
        Self { scene, world, translucent, bounds }
    }

    /// The meshes to draw: the opaque ones (back faces culled) or the translucent ones
    /// (two-sided).
    pub(crate) fn sources(&self, translucent: bool) -> Vec<Source<'_>> {
        self.world
            .iter()
            .enumerate()
            .filter(|&(i, _)| self.translucent[i] == translucent)
            .map(|(i, mesh)| Source { mesh, instance: i as u32, two_sided: translucent })
            .collect()
    }
}

/// What the visibility buffer holds at one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VisibilitySample {
    /// Instance index.
    pub instance: u32,
    /// Triangle index in the instance's mesh.
    pub triangle: u32,
    /// Perspective-correct barycentrics (weights of the second and third vertex) at the
    /// pixel centre.
    pub bary: Vec2,
}

/// The geometry pass's output.
#[derive(Clone, Debug)]
pub struct GeometryPass {
    /// The stage contract: nearest opaque and nearest translucent surface per pixel.
    pub gbuffer: GBuffer,
    /// The opaque visibility buffer, row-major.
    pub visibility: Vec<Option<VisibilitySample>>,
    /// Translucent layers in front of the opaque surface, `layers` per pixel, nearest first
    /// (`None` where fewer exist).
    pub translucent_layers: Vec<Option<ShadingPoint>>,
    /// Layers per pixel in `translucent_layers`.
    pub layers: usize,
}

impl GeometryPass {
    /// The translucent layers of pixel `i`, nearest first.
    pub fn layers_at(&self, i: usize) -> impl Iterator<Item = &ShadingPoint> {
        self.translucent_layers[i * self.layers..(i + 1) * self.layers].iter().flatten()
    }
}

/// Rasterizes `prepared` as `camera` sees it and resolves the G-buffer, keeping up to
/// `layers` translucent layers per pixel (at least 1).
pub fn geometry_pass(prepared: &PreparedScene, camera: &Camera, layers: usize) -> GeometryPass {
    let layers = layers.max(1);
    let (w, h) = (camera.width, camera.height);
    let vp = camera.view_projection().as_dmat4();
    let view = |i: usize| camera.ray_direction((i as u32 % w) as f32 + 0.5, (i as u32 / w) as f32 + 0.5);
    let scene = prepared.scene;

    let opaque = VisFrame::new(&prepared.sources(false), vp, w, h);
    let (keys, ids) = opaque.nearest(None);
    let visibility: Vec<Option<VisibilitySample>> = ids
        .par_iter()
        .enumerate()
        .map(|(i, &id)| {
            (id != NO_TRIANGLE).then(|| {
                let t = opaque.tris[id as usize];
                let bary = t.barycentrics(i as u32 % w, i as u32 / w);
                VisibilitySample { instance: t.instance, triangle: t.triangle, bary }
            })
        })
        .collect();
    let resolve =
        |i: usize, v: &VisibilitySample| scene.shading_point(v.instance, v.triangle, v.bary, view(i));
    let opaque_points: Vec<Option<ShadingPoint>> =
        visibility.par_iter().enumerate().map(|(i, v)| v.as_ref().map(|v| resolve(i, v))).collect();

    let translucent = VisFrame::new(&prepared.sources(true), vp, w, h);
    let found = translucent.nearest_layers(&keys, layers);
    let translucent_layers: Vec<Option<ShadingPoint>> = found
        .par_iter()
        .enumerate()
        .map(|(k, &(_, id))| {
            (id != NO_TRIANGLE).then(|| {
                let i = k / layers;
                let t = translucent.tris[id as usize];
                let bary = t.barycentrics(i as u32 % w, i as u32 / w);
                resolve(i, &VisibilitySample { instance: t.instance, triangle: t.triangle, bary })
            })
        })
        .collect();
    let nearest = translucent_layers.chunks(layers).map(|l| l[0]).collect();
    GeometryPass {
        gbuffer: GBuffer { camera: *camera, opaque: opaque_points, translucent: nearest },
        visibility,
        translucent_layers,
        layers,
    }
}

/// Distance along the camera's viewing direction of every pixel's opaque surface
/// (`f32::INFINITY` where the sky shows): the depth buffer the screen-space stages march
/// against, derived from the G-buffer alone so that any G-buffer can feed them.
pub fn view_depth(gbuffer: &GBuffer) -> Vec<f32> {
    let cam = &gbuffer.camera;
    gbuffer
        .opaque
        .par_iter()
        .map(|sp| sp.as_ref().map_or(f32::INFINITY, |sp| (sp.position - cam.position).dot(cam.forward)))
        .collect()
}
