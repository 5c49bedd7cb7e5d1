// The relief frame on the GPU, the twin of `renderlab_relief::render::shade` and of the
// rasterizer's surface reconstruction (`renderlab_raster`): bindings, the vertex stage, the
// per-pixel surface (UV, its exact screen Jacobian, the tangent frame), texture sampling,
// the thesis's lighting, and the fragment entry points that call the technique's `trace`.
//
// Conventions as on the CPU: tangent space is (T, B, N) = (direction of increasing u,
// direction of increasing v, normal); colours are linear; pixel centres are at +0.5.

// What is constant over a frame (`FrameUniform` on the Rust side).
struct Frame {
    view_proj: mat4x4<f32>,
    // Eye position (xyz).
    eye: vec4<f32>,
    // Unit vector toward the light (xyz).
    to_light: vec4<f32>,
    // The technique's parameters in descriptor order (see `param`).
    params: vec4<u32>,
    // Ambient factor, Blinn–Phong exponent and strength.
    ambient: f32,
    specular_exponent: f32,
    specular_strength: f32,
    // 0: unlit (albedo alone); 1: lit; 2: lit with soft self-shadows.
    lit: u32,
    // Samples along the light ray of the soft shadows (`ShadowMode::Soft`).
    shadow_samples: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// One material's constants (`MaterialUniform`).
struct Material {
    // Depth scale in UV per unit depth.
    height_scale: f32,
    // Mip levels of the albedo and normal textures.
    albedo_levels: f32,
    normal_levels: f32,
    _pad: f32,
}

@group(0) @binding(0) var<uniform> frame: Frame;
// Bilinear within a level, linear between levels, repeat: the CPU's `trilinear_at` and
// `HeightField::depth`.
@group(0) @binding(1) var map_sampler: sampler;

@group(1) @binding(0) var<uniform> material: Material;
@group(1) @binding(1) var albedo_map: texture_2d<f32>;
@group(1) @binding(2) var normal_map: texture_2d<f32>;
@group(1) @binding(3) var depth_map: texture_2d<f32>;
@group(1) @binding(4) var complexity_map: texture_2d<f32>;
// The relaxed cone ratios, read at the nearest texel (`ConeMap::ratio`).
@group(1) @binding(5) var cone_map: texture_2d<f32>;
// The packed map's padded grid: depth (high 16 bits) and cone ratio (low 16 bits) per texel.
@group(1) @binding(6) var packed_map: texture_2d<u32>;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
}

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    // Perspective-correct, like every attribute here (see `surface` for its derivatives).
    @location(0) uv: vec2<f32>,
    @location(1) world: vec3<f32>,
    @location(2) normal: vec3<f32>,
    @location(3) tangent: vec4<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> Varyings {
    var out: Varyings;
    out.clip = frame.view_proj * vec4<f32>(v.position, 1.0);
    out.uv = v.uv;
    out.world = v.position;
    out.normal = v.normal;
    out.tangent = v.tangent;
    return out;
}

// What the rasterizer knows about one pixel (`SurfacePoint`).
struct Surface {
    uv: vec2<f32>,
    duv_dx: vec2<f32>,
    duv_dy: vec2<f32>,
    view_ts: vec3<f32>,
    light_ts: vec3<f32>,
}

// The pixel's surface. The fragment position's w is q = 1/w, and h = uv·q is affine in screen
// space, so ∂uv/∂x = (∂h/∂x − uv·∂q/∂x)/q exactly, as the CPU rasterizer computes it: the
// fine derivatives of an affine quantity are its slopes, where finite differences of uv
// itself would be off by its curvature. (Interpolating uv/w and 1/w without perspective
// would be wrong where the near plane clips a triangle: the clipper interpolates such
// attributes linearly in clip space.) Must run in uniform control flow.
fn surface(in: Varyings) -> Surface {
    var s: Surface;
    let q = in.clip.w;
    s.uv = in.uv;
    let h = s.uv * q;
    s.duv_dx = (dpdxFine(h) - s.uv * dpdxFine(q)) / q;
    s.duv_dy = (dpdyFine(h) - s.uv * dpdyFine(q)) / q;
    // The tangent frame as `tangent_frame` builds it: N, T by Gram–Schmidt, B = N × T · sign.
    let n = normalize(in.normal);
    var t = in.tangent.xyz - n * dot(n, in.tangent.xyz);
    t = select(vec3<f32>(1.0, 0.0, 0.0), normalize(t), dot(t, t) > 0.0);
    let handedness = select(1.0, -1.0, in.tangent.w < 0.0);
    let b = cross(n, t) * handedness;
    let view = normalize(frame.eye.xyz - in.world);
    s.view_ts = vec3<f32>(dot(t, view), dot(b, view), dot(n, view));
    let l = frame.to_light.xyz;
    s.light_ts = vec3<f32>(dot(t, l), dot(b, l), dot(n, l));
    return s;
}

// The level of detail of a footprint as the CPU's `lod` (and the Vulkan specification)
// defines it, for a texture of `size` texels and `levels` levels.
fn lod(size: vec2<f32>, levels: f32, duv_dx: vec2<f32>, duv_dy: vec2<f32>) -> f32 {
    let a = dot(duv_dx * size, duv_dx * size);
    let b = dot(duv_dy * size, duv_dy * size);
    if !(abs(a) <= 3.0e38 && abs(b) <= 3.0e38) {
        return levels - 1.0;
    }
    let l = 0.5 * log2(max(max(a, b), 1e-30));
    return clamp(l, 0.0, levels - 1.0);
}

// `x^e`; by repeated squaring when `e` is a whole number up to 256, as the CPU's `powi`.
fn pow_exponent(x: f32, e: f32) -> f32 {
    if e >= 0.0 && e <= 256.0 && e == trunc(e) {
        var k = u32(e);
        var base = x;
        var acc = 1.0;
        while k > 0u {
            if (k & 1u) == 1u {
                acc *= base;
            }
            base *= base;
            k >>= 1u;
        }
        return acc;
    }
    return pow(x, e);
}

// The thesis's ambient + Lambert + Blinn–Phong in tangent space (`light`); `shadow` (1 lit …
// 0 shadowed) scales what the light adds.
fn light(albedo: vec3<f32>, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, shadow: f32) -> vec3<f32> {
    let ambient = albedo * frame.ambient;
    let diff = max(dot(n, l), 0.0);
    let hv = l + v;
    let h = select(vec3<f32>(0.0), normalize(hv), dot(hv, hv) > 0.0);
    let spec = pow_exponent(max(dot(n, h), 0.0), frame.specular_exponent) * frame.specular_strength;
    // Light arriving from below the geometric surface reaches no point of it.
    let facing = select(0.0, shadow, l.z > 0.0);
    return ambient + (albedo * diff + vec3<f32>(spec)) * facing;
}

// One shaded pixel and what the debug targets show of it.
struct Shaded {
    color: vec3<f32>,
    uv: vec2<f32>,
    layers: u32,
}

// Traces and lights one pixel (`shade_point`): the ray enters at its UV moved into the first
// tile (the field repeats, so the hit is the same and f32 keeps its precision), the hit moves
// back, and the maps are sampled there with the level of the undisplaced footprint; a
// shadowed technique then marches toward the light from the hit (`soft_shadow`).
fn shade(in: Varyings) -> Shaded {
    let s = surface(in);
    let base = floor(s.uv);
    var hit = trace(s.uv - base, s.view_ts);
    hit.uv += base;
    let albedo_size = vec2<f32>(textureDimensions(albedo_map));
    let albedo_lod = lod(albedo_size, material.albedo_levels, s.duv_dx, s.duv_dy);
    let albedo = textureSampleLevel(albedo_map, map_sampler, hit.uv, albedo_lod).rgb;
    var color = albedo;
    if frame.lit != 0u {
        let normal_size = vec2<f32>(textureDimensions(normal_map));
        let normal_lod = lod(normal_size, material.normal_levels, s.duv_dx, s.duv_dy);
        let raw = textureSampleLevel(normal_map, map_sampler, hit.uv, normal_lod).xyz;
        let n = select(vec3<f32>(0.0, 0.0, 1.0), normalize(raw), dot(raw, raw) > 1e-30);
        var shadow = 1.0;
        if frame.lit == 2u {
            shadow = soft_shadow(hit.uv, hit.depth, s.light_ts, frame.shadow_samples);
        }
        color = light(albedo, n, s.light_ts, s.view_ts, shadow);
    }
    return Shaded(color, hit.uv, hit.layers);
}

// The image alone (timed runs). Alpha marks covered pixels (the clear leaves 0).
@fragment
fn fs_color(in: Varyings) -> @location(0) vec4<f32> {
    return vec4<f32>(shade(in).color, 1.0);
}

// The image with the debug targets: displaced UV and planned layer count.
struct DebugOut {
    @location(0) color: vec4<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) layers: u32,
}

@fragment
fn fs_debug(in: Varyings) -> DebugOut {
    let s = shade(in);
    return DebugOut(vec4<f32>(s.color, 1.0), s.uv, s.layers);
}
