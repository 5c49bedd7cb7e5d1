// Parallax occlusion mapping, the GPU twin of `pom.rs` (its scalar kernel): the layered
// march, then the thesis's interpolation between the last two layers. Parameter 0: LAYERS.
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let layers = param(0u);
    let m = layered_march(uv, layer_step(view_ts, layers), layers);
    return interpolate(m, layers);
}
