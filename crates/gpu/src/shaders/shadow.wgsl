// Soft self-shadowing toward the light, the GPU twin of `renderlab_relief::render::shadow`:
// the light ray sampled from the hit up to the top surface, darkened by the deepest
// penetration of the surface above it, weighted down with distance. 1 lit … 0 shadowed.
fn soft_shadow(uv: vec2<f32>, depth: f32, light_ts: vec3<f32>, samples: u32) -> f32 {
    if light_ts.z <= 0.0 {
        return 0.0;
    }
    if depth <= 0.0 || samples == 0u {
        return 1.0;
    }
    let lz = max(light_ts.z, MIN_VIEW_Z);
    let dl = light_ts.xy / lz * material.height_scale;
    let n = f32(samples);
    let step = depth / n;
    var occlusion = 0.0;
    for (var i = 1u; i <= samples; i += 1u) {
        let risen = step * f32(i);
        let ray_depth = depth - risen;
        let map = depth_at(uv + dl * risen);
        let pen = (ray_depth - map) * (1.0 - f32(i) / (n + 1.0));
        occlusion = max(occlusion, pen);
    }
    return 1.0 - clamp(occlusion * SHADOW_SHARPNESS, 0.0, 1.0);
}
