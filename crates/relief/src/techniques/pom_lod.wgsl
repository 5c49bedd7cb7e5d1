// POM whose layers follow the parallax's length in pixels (footprint and view angle) and in
// texels, fading to normal mapping where it is sub-pixel: the GPU twin of `pom_lod.rs` (its
// maths there). Parameters 0, 1 and 2: MAX and MIN layers, FADE in tenths of a pixel. Reads
// the frame's `ray_ctx.footprint` (UV per pixel).

// The parallax in pixels (`parallax_px`); an unknown footprint (not positive) gives the
// largest f32, which every rule below treats as the CPU's +∞ (MAX layers, full weight).
fn parallax_px(view_ts: vec3<f32>, footprint: f32) -> f32 {
    if !(footprint > 0.0) {
        return 3.4028235e38;
    }
    let vz = max(view_ts.z, MIN_VIEW_Z);
    return material.height_scale * length(view_ts.xy) / vz / footprint;
}

fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let max_layers = param(0u);
    let min_layers = param(1u);
    let threshold = f32(param(2u)) / 10.0;
    let p = parallax_px(view_ts, ray_ctx.footprint);
    if !(p > threshold) {
        return Hit(uv, 0.0, 0u);
    }
    // The parallax in texels of the depth map's larger side (`parallax_texels`).
    let size = textureDimensions(depth_map);
    let vz = max(view_ts.z, MIN_VIEW_Z);
    let q = material.height_scale * length(view_ts.xy) / vz * f32(max(size.x, size.y));
    // max(MIN, min(MAX, ⌈max(p, q)⌉)) (`layer_count`).
    let pq = max(p, q);
    var n = max_layers;
    if pq < f32(max_layers) {
        n = u32(max(ceil(pq), 0.0));
    }
    n = max(max(n, min_layers), 1u);
    let hit = interpolate(layered_march(uv, layer_step(view_ts, n), n), n);
    // min(1, (p − T) / T) (`weight`).
    var w = 1.0;
    if threshold > 0.0 {
        w = clamp((p - threshold) / threshold, 0.0, 1.0);
    }
    if w >= 1.0 {
        return hit;
    }
    return Hit(uv + (hit.uv - uv) * w, hit.depth * w, n);
}
