//! The ray-tracing benchmarks' workload, shared by the CPU criterion bench, the Embree
//! comparison and the GPU ray-rate example, so that every one of them traces the same triangles
//! and rays.
//!
//! Meshes ([`MESHES`]), each with its own view ([`View`]): a procedural terrain of 708 × 708
//! quads (1,002,528 triangles), displaced by a sum of ridged sine octaves into hills and
//! canyons; a closed lumpy blob of the Stanford bunny's size (69,312 triangles, [`blob()`]); and
//! 48 transformed copies of the blob flattened into one mesh (3,326,976 triangles). Primary
//! rays: a 512 × 512 pinhole camera, in tiles of 8 × 8 pixels (tiles row by row, pixels in
//! Morton order inside a tile), so that every 8 consecutive rays are a 4 × 2 block of pixels,
//! every 16 a 4 × 4 block and every 32 an 8 × 4 block. Incoherent rays: one cosine-weighted
//! diffuse bounce from every primary hit. Shadow rays: segments from every primary hit to a
//! point light (any-hit).

mod blob;

pub use blob::{blob, blob_with, flatten, placements, BLOB_GRID, COPIES, SMALL_BLOB_GRID};

use crate::{Blas, Ray};
use glam::Vec3;

/// Where a mesh is seen from and lit from.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// The camera's position.
    pub eye: Vec3,
    /// The point at the image's centre.
    pub target: Vec3,
    /// The vertical (and horizontal: the image is square) field of view in degrees.
    pub fov_deg: f32,
    /// The point light the shadow rays go to.
    pub light: Vec3,
}

/// The terrain's view: across the hills from one edge.
pub const TERRAIN_VIEW: View = View {
    eye: Vec3::new(50.0, 32.0, -12.0),
    target: Vec3::new(50.0, 0.0, 45.0),
    fov_deg: 55.0,
    light: Vec3::new(20.0, 60.0, 80.0),
};

/// The blob's view: the whole blob, ears included, filling most of the image.
pub const BLOB_VIEW: View = View {
    eye: Vec3::new(1.1, 1.3, 3.3),
    target: Vec3::new(0.0, 0.45, 0.0),
    fov_deg: 44.0,
    light: Vec3::new(4.0, 6.0, 3.0),
};

/// The copies' view: over the field of blobs from its front edge.
pub const BLOBS_VIEW: View = View {
    eye: Vec3::new(0.0, 15.0, -5.0),
    target: Vec3::new(0.0, 0.0, 7.0),
    fov_deg: 58.0,
    light: Vec3::new(-10.0, 25.0, 5.0),
};

/// The benchmark meshes by name: `terrain`, `blob`, `blobs`.
pub const MESHES: [&str; 3] = ["terrain", "blob", "blobs"];

/// Meshes that [`mesh`] also makes but the benchmarks leave out unless asked: `small-blob`,
/// the blob with [`SMALL_BLOB_GRID`] (1,728 triangles), small enough to stay in a core's caches.
pub const DIAGNOSTIC_MESHES: [&str; 1] = ["small-blob"];

/// The mesh named `name` (one of [`MESHES`] or [`DIAGNOSTIC_MESHES`]) and its view, or `None`.
pub fn mesh(name: &str) -> Option<(Vec<Vec3>, Vec<[u32; 3]>, View)> {
    Some(match name {
        "terrain" => {
            let (p, t) = terrain();
            (p, t, TERRAIN_VIEW)
        }
        "blob" => {
            let (p, t) = blob();
            (p, t, BLOB_VIEW)
        }
        "small-blob" => {
            let (p, t) = blob_with(SMALL_BLOB_GRID);
            (p, t, BLOB_VIEW)
        }
        "blobs" => {
            let (p, t) = flatten(&blob(), &placements());
            (p, t, BLOBS_VIEW)
        }
        _ => return None,
    })
}

/// Quads along each side of the terrain.
pub const GRID: usize = 708;
/// The terrain's side length.
pub const SIZE: f32 = 100.0;
/// Image width in pixels.
pub const WIDTH: usize = 512;
/// Image height in pixels.
pub const HEIGHT: usize = 512;
/// Side of a square tile of pixels.
pub const TILE: usize = 8;

fn height(x: f32, z: f32) -> f32 {
    let mut h = 0.0;
    let (mut amp, mut freq) = (9.0f32, 0.045f32);
    for o in 0..7 {
        let a = o as f32 * 1.7 + 0.3;
        let (s, c) = a.sin_cos();
        let u = (x * c + z * s) * freq;
        let v = (z * c - x * s) * freq;
        // Ridged: sharp crests and round valleys.
        h += amp * (1.0 - (u.sin() * (v * 0.8 + o as f32).cos()).abs() * 2.0);
        amp *= 0.5;
        freq *= 2.03;
    }
    h
}

/// The terrain: positions and indexed triangles.
pub fn terrain() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let n = GRID;
    let mut pos = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (i as f32 / n as f32 * SIZE, j as f32 / n as f32 * SIZE);
            pos.push(Vec3::new(x, height(x, z), z));
        }
    }
    let mut tris = Vec::with_capacity(2 * n * n);
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    (pos, tris)
}

/// The pixel `(x, y)` of the `k`-th ray in tiled Morton order.
pub fn tiled_morton(k: usize) -> (usize, usize) {
    let (tile, m) = (k / (TILE * TILE), k % (TILE * TILE));
    let tiles_x = WIDTH / TILE;
    let (tx, ty) = (tile % tiles_x, tile / tiles_x);
    // Even bits of the Morton index are x, odd bits y.
    let (mut x, mut y) = (0, 0);
    for b in 0..3 {
        x |= ((m >> (2 * b)) & 1) << b;
        y |= ((m >> (2 * b + 1)) & 1) << b;
    }
    (tx * TILE + x, ty * TILE + y)
}

/// The terrain's primary rays, in tiled Morton order.
pub fn camera_rays() -> Vec<Ray> {
    view_rays(&TERRAIN_VIEW)
}

/// The primary rays of `view`, in tiled Morton order.
pub fn view_rays(view: &View) -> Vec<Ray> {
    let eye = view.eye;
    let forward = (view.target - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half = (view.fov_deg.to_radians() / 2.0).tan();
    (0..WIDTH * HEIGHT)
        .map(|k| {
            let (x, y) = tiled_morton(k);
            let sx = ((x as f32 + 0.5) / WIDTH as f32 * 2.0 - 1.0) * half;
            let sy = (1.0 - (y as f32 + 0.5) / HEIGHT as f32 * 2.0) * half;
            Ray::new(eye, (forward + right * sx + up * sy).normalize())
        })
        .collect()
}

/// A small deterministic generator for the bounce directions.
struct Pcg(u64);

impl Pcg {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }
}

/// The terrain's secondary rays ([`secondary_rays_to`] its light).
pub fn secondary_rays(blas: &Blas, pos: &[Vec3], tris: &[[u32; 3]], primary: &[Ray]) -> (Vec<Ray>, Vec<Ray>) {
    secondary_rays_to(blas, pos, tris, primary, TERRAIN_VIEW.light)
}

/// From every primary hit (in the primary rays' order): a cosine-weighted bounce about the
/// facing geometric normal, and a shadow segment towards the point light at `light`. The new
/// origins are offset 1e-3 along that normal.
pub fn secondary_rays_to(
    blas: &Blas,
    pos: &[Vec3],
    tris: &[[u32; 3]],
    primary: &[Ray],
    light: Vec3,
) -> (Vec<Ray>, Vec<Ray>) {
    let mut rng = Pcg(7);
    let (mut bounce, mut shadow) = (Vec::new(), Vec::new());
    for ray in primary {
        let Some(hit) = blas.closest_hit(ray) else { continue };
        let [a, b, c] = tris[hit.primitive as usize].map(|i| pos[i as usize]);
        let mut n = (b - a).cross(c - a).normalize();
        if n.dot(ray.dir) > 0.0 {
            n = -n;
        }
        let p = ray.at(hit.t) + n * 1e-3;
        let (t, s) = n.any_orthonormal_pair();
        let (r1, r2) = (rng.next(), rng.next());
        let (sin_phi, cos_phi) = (2.0 * std::f32::consts::PI * r1).sin_cos();
        let r = r2.sqrt();
        let d = t * (r * cos_phi) + s * (r * sin_phi) + n * (1.0 - r2).max(0.0).sqrt();
        bounce.push(Ray::new(p, d.normalize()));
        let to_light = light - p;
        shadow.push(Ray::segment(p, to_light.normalize(), 0.0, to_light.length()));
    }
    (bounce, shadow)
}
