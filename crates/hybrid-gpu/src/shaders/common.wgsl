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

// One G-buffer texel: a resolved shading point (the CPU's `ShadingPoint`).
struct GPoint {
    p: vec4f,   // position, uv.x
    n: vec4f,   // shading normal, uv.y
    g: vec4f,   // geometric normal, roughness
    c: vec4f,   // base colour, metallic
    e: vec4f,   // emissive, transmission
    ids: vec4u, // material, drawn triangle + 1 (0: sky), front face (1/0), bits of the ior
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
    ssr_steps: vec4u, // max steps, refinements, shadow maps present (1/0), 0
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

fn gp_valid(g: GPoint) -> bool {
    return g.ids.y != 0u;
}

fn gp_ior(g: GPoint) -> f32 {
    return bitcast<f32>(g.ids.w);
}
