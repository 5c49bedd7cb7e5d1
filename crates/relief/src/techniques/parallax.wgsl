// Parallax (offset) mapping, the GPU twin of `parallax.rs`: one depth fetch at the entry
// point, `uv − V.xy / V.z · depth · scale`, no offset limiting.
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let d = depth_at(uv);
    return Hit(uv + uv_per_depth(view_ts) * d, d, 1u);
}
