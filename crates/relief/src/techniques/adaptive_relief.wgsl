// Angle-adaptive relief mapping, the GPU twin of `adaptive_relief.rs`: relief mapping whose
// linear step count is the ray's path through the relief box in texels over
// `TEXELS_PER_STEP`, clamped to MIN..MAX. Parameters 0, 1, 2: MIN, MAX, BINARY.

// Texels of ray travel one linear step may cover, as `TEXELS_PER_STEP` in the CPU twin.
const TEXELS_PER_STEP: f32 = 6.0;

fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let lo = param(0u);
    let hi = param(1u);
    let dp = uv_per_depth(view_ts);
    let len = length(dp * vec2<f32>(textureDimensions(depth_map)));
    let n = ceil(len / TEXELS_PER_STEP);
    let steps = clamp(u32(min(n, f32(hi))), max(lo, 1u), max(hi, 1u));
    return relief_trace(uv, view_ts, steps, param(2u));
}
