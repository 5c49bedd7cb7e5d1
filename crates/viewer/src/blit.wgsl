// The room's picture copied pixel for pixel into egui's pass (see blit.rs): a triangle
// covering the viewport (the picture's rectangle, set by egui before the callback), each
// fragment loading the texel under it. No filtering, no blending.

@group(0) @binding(0) var picture: texture_2d<f32>;

struct Out {
    @builtin(position) pos: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> Out {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var out: Out;
    out.pos = vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
    // Clip-space y points up, the picture's rows down.
    out.uv = vec2<f32>(p.x, 1.0 - p.y);
    return out;
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let size = vec2<i32>(textureDimensions(picture));
    let texel = clamp(vec2<i32>(floor(in.uv * vec2<f32>(size))), vec2<i32>(0), size - 1);
    return vec4<f32>(textureLoad(picture, texel, 0).rgb, 1.0);
}
