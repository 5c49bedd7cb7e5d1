// Normal mapping, the GPU twin of `normal.rs`: no displacement; the frame lights the entry
// point with the normal map.
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    return Hit(uv, 0.0, 0u);
}
