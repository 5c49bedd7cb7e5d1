// Steep parallax mapping, the GPU twin of `steep.rs`: the layered march's first layer below
// the surface, without interpolation. Parameter 0: LAYERS.
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let layers = param(0u);
    let m = layered_march(uv, layer_step(view_ts, layers), layers);
    return Hit(m.uv, m.layer, layers);
}
