// The relief marches every technique shader builds on: the GPU twins of
// `renderlab_relief::march::layered` and `renderlab_relief::trace`, written with the same
// operations in the same order so that the CPU and the GPU agree up to f32 rounding and the
// sampler's arithmetic.
//
// The contract with the technique files (`crates/relief/src/techniques/*.wgsl`): each defines
// `fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit`, where `uv` is the entry point moved
// into the first texture tile and `view_ts` the unit direction toward the eye in tangent
// space, and may call every function of this file.

// Where a technique decided the view ray meets the height field (`ReliefHit`).
struct Hit {
    // Displaced texture coordinate.
    uv: vec2<f32>,
    // Depth of the hit below the top surface, in [0, 1].
    depth: f32,
    // Layers (or steps) the technique planned for this pixel; 0 without layers.
    layers: u32,
}

// The state at the end of a layered march (`March`).
struct March {
    prev_uv: vec2<f32>,
    prev_map: f32,
    prev_layer: f32,
    uv: vec2<f32>,
    map: f32,
    layer: f32,
}

// Smallest tangent-space V.z divided by (`MIN_VIEW_Z`).
const MIN_VIEW_Z: f32 = 1e-3;

// The technique's parameter `i`, in its descriptor's order.
fn param(i: u32) -> u32 {
    return frame.params[i];
}

// `a + (b − a)·t`: the CPU's `mix`, with its rounding (WGSL's `mix` rounds differently).
fn lerp(a: f32, b: f32, t: f32) -> f32 {
    return a + (b - a) * t;
}

// The depth map (`1 − height`), bilinear with repeat wrap, as `HeightField::depth`.
fn depth_at(uv: vec2<f32>) -> f32 {
    return textureSampleLevel(depth_map, map_sampler, uv, 0.0).r;
}

// The complexity map at `uv`, nearest texel with repeat wrap, as
// `ReliefInputs::complexity_at` (floor, then wrap; non-finite coordinates give 0).
fn complexity_at(uv: vec2<f32>) -> f32 {
    let size = vec2<i32>(textureDimensions(complexity_map));
    let p = floor(uv * vec2<f32>(size));
    // Beyond ±2^30 (or NaN) the CPU's answer is its wrap of a huge index; such UVs never
    // occur on the scene's surfaces, so they read 0 as non-finite ones do.
    if !(all(abs(p) < vec2<f32>(1073741824.0))) {
        return 0.0;
    }
    let q = ((vec2<i32>(p) % size) + size) % size;
    return textureLoad(complexity_map, q, 0).r;
}

// UV offset per unit depth, `−V.xy / V.z · scale`, with V.z clamped (`uv_per_depth`).
fn uv_per_depth(view_ts: vec3<f32>) -> vec2<f32> {
    let vz = max(view_ts.z, MIN_VIEW_Z);
    return -view_ts.xy / vz * material.height_scale;
}

// UV step of one layer of `layers` (`layer_step`).
fn layer_step(view_ts: vec3<f32>, layers: u32) -> vec2<f32> {
    let layer_depth = 1.0 / f32(max(layers, 1u));
    return uv_per_depth(view_ts) * layer_depth;
}

// `layers` equal depth steps from `uv0`, each moving `step`, until the layer depth reaches the
// depth map; bounded by `layers` (`layered_march`).
fn layered_march(uv0: vec2<f32>, step: vec2<f32>, layers: u32) -> March {
    let n = max(layers, 1u);
    let layer_depth = 1.0 / f32(n);
    var uv = uv0;
    var map = depth_at(uv);
    var prev_uv = uv;
    var prev_map = map;
    var i = 0u;
    // Invariant: the layer at index i has depth i / n.
    while f32(i) * layer_depth < map && i < n {
        prev_uv = uv;
        prev_map = map;
        i += 1u;
        uv = uv0 + step * f32(i);
        map = depth_at(uv);
    }
    let layer = f32(i) * layer_depth;
    let prev_layer = select(layer - layer_depth, 0.0, i == 0u);
    return March(prev_uv, prev_map, prev_layer, uv, map, layer);
}

// The thesis's POM interpolation between the last two layers (`interpolate`).
fn interpolate(m: March, layers: u32) -> Hit {
    let after = m.map - m.layer;
    let before = m.prev_map - m.prev_layer;
    let denom = after - before;
    let w = select(0.0, clamp(after / denom, 0.0, 1.0), abs(denom) > 1e-12);
    return Hit(m.prev_uv * w + m.uv * (1.0 - w), m.prev_layer * w + m.layer * (1.0 - w), layers);
}

// Bisection of the bracket [a, b] of depths along the ray `uv0 + dp·t`, `a` above the
// surface and `b` at or below, for `steps` iterations; the midpoint of the final bracket as
// (u, v, depth) (`bisect`).
fn bisect(uv0: vec2<f32>, dp: vec2<f32>, a0: f32, b0: f32, steps: u32) -> vec3<f32> {
    var a = a0;
    var b = b0;
    for (var i = 0u; i < steps; i += 1u) {
        let mid = 0.5 * (a + b);
        let map = depth_at(uv0 + dp * mid);
        if mid >= map {
            b = mid;
        } else {
            a = mid;
        }
    }
    let t = 0.5 * (a + b);
    return vec3<f32>(uv0 + dp * t, t);
}

// Relief mapping's two phases with `linear` layers and `binary` bisection steps: the layered
// march, then bisection between its last two layers (a ray that meets the relief at its top
// surface stops there).
fn relief_trace(uv: vec2<f32>, view_ts: vec3<f32>, linear: u32, binary: u32) -> Hit {
    let m = layered_march(uv, layer_step(view_ts, linear), linear);
    if m.layer == 0.0 {
        return Hit(uv, 0.0, linear);
    }
    let hit = bisect(uv, uv_per_depth(view_ts), m.prev_layer, m.layer, binary);
    return Hit(hit.xy, hit.z, linear);
}
