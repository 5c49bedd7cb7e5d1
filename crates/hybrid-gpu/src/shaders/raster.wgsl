// The raster passes: world-space triangles pulled from storage buffers (three entries of
// `draw_indices` per drawn triangle, so `vertex_index / 3` is the drawn triangle's number),
// projected by a view's matrix with the depth reversed to the CPU rasterizer's key
// `1 − Z/W` (nearer is larger, compared with `Greater`, cleared to 0, the far plane).
//
// fs_id writes the drawn triangle + 1 (the visibility buffer); fs_distance writes the
// distance along the view's axis of the fragment's world point (a shadow map's texel);
// fs_peel keeps only fragments in front of the opaque surface and behind the previous
// translucent layer (by key, then by triangle number for equal keys), the next layer of a
// depth peel.

struct RasterView {
    view_proj: mat4x4f,
    eye: vec4f,
    forward: vec4f,
}

struct Peel {
    layer: vec4u, // layer index, 0, 0, 0
}

@group(0) @binding(0) var<uniform> rview: RasterView;
@group(0) @binding(1) var<storage, read> r_positions: array<vec4f>;
@group(0) @binding(2) var<storage, read> r_indices: array<u32>;

@group(1) @binding(0) var<uniform> peel: Peel;
@group(1) @binding(1) var opaque_key: texture_2d<f32>;
@group(1) @binding(2) var prev_key: texture_2d<f32>;
@group(1) @binding(3) var prev_id: texture_2d<u32>;

struct VsOut {
    @builtin(position) clip: vec4f,
    @location(0) @interpolate(flat) tri: u32,
    @location(1) world: vec3f,
}

@vertex
fn vs(@builtin(vertex_index) vi: u32) -> VsOut {
    let p = r_positions[r_indices[vi]].xyz;
    var c = rview.view_proj * vec4f(p, 1.0);
    c.z = c.w - c.z;
    var out: VsOut;
    out.clip = c;
    out.tri = vi / 3u;
    out.world = p;
    return out;
}

struct IdOut {
    @location(0) id: u32,
    @location(1) key: f32,
}

@fragment
fn fs_id(in: VsOut) -> IdOut {
    return IdOut(in.tri + 1u, in.clip.z);
}

@fragment
fn fs_distance(in: VsOut) -> @location(0) f32 {
    return dot(in.world - rview.eye.xyz, rview.forward.xyz);
}

@fragment
fn fs_peel(in: VsOut) -> IdOut {
    let px = vec2i(in.clip.xy);
    let key = in.clip.z;
    if key <= textureLoad(opaque_key, px, 0).x {
        discard;
    }
    if peel.layer.x > 0u {
        let pk = textureLoad(prev_key, px, 0).x;
        let pid = textureLoad(prev_id, px, 0).x;
        if pid == 0u || key > pk || (key == pk && in.tri + 1u <= pid) {
            discard;
        }
    }
    return IdOut(in.tri + 1u, key);
}
