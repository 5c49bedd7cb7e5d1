//! Turning the vertex streams a file gives into a [`Mesh`] the renderers accept: indices
//! checked, non-finite positions refused, degenerate triangles dropped and counted,
//! missing or broken normals computed (flat, as glTF asks, or smooth, as OBJ files expect),
//! missing UVs set to zero, missing tangents computed from the UVs.

use super::common::Problem;
use glam::{Vec2, Vec3, Vec4};
use renderlab_core::{Mesh, Vertex};

/// How to make normals that the file does not give.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalRule {
    /// One normal per face (vertices are split): glTF's rule for primitives without normals.
    Flat,
    /// Area-weighted average of the faces around each shared vertex.
    Smooth,
}

/// Vertex streams as read from a file: every optional stream, when present, has one entry
/// per position.
#[derive(Debug, Default)]
pub struct RawMesh {
    /// Name for messages.
    pub name: String,
    /// Positions.
    pub positions: Vec<Vec3>,
    /// Normals, if the file has them.
    pub normals: Option<Vec<Vec3>>,
    /// First texture coordinate set, if any.
    pub uvs: Option<Vec<Vec2>>,
    /// Tangents with handedness, if any.
    pub tangents: Option<Vec<Vec4>>,
    /// Linear RGBA vertex colours, if any.
    pub colors: Option<Vec<Vec4>>,
    /// Triangles (not yet checked).
    pub triangles: Vec<[u32; 3]>,
}

/// The mesh and what had to be repaired on the way.
pub struct Cleaned {
    /// The usable mesh (possibly with no triangles left).
    pub mesh: Mesh,
    /// The vertex colours of `mesh`'s vertices (one per vertex), when the file gave them.
    pub colors: Option<Vec<Vec4>>,
    /// Degenerate triangles dropped.
    pub dropped: usize,
    /// Repairs worth telling the user (one line each).
    pub notes: Vec<String>,
}

/// Checks and completes `raw`. Errors: an index past the vertex count, a stream whose
/// length differs from the positions', a non-finite position.
pub fn clean(raw: RawMesh, rule: NormalRule) -> Result<Cleaned, Problem> {
    let n = raw.positions.len();
    let name = &raw.name;
    let mut notes = Vec::new();
    for (what, len) in [
        ("normals", raw.normals.as_ref().map(Vec::len)),
        ("texture coordinates", raw.uvs.as_ref().map(Vec::len)),
        ("tangents", raw.tangents.as_ref().map(Vec::len)),
        ("colours", raw.colors.as_ref().map(Vec::len)),
    ] {
        if let Some(len) = len.filter(|&l| l != n) {
            return Err(Problem::Invalid(format!("mesh {name:?}: {len} {what} for {n} positions")));
        }
    }
    if let Some(v) = raw.positions.iter().position(|p| !p.is_finite()) {
        return Err(Problem::Invalid(format!("mesh {name:?}: vertex {v} has a non-finite position")));
    }
    if let Some((t, &i)) = raw
        .triangles
        .iter()
        .enumerate()
        .find_map(|(t, tri)| tri.iter().find(|&&i| i as usize >= n).map(|i| (t, i)))
    {
        return Err(Problem::Invalid(format!(
            "mesh {name:?}: triangle {t} uses vertex {i}, but there are only {n} vertices"
        )));
    }
    let p = |i: u32| raw.positions[i as usize];
    let before = raw.triangles.len();
    let triangles: Vec<[u32; 3]> = raw
        .triangles
        .iter()
        .copied()
        .filter(|&[a, b, c]| {
            let area2 = (p(b) - p(a)).cross(p(c) - p(a)).length_squared();
            a != b && b != c && a != c && area2 > 0.0 && area2.is_finite()
        })
        .collect();
    let dropped = before - triangles.len();

    let mut uvs = raw.uvs.unwrap_or_else(|| vec![Vec2::ZERO; n]);
    if uvs.iter().any(|u| !u.is_finite()) {
        notes.push(format!("mesh {name:?}: non-finite texture coordinates set to 0"));
        uvs.iter_mut().filter(|u| !u.is_finite()).for_each(|u| *u = Vec2::ZERO);
    }
    let normals = raw.normals.filter(|ns| {
        let ok = ns.iter().all(|v| v.is_finite() && v.length_squared() > 1e-20);
        if !ok {
            notes.push(format!("mesh {name:?}: zero or non-finite normals in the file; normals recomputed"));
        }
        ok
    });
    let colors = raw.colors.map(|cs| {
        if cs.iter().any(|c| !c.is_finite()) {
            notes.push(format!("mesh {name:?}: non-finite vertex colours set to white"));
        }
        cs.into_iter().map(|c| if c.is_finite() { c.max(Vec4::ZERO) } else { Vec4::ONE }).collect::<Vec<_>>()
    });
    let tangents = raw.tangents.filter(|ts| {
        let ok = ts.iter().all(|t| t.is_finite() && t.truncate().length_squared() > 1e-20);
        if !ok {
            notes.push(format!("mesh {name:?}: unusable tangents in the file; tangents recomputed"));
        }
        ok
    });

    // `origin[i]`: the file's vertex that vertex `i` of the mesh built below comes from.
    let (mut mesh, origin): (Mesh, Vec<u32>) = match (normals, rule) {
        (Some(ns), _) => {
            let vertices = (0..n)
                .map(|i| Vertex {
                    position: raw.positions[i],
                    normal: ns[i].normalize(),
                    uv: uvs[i],
                    tangent: Vec4::ZERO,
                })
                .collect();
            let mut mesh = Mesh { vertices, triangles };
            match tangents {
                Some(ts) => {
                    for (v, t) in mesh.vertices.iter_mut().zip(ts) {
                        let w = if t.w < 0.0 { -1.0 } else { 1.0 };
                        v.tangent = t.truncate().normalize().extend(w);
                    }
                }
                None => mesh.compute_tangents(),
            }
            let (mesh, kept) = compact(mesh);
            let colors = colors.map(|cs| kept.iter().map(|&i| cs[i as usize]).collect());
            return Ok(Cleaned { mesh, colors, dropped, notes });
        }
        (None, NormalRule::Flat) => {
            let origin = triangles.iter().flatten().copied().collect();
            (flat(&raw.positions, &uvs, &triangles), origin)
        }
        (None, NormalRule::Smooth) => (smooth(&raw.positions, &uvs, triangles), (0..n as u32).collect()),
    };
    mesh.compute_tangents();
    let (mesh, kept) = compact(mesh);
    let colors = colors.map(|cs| kept.iter().map(|&i| cs[origin[i as usize] as usize]).collect());
    Ok(Cleaned { mesh, colors, dropped, notes })
}

/// One vertex per triangle corner, each with its face's normal.
fn flat(positions: &[Vec3], uvs: &[Vec2], triangles: &[[u32; 3]]) -> Mesh {
    let mut mesh = Mesh { vertices: Vec::with_capacity(triangles.len() * 3), triangles: Vec::new() };
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let normal = (b - a).cross(c - a).normalize_or_zero();
        let base = mesh.vertices.len() as u32;
        for &i in t {
            mesh.vertices.push(Vertex {
                position: positions[i as usize],
                normal,
                uv: uvs[i as usize],
                tangent: Vec4::ZERO,
            });
        }
        mesh.triangles.push([base, base + 1, base + 2]);
    }
    mesh
}

/// Shared vertices with area-weighted face normals; a vertex no triangle uses gets +Y.
fn smooth(positions: &[Vec3], uvs: &[Vec2], triangles: Vec<[u32; 3]>) -> Mesh {
    let mut acc = vec![Vec3::ZERO; positions.len()];
    for t in &triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let face = (b - a).cross(c - a);
        for &i in t {
            acc[i as usize] += face;
        }
    }
    let vertices = positions
        .iter()
        .zip(uvs)
        .zip(acc)
        .map(|((&position, &uv), n)| {
            let normal = n.try_normalize().unwrap_or(Vec3::Y);
            Vertex { position, normal, uv, tangent: Vec4::ZERO }
        })
        .collect();
    Mesh { vertices, triangles }
}

/// Drops vertices no triangle uses (files often share one vertex pool among primitives);
/// also returns, for each kept vertex, its index in `mesh`.
fn compact(mesh: Mesh) -> (Mesh, Vec<u32>) {
    let mut map = vec![u32::MAX; mesh.vertices.len()];
    let mut vertices = Vec::new();
    let mut kept = Vec::new();
    let mut triangles = Vec::with_capacity(mesh.triangles.len());
    for t in &mesh.triangles {
        triangles.push(t.map(|i| {
            let slot = &mut map[i as usize];
            if *slot == u32::MAX {
                *slot = vertices.len() as u32;
                vertices.push(mesh.vertices[i as usize]);
                kept.push(i);
            }
            *slot
        }));
    }
    (Mesh { vertices, triangles }, kept)
}

/// Gives each triangle of `mesh` its own three vertices and its own 2×2 texel cell of the
/// returned texture, so that the material's bilinear texture lookup reproduces `colors`
/// (one per vertex) interpolated across each triangle exactly as a vertex-colour
/// rasteriser would. The cell's corner texels `a`, `b`, `c` hold the triangle's corner
/// colours and its fourth texel `b + c − a`, so that the bilinear patch over the cell is the
/// affine (barycentric) interpolant; the UVs sit on the three texel centres, so a lookup
/// inside the triangle never reads a neighbouring cell. The mesh's UVs are replaced (any
/// other texture of its material would be read at the wrong place: the caller checks).
pub fn bake_vertex_colors(mesh: &mut Mesh, colors: &[Vec4]) -> Result<renderlab_core::Image<Vec4>, String> {
    let n = mesh.triangles.len().max(1);
    let cols = (n as f64).sqrt().ceil() as usize;
    let rows = n.div_ceil(cols);
    let (w, h) = (2 * cols, 2 * rows);
    let mut texels = vec![Vec4::ONE; w * h];
    let mut vertices = Vec::with_capacity(mesh.triangles.len() * 3);
    let mut triangles = Vec::with_capacity(mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let (x, y) = (2 * (t % cols), 2 * (t / cols));
        let [a, b, c] = tri.map(|i| colors[i as usize]);
        texels[y * w + x] = a;
        texels[y * w + x + 1] = b;
        texels[(y + 1) * w + x] = c;
        texels[(y + 1) * w + x + 1] = b + c - a;
        let base = vertices.len() as u32;
        for (k, &i) in tri.iter().enumerate() {
            let (dx, dy) = [(0, 0), (1, 0), (0, 1)][k];
            let mut v = mesh.vertices[i as usize];
            v.uv = Vec2::new((x + dx) as f32 + 0.5, (y + dy) as f32 + 0.5) / Vec2::new(w as f32, h as f32);
            vertices.push(v);
        }
        triangles.push([base, base + 1, base + 2]);
    }
    mesh.vertices = vertices;
    mesh.triangles = triangles;
    mesh.compute_tangents();
    renderlab_core::Image::from_vec(w as u32, h as u32, texels).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> RawMesh {
        RawMesh {
            name: "q".into(),
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..RawMesh::default()
        }
    }

    #[test]
    fn missing_normals_are_computed_and_face_the_winding() {
        for rule in [NormalRule::Flat, NormalRule::Smooth] {
            let c = clean(quad(), rule).unwrap();
            assert_eq!(c.mesh.triangles.len(), 2);
            for v in &c.mesh.vertices {
                assert!((v.normal - Vec3::Z).length() < 1e-6, "{rule:?}: {}", v.normal);
                assert!((v.tangent.truncate().dot(v.normal)).abs() < 1e-5);
            }
        }
        assert_eq!(clean(quad(), NormalRule::Flat).unwrap().mesh.vertices.len(), 6);
        assert_eq!(clean(quad(), NormalRule::Smooth).unwrap().mesh.vertices.len(), 4);
    }

    #[test]
    fn degenerate_triangles_are_dropped_and_counted() {
        let mut q = quad();
        q.triangles.push([1, 1, 2]);
        q.positions.push(Vec3::X * 2.0);
        q.triangles.push([0, 1, 4]); // collinear
        let c = clean(q, NormalRule::Smooth).unwrap();
        assert_eq!((c.mesh.triangles.len(), c.dropped), (2, 2));
        assert_eq!(c.mesh.vertices.len(), 4, "the unused vertex is gone");
    }

    #[test]
    fn bad_indices_and_nan_positions_are_errors() {
        let mut q = quad();
        q.triangles[1][2] = 9;
        assert!(clean(q, NormalRule::Flat).is_err());
        let mut q = quad();
        q.positions[2].y = f32::NAN;
        assert!(clean(q, NormalRule::Flat).is_err());
        let mut q = quad();
        q.uvs = Some(vec![Vec2::ZERO; 3]);
        assert!(clean(q, NormalRule::Flat).is_err());
    }
}
