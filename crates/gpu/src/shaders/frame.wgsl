// The relief frame on the GPU, the twin of `renderlab_relief::render::shade`: the frame's
// and the materials' bindings, the per-pixel surface (UV, its exact screen Jacobian, the
// tangent frame), texture sampling and the thesis's lighting. Both pipelines call `shade`
// with the surface their own entry points reconstruct: `fragment.wgsl` from the hardware
// rasterizer's interpolants, `compute.wgsl` from the visibility buffer.
//
// Conventions as on the CPU: tangent space is (T, B, N) = (direction of increasing u,
// direction of increasing v, normal); colours are linear; pixel centres are at +0.5.

// One material's constants (`MaterialUniform`).
struct Material {
    // Depth scale in UV per unit depth.
    height_scale: f32,
    // Mip levels of the albedo and normal textures.
    albedo_levels: f32,
    normal_levels: f32,
    // The material's index in the scene's list (the compute pipeline shades one material
    // per dispatch and skips the others' pixels).
    index: u32,
    // Levels of the min-depth pyramid in `pyramid_map`.
    pyramid_levels: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

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
// The min-depth pyramid of space leaping, its levels side by side (`upload.rs`'s atlas), read
// with `textureLoad`.
@group(1) @binding(7) var pyramid_map: texture_2d<f32>;

// What the rasterizer knows about one pixel (`SurfacePoint`).
struct Surface {
    uv: vec2<f32>,
    duv_dx: vec2<f32>,
    duv_dy: vec2<f32>,
    view_ts: vec3<f32>,
    light_ts: vec3<f32>,
    // Distance from the eye to the surface point (world units).
    eye_distance: f32,
    // World units per UV unit (`PatchInfo::world_per_uv`; 0 when the mapping is degenerate).
    world_per_uv: f32,
}

// The surface from its interpolated attributes, its exact UV Jacobian and its scale in world
// units per UV unit: the tangent frame as `tangent_frame` builds it (N, T by Gram–Schmidt,
// B = N × T · sign) and the view and light directions in it.
fn surface_from(
    uv: vec2<f32>,
    duv_dx: vec2<f32>,
    duv_dy: vec2<f32>,
    world: vec3<f32>,
    normal: vec3<f32>,
    tangent: vec4<f32>,
    world_per_uv: f32,
) -> Surface {
    var s: Surface;
    s.eye_distance = length(frame.eye.xyz - world);
    s.world_per_uv = world_per_uv;
    s.uv = uv;
    s.duv_dx = duv_dx;
    s.duv_dy = duv_dy;
    let n = normalize(normal);
    var t = tangent.xyz - n * dot(n, tangent.xyz);
    t = select(vec3<f32>(1.0, 0.0, 0.0), normalize(t), dot(t, t) > 0.0);
    let handedness = select(1.0, -1.0, tangent.w < 0.0);
    let b = cross(n, t) * handedness;
    let view = normalize(frame.eye.xyz - world);
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

// What the frame knows about a ray's pixel besides the ray (`RayContext`): the footprint in
// UV per pixel, the patch's curvature along T and B in 1/UV (0: flat) and its UV rectangle in
// the ray's own coordinates (moved into the first tile with the UV; ±3.4e38: unbounded).
struct RayContext {
    footprint: f32,
    curvature: vec2<f32>,
    uv_min: vec2<f32>,
    uv_max: vec2<f32>,
}

// The context of the ray being traced, set by `shade` before it calls `trace`; techniques that
// adapt to the footprint or the patch read it.
var<private> ray_ctx: RayContext;

// UV per pixel: the longer screen derivative (`footprint`).
fn footprint(duv_dx: vec2<f32>, duv_dy: vec2<f32>) -> f32 {
    return max(length(duv_dx), length(duv_dy));
}

// One shaded pixel and what the debug targets show of it. `covered` is false where the trace
// missed the relief (a silhouette): the entry points leave the background there.
struct Shaded {
    color: vec3<f32>,
    uv: vec2<f32>,
    layers: u32,
    covered: bool,
    // The pixel-depth offset: distance from the eye to the displaced hit (`offset_depth`).
    view_depth: f32,
}

// World units per UV unit of a surface whose position and UV change by (dp1, duv1) and
// (dp2, duv2) along two directions: √(|dp1 × dp2| / |duv1 × duv2|), the CPU's per-patch
// √(world area / UV area); 0 where the UV mapping is degenerate.
fn world_per_uv(dp1: vec3<f32>, dp2: vec3<f32>, duv1: vec2<f32>, duv2: vec2<f32>) -> f32 {
    let uv_area = abs(duv1.x * duv2.y - duv1.y * duv2.x);
    let world_area = length(cross(dp1, dp2));
    return select(0.0, sqrt(world_area / uv_area), uv_area > 0.0 && world_area < 3.4e38);
}

// Traces and lights one pixel (`shade_point`): the ray enters at its UV moved into the first
// tile (the field repeats, so the hit is the same and f32 keeps its precision), the hit moves
// back, and the maps are sampled there with the level of the undisplaced footprint; a
// shadowed technique then marches toward the light from the hit (`soft_shadow`, or
// `horizon_shadow` when `frame.lit` is 3).
fn shade(s: Surface) -> Shaded {
    let base = floor(s.uv);
    let unbounded = vec2<f32>(3.4e38);
    ray_ctx = RayContext(footprint(s.duv_dx, s.duv_dy), vec2<f32>(0.0), -unbounded - base, unbounded - base);
    var hit = trace(s.uv - base, s.view_ts);
    if hit.depth < 0.0 {
        return Shaded(frame.background.xyz, vec2<f32>(0.0), 0u, false, 0.0);
    }
    // The hit's distance below the top surface along the ray, moved to world units.
    let along = length(vec3<f32>(hit.uv, hit.depth * material.height_scale) - vec3<f32>(s.uv - base, 0.0));
    let view_depth = s.eye_distance + select(0.0, along * s.world_per_uv, along < 3.4e38);
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
        } else if frame.lit == 3u {
            shadow = horizon_shadow(hit.uv, s.light_ts, frame.shadow_samples, HORIZON_LIGHT_RADIUS);
        }
        color = light(albedo, n, s.light_ts, s.view_ts, shadow);
    }
    return Shaded(color, hit.uv, hit.layers, true, view_depth);
}
