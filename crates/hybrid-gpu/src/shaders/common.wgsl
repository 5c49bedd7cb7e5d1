// What every compute pass of the deferred frame shares: the scene's buffers (group 0, laid
// out as `scene.rs` documents), the frame's constants and targets (group 1, as `targets.rs`
// documents), and the small helpers that mirror glam's (normalize_or_zero, signum) so that
// the GPU computes what the CPU computes.

struct Instance {
    c0: vec4f, c1: vec4f, c2: vec4f, c3: vec4f, // transform columns (c3: translation)
    n0: vec4f, n1: vec4f, n2: vec4f,             // normal-matrix columns
    refs: vec4u,                                 // first vertex, first index, material, 0
}

struct Vertex {
    position_u: vec4f,
    normal_v: vec4f,
    tangent: vec4f,
}

struct Material {
    base_rough: vec4f,
    emissive_metal: vec4f,
    transmission_ior: vec4f, // transmission, ior, double-sided (1/0), 0
    textures: vec4u,         // base colour, metallic-roughness, normal (NONE: none)
}

struct Light {
    position_kind: vec4f,       // w: kind bits (0 point, 1 spot, 2 directional, 3 area)
    direction_intensity: vec4f,
    color_range: vec4f,         // w: range, < 0 for none
    half_u_inner: vec4f,
    half_v_outer: vec4f,
}

// A resolved shading point (the CPU's `ShadingPoint`), as the shading code reads it.
struct Surface {
    p: vec4f,   // position, uv.x
    n: vec4f,   // shading normal, uv.y
    g: vec4f,   // geometric normal, roughness
    c: vec4f,   // base colour, metallic
    e: vec4f,   // emissive, transmission
    ids: vec4u, // material, drawn triangle + 1 (0: sky), front face (1/0), bits of the ior
}

// One G-buffer texel, 64 bytes: a `Surface` without what its material holds (emission,
// transmission, ior), its geometric normal octahedron-encoded in two 16-bit snorms.
struct GPoint {
    p: vec4f,   // position, uv.x
    n: vec4f,   // shading normal, uv.y
    c: vec4f,   // base colour, roughness
    ids: vec4u, // material, drawn triangle + 1 (0: sky) | front face << 31, octahedral geometric normal, bits of metallic
}

struct Frame {
    view_proj: mat4x4f,
    eye: vec4f,      // camera position, tan(fov_y / 2)
    forward: vec4f,  // unit forward, aspect
    right: vec4f,    // unit right, near
    up: vec4f,       // unit up (right × forward), far
    sky: vec4f,      // sky radiance, exposure
    size: vec4u,     // width, height, lights, area samples per side
    params: vec4u,   // translucent layers, tone map (0 ACES, 1 Reinhard, 2 clamp), PCF radius, SSAO samples
    shadow: vec4f,   // bias constant, bias slope, SSAO radius, SSAO bias
    ssr: vec4f,      // max roughness, stride (px), thickness, max distance
    ssr_steps: vec4u, // max steps, refinements, shadow maps present (1/0), translucent layer to resolve for read-back
}

const NONE: u32 = 0xffffffffu;
const PI: f32 = 3.14159265358979323846;
const F32_MAX: f32 = 3.40282347e38;

@group(0) @binding(0) var<storage, read> world_positions: array<vec4f>;
@group(0) @binding(1) var<storage, read> draw_indices: array<u32>;
@group(0) @binding(2) var<storage, read> triangle_refs: array<vec2u>;
@group(0) @binding(3) var<storage, read> instances: array<Instance>;
@group(0) @binding(4) var<storage, read> vertices: array<Vertex>;
@group(0) @binding(5) var<storage, read> indices: array<u32>;
@group(0) @binding(6) var<storage, read> materials: array<Material>;
@group(0) @binding(7) var<storage, read> texture_info: array<vec4u>;
@group(0) @binding(8) var<storage, read> texels: array<vec4f>;
@group(0) @binding(9) var<storage, read> lights: array<Light>;

@group(1) @binding(0) var<uniform> frame: Frame;

// glam's `normalize_or_zero`: v · (1/|v|) where that reciprocal is finite and positive.
fn normalize_or_zero(v: vec3f) -> vec3f {
    let r = 1.0 / length(v);
    if r > 0.0 && r <= F32_MAX {
        return v * r;
    }
    return vec3f(0.0);
}

// glam's `normalize`: v · (1/|v|).
fn normalize_exact(v: vec3f) -> vec3f {
    return v * (1.0 / length(v));
}

fn is_finite(x: f32) -> bool {
    return abs(x) <= F32_MAX;
}

fn pixel_index(x: u32, y: u32) -> u32 {
    return y * frame.size.x + x;
}

// `Camera::ray_direction` at the centre of pixel (x, y).
fn view_dir(x: u32, y: u32) -> vec3f {
    let px = f32(x) + 0.5;
    let py = f32(y) + 0.5;
    let ndc_x = 2.0 * px / f32(frame.size.x) - 1.0;
    let ndc_y = 1.0 - 2.0 * py / f32(frame.size.y);
    let t = frame.eye.w;
    let d = frame.forward.xyz + frame.right.xyz * (ndc_x * t * frame.forward.w) + frame.up.xyz * (ndc_y * t);
    return normalize_exact(d);
}

fn gp_valid(g: Surface) -> bool {
    return g.ids.y != 0u;
}

fn gp_ior(g: Surface) -> f32 {
    return bitcast<f32>(g.ids.w);
}

fn packed_valid(g: GPoint) -> bool {
    return (g.ids.y & 0x7fffffffu) != 0u;
}

fn sign_not_zero(v: vec2f) -> vec2f {
    return select(vec2f(-1.0), vec2f(1.0), v >= vec2f(0.0));
}

// Octahedral encoding of a unit vector in two 16-bit snorms.
fn oct_encode(n: vec3f) -> u32 {
    var e = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if n.z < 0.0 {
        e = (vec2f(1.0) - abs(e.yx)) * sign_not_zero(e);
    }
    return pack2x16snorm(e);
}

fn oct_decode(bits: u32) -> vec3f {
    let e = unpack2x16snorm(bits);
    var n = vec3f(e, 1.0 - abs(e.x) - abs(e.y));
    if n.z < 0.0 {
        n = vec3f((vec2f(1.0) - abs(n.yx)) * sign_not_zero(n.xy), n.z);
    }
    return normalize(n);
}

fn pack_surface(s: Surface) -> GPoint {
    var g: GPoint;
    g.p = s.p;
    g.n = s.n;
    g.c = vec4f(s.c.xyz, s.g.w);
    g.ids = vec4u(s.ids.x, s.ids.y | (s.ids.z << 31u), oct_encode(s.g.xyz), bitcast<u32>(s.c.w));
    return g;
}

// The surface of a G-buffer texel; emission, transmission and ior from its material
// (no emission from the back of a single-sided one).
fn unpack_surface(g: GPoint) -> Surface {
    var s: Surface;
    if !packed_valid(g) {
        return s;
    }
    let m = materials[g.ids.x];
    let front = g.ids.y >> 31u;
    s.p = g.p;
    s.n = g.n;
    s.g = vec4f(oct_decode(g.ids.z), g.c.w);
    s.c = vec4f(g.c.xyz, bitcast<f32>(g.ids.w));
    var emissive = m.emissive_metal.xyz;
    if front == 0u && m.transmission_ior.z == 0.0 {
        emissive = vec3f(0.0);
    }
    s.e = vec4f(emissive, m.transmission_ior.x);
    s.ids = vec4u(g.ids.x, g.ids.y & 0x7fffffffu, front, bitcast<u32>(m.transmission_ior.y));
    return s;
}
