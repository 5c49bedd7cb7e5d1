// The split screen's error half: the technique's picture left of the split, and right of it
// the per-pixel error against the reference, mean over R, G, B of |technique − reference| in
// 8-bit sRGB codes (the lab's `per_pixel_abs_error`), mapped through the lab's heat ramp
// (sampled into `ramp`), from 0 at the cold end to `1 / inv_max` and above at the hot end.
// Pixels no surface covers (alpha 0 in the technique's picture) are the lab's masked grey.
// Both inputs and the output are read and written as codes (non-sRGB views), so the
// technique's half is copied bit for bit.

struct Params {
    masked: vec4<f32>,
    split_x: u32,
    inv_max: f32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var technique_img: texture_2d<f32>;
@group(0) @binding(1) var reference_img: texture_2d<f32>;
@group(0) @binding(2) var<uniform> params: Params;
@group(0) @binding(3) var<uniform> ramp: array<vec4<f32>, 256>;

// One triangle covering the frame.
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    return vec4<f32>(x * 2.0 - 1.0, 1.0 - y * 2.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(pos.xy);
    let a = textureLoad(technique_img, p, 0);
    if u32(p.x) < params.split_x {
        return vec4<f32>(a.rgb, 1.0);
    }
    if a.a < 0.5 {
        return params.masked;
    }
    let b = textureLoad(reference_img, p, 0);
    let d = abs(a.rgb - b.rgb);
    let e = (d.r + d.g + d.b) / 3.0;
    let t = clamp(e * params.inv_max, 0.0, 1.0) * 255.0;
    let i = min(u32(t), 254u);
    return vec4<f32>(mix(ramp[i].rgb, ramp[i + 1u].rgb, t - f32(i)), 1.0);
}
