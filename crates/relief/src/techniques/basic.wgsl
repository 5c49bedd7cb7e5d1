// Basic texturing, the GPU twin of `basic.rs`: no displacement. The frame shades the result
// unlit (the technique's descriptor says so).
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    return Hit(uv, 0.0, 0u);
}
