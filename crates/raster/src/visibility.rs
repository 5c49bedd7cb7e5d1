//! The visibility-buffer rasterizer (the hybrid crate's geometry pass and shadow maps draw
//! with it): world-space meshes seen through any projection (the camera's perspective, a
//! light's perspective or orthographic view) rasterized into, per pixel, the nearest triangle's id and depth key, or the nearest few
//! (the translucent layers). It reuses the crate's clipping, fixed-point edge functions,
//! fill rule and band binning; only the per-triangle setup differs: instead of every
//! attribute's plane it keeps the three rows of `M⁻¹` (see the crate's `setup` module),
//! from which the perspective-correct barycentrics at a pixel centre follow exactly:
//! `qᵢ = rowᵢ · (x, y, 1) = λᵢ / w`, `λᵢ = qᵢ / Σ q`.
//!
//! The depth key is `1 − Z/W` (the reversed NDC depth), a plane in screen space for
//! perspective and orthographic projections alike: `Σ (Wᵢ − Zᵢ) rowᵢ`. Larger is nearer.
//!
//! Back faces are culled unless the mesh is two-sided (translucent materials): a two-sided
//! back face is scan-converted with its fan reversed, and its barycentrics still refer to
//! the original vertex order.

use crate::bin::{Bins, BAND_HEIGHT};
use crate::clip::{clip_triangle, Clipped, Polygon, MAX_POLYGON};
use crate::triangle::{snap, DepthPlane, FixedPoint, RasterTriangle};
use crate::viewport::{Viewport, GUARD_BAND_PX};
use glam::{DMat4, DVec3, DVec4, Vec2};
use rayon::prelude::*;
use renderlab_core::Mesh;

/// Marks a pixel that no triangle reached.
pub const NO_TRIANGLE: u32 = u32::MAX;

/// Triangles per parallel setup task.
const SETUP_CHUNK: usize = 2048;

/// Relative size of `det M` below which a triangle is degenerate (as in the G-buffer
/// rasterizer's setup).
const DET_EPSILON: f64 = 1e-14;

/// One mesh to draw.
#[derive(Clone, Copy, Debug)]
pub struct Source<'a> {
    /// World-space mesh.
    pub mesh: &'a Mesh,
    /// Instance index reported back for its pixels.
    pub instance: u32,
    /// Whether back faces are drawn too.
    pub two_sided: bool,
}

/// A set-up triangle: enough to recover the barycentrics at any pixel.
#[derive(Clone, Copy, Debug)]
pub struct VisTriangle {
    /// Rows of `M⁻¹`: `rowᵢ · (x, y, 1) = λᵢ / w`.
    rows: [DVec3; 3],
    /// Instance index.
    pub instance: u32,
    /// Triangle index in the instance's mesh.
    pub triangle: u32,
}

impl VisTriangle {
    /// Perspective-correct barycentrics (weights of the second and third vertex) at the
    /// centre of pixel `(x, y)`.
    #[inline]
    pub fn barycentrics(&self, x: u32, y: u32) -> Vec2 {
        let p = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, 1.0);
        let q = self.rows.map(|r| r.dot(p));
        let s = q[0] + q[1] + q[2];
        Vec2::new((q[1] / s) as f32, (q[2] / s) as f32)
    }
}

/// Everything set up for one view: triangles, their screen triangles and the bins.
pub struct VisFrame {
    /// Set-up triangles, in submission order.
    pub tris: Vec<VisTriangle>,
    raster: Vec<RasterTriangle>,
    bins: Bins,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

/// One chunk's set-up output.
#[derive(Default)]
struct Part {
    tris: Vec<VisTriangle>,
    raster: Vec<RasterTriangle>,
}

impl VisFrame {
    /// Sets up `sources` (in order) seen through `view_projection` (world → clip, depth in
    /// [0, 1]) at `width × height` pixels. Chunks of triangles are set up in parallel and
    /// collected in order, so the result does not depend on the thread count.
    pub fn new(sources: &[Source], view_projection: DMat4, width: u32, height: u32) -> Self {
        let vp = Viewport::from_view_projection(view_projection, width, height);
        let mut tris = Vec::new();
        let mut raster = Vec::new();
        for src in sources {
            let homogeneous: Vec<DVec4> =
                src.mesh.vertices.iter().map(|v| vp.to_pixel * v.position.as_dvec3().extend(1.0)).collect();
            let parts: Vec<Part> = src
                .mesh
                .triangles
                .par_chunks(SETUP_CHUNK)
                .enumerate()
                .map(|(chunk, list)| {
                    let mut part = Part::default();
                    for (k, &tri) in list.iter().enumerate() {
                        let index = (chunk * SETUP_CHUNK + k) as u32;
                        part.add(&vp, &homogeneous, tri, src, index);
                    }
                    part
                })
                .collect();
            for part in parts {
                let offset = tris.len() as u32;
                tris.extend(part.tris);
                raster.extend(part.raster.into_iter().map(|mut t| {
                    t.setup += offset;
                    t
                }));
            }
        }
        let bins = Bins::new(&raster, height);
        Self { tris, raster, bins, width, height }
    }

    /// Rows of band `band`: `y_start..y_end`.
    fn rows(&self, band: usize) -> (u32, u32) {
        let y0 = band as u32 * BAND_HEIGHT;
        (y0, (y0 + BAND_HEIGHT).min(self.height))
    }

    /// Calls `f(set-up triangle, key, pixel index within the band)` for every covered
    /// pixel of band `band`, triangle by triangle in submission order.
    #[inline]
    fn for_each_fragment(&self, band: usize, mut f: impl FnMut(u32, f32, usize)) {
        let (y_start, y_end) = self.rows(band);
        let w = self.width as usize;
        for &i in self.bins.band(band) {
            let t = &self.raster[i as usize];
            for y in t.y0.max(y_start)..=t.y1.min(y_end - 1) {
                let (xs, xe) = t.span(y);
                let row = (y - y_start) as usize * w;
                for x in xs..xe {
                    f(t.setup, t.inv_w(x, y), row + x as usize);
                }
            }
        }
    }

    /// The nearest triangle per pixel: `(key, set-up triangle or NO_TRIANGLE)`, row-major.
    /// A pixel keeps a fragment only if its key is strictly larger than the stored one (ties
    /// keep the earlier triangle); `floor` gives the initial keys (a fragment must be nearer
    /// than it), or 0 (the far plane) when `None`.
    pub fn nearest(&self, floor: Option<&[f32]>) -> (Vec<f32>, Vec<u32>) {
        let n = self.width as usize * self.height as usize;
        let mut key = match floor {
            Some(f) => f.to_vec(),
            None => vec![0.0f32; n],
        };
        let mut id = vec![NO_TRIANGLE; n];
        let band_len = self.width as usize * BAND_HEIGHT as usize;
        if band_len == 0 {
            return (key, id);
        }
        key.par_chunks_mut(band_len).zip(id.par_chunks_mut(band_len)).enumerate().for_each(
            |(band, (key, id))| {
                self.for_each_fragment(band, |tri, z, k| {
                    if z > key[k] {
                        key[k] = z;
                        id[k] = tri;
                    }
                })
            },
        );
        (key, id)
    }

    /// The `layers` nearest triangles per pixel that are nearer than `floor` (the opaque
    /// keys), nearest first: `layers` entries per pixel, `NO_TRIANGLE` where fewer exist.
    /// Equal keys keep submission order.
    pub fn nearest_layers(&self, floor: &[f32], layers: usize) -> Vec<(f32, u32)> {
        let n = self.width as usize * self.height as usize;
        let mut out = vec![(0.0f32, NO_TRIANGLE); n * layers];
        let band_len = self.width as usize * BAND_HEIGHT as usize;
        if band_len == 0 || layers == 0 {
            return out;
        }
        out.par_chunks_mut(band_len * layers).zip(floor.par_chunks(band_len)).enumerate().for_each(
            |(band, (out, floor))| {
                self.for_each_fragment(band, |tri, z, k| {
                    if z <= floor[k] {
                        return;
                    }
                    let list = &mut out[k * layers..(k + 1) * layers];
                    // Insert after every entry at least as near; drop the farthest.
                    let Some(pos) = list.iter().position(|&(key, id)| id == NO_TRIANGLE || z > key) else {
                        return;
                    };
                    list[pos..].rotate_right(1);
                    list[pos] = (z, tri);
                })
            },
        );
        out
    }
}

impl Part {
    /// Culls, sets up, clips, snaps and fans one triangle.
    fn add(&mut self, vp: &Viewport, homogeneous: &[DVec4], tri: [u32; 3], src: &Source, index: u32) {
        if tri.iter().any(|&i| i as usize >= homogeneous.len()) {
            return;
        }
        let h = tri.map(|i| homogeneous[i as usize]);
        if !h.iter().all(|v| v.is_finite()) {
            return;
        }
        let c = h.map(|p| DVec3::new(p.x, p.y, p.w));
        let det = c[0].dot(c[1].cross(c[2]));
        let scale = c[0].length() * c[1].length() * c[2].length();
        // Front faces have det < 0 (counter-clockwise from the front on a y-down screen).
        let back = det > 0.0;
        if !det.is_finite() || det.abs() <= DET_EPSILON * scale || (back && !src.two_sided) {
            return;
        }
        let inv = 1.0 / det;
        let rows = [c[1].cross(c[2]) * inv, c[2].cross(c[0]) * inv, c[0].cross(c[1]) * inv];
        let key = rows[0] * (h[0].w - h[0].z) + rows[1] * (h[1].w - h[1].z) + rows[2] * (h[2].w - h[2].z);
        let depth = DepthPlane { dx: key.x, dy: key.y, c: key.z };
        let mut clipped = Polygon::new();
        let polygon: &[DVec4] = match clip_triangle(h, &vp.planes, &mut clipped) {
            Clipped::Rejected => return,
            Clipped::Inside => &h,
            Clipped::Polygon => clipped.as_slice(),
        };
        let (g, width, height) = (GUARD_BAND_PX, vp.width as f64, vp.height as f64);
        let mut points: [FixedPoint; MAX_POLYGON] = [[0; 2]; MAX_POLYGON];
        for (p, v) in points.iter_mut().zip(polygon) {
            let (x, y) = (v.x / v.w, v.y / v.w);
            if !(v.w > 0.0 && x.is_finite() && y.is_finite()) {
                return;
            }
            *p = snap(x.clamp(-g, width + g), y.clamp(-g, height + g));
        }
        let setup = self.tris.len() as u32;
        let before = self.raster.len();
        for k in 1..polygon.len() - 1 {
            let fan = if back {
                [points[0], points[k + 1], points[k]]
            } else {
                [points[0], points[k], points[k + 1]]
            };
            if let Some(t) = RasterTriangle::new(fan, setup, &depth, vp.width, vp.height) {
                self.raster.push(t);
            }
        }
        if self.raster.len() > before {
            self.tris.push(VisTriangle { rows, instance: src.instance, triangle: index });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec3, Vec4};
    use renderlab_core::Vertex;

    fn triangle(a: Vec3, b: Vec3, c: Vec3) -> Mesh {
        let v = |p| Vertex { position: p, normal: Vec3::Z, uv: Vec2::ZERO, tangent: Vec4::X };
        Mesh { vertices: vec![v(a), v(b), v(c)], triangles: vec![[0, 1, 2]] }
    }

    #[test]
    fn barycentrics_reconstruct_the_point_on_the_ray() {
        // A slanted triangle seen in perspective: the barycentric blend of its vertices lies
        // on the pixel's ray.
        let cam = renderlab_core::Camera::look_at(Vec3::new(0.3, 0.2, 3.0), Vec3::ZERO, 32, 24);
        let mesh = triangle(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.5, -1.0, 0.5), Vec3::new(0.0, 1.2, 0.0));
        let vp = cam.view_projection().as_dmat4();
        let frame = VisFrame::new(&[Source { mesh: &mesh, instance: 7, two_sided: false }], vp, 32, 24);
        let (_, id) = frame.nearest(None);
        let mut seen = 0;
        for (i, &t) in id.iter().enumerate() {
            if t == NO_TRIANGLE {
                continue;
            }
            seen += 1;
            let (x, y) = (i as u32 % 32, i as u32 / 32);
            let tri = frame.tris[t as usize];
            assert_eq!((tri.instance, tri.triangle), (7, 0));
            let b = tri.barycentrics(x, y);
            let [p0, p1, p2] = [0, 1, 2].map(|k| mesh.vertices[k].position);
            let p = p0 * (1.0 - b.x - b.y) + p1 * b.x + p2 * b.y;
            let d = cam.ray_direction(x as f32 + 0.5, y as f32 + 0.5);
            let off_ray = (p - cam.position).cross(d).length();
            assert!(off_ray < 1e-4, "pixel ({x}, {y}) point {p} is {off_ray} off the ray");
        }
        assert!(seen > 50, "only {seen} pixels covered");
    }

    #[test]
    fn back_faces_are_drawn_only_when_two_sided() {
        let cam = renderlab_core::Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 16, 16);
        // Clockwise seen from +Z: a back face.
        let mesh = triangle(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, -1.0, 0.0));
        let vp = cam.view_projection().as_dmat4();
        let count = |two_sided| {
            let f = VisFrame::new(&[Source { mesh: &mesh, instance: 0, two_sided }], vp, 16, 16);
            f.nearest(None).1.iter().filter(|&&t| t != NO_TRIANGLE).count()
        };
        assert_eq!(count(false), 0);
        assert!(count(true) > 20);
    }
}
