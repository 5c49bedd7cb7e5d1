// Tone mapping and display encoding (`deferred::tonemap`): exposure, the tone curve per
// channel, then 8-bit sRGB, packed RGBA8 (alpha 255).

@group(1) @binding(7) var<storage, read_write> hdr: array<vec4f>;
@group(1) @binding(8) var<storage, read_write> ldr: array<u32>;

fn tone_curve(x0: f32) -> f32 {
    var x = 0.0;
    if is_finite(x0) {
        x = max(x0, 0.0);
    }
    let op = frame.params.y;
    if op == 0u {
        return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    }
    if op == 1u {
        return x / (1.0 + x);
    }
    return min(x, 1.0);
}

fn encode(c0: f32) -> u32 {
    let c = clamp(c0, 0.0, 1.0);
    var s = c * 12.92;
    if c > 0.0031308 {
        s = 1.055 * pow(c, 1.0 / 2.4) - 0.055;
    }
    return u32(s * 255.0 + 0.5);
}

@compute @workgroup_size(8, 8, 1)
fn tonemap_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let c = hdr[i].xyz * frame.sky.w;
    let r = encode(tone_curve(c.x));
    let g = encode(tone_curve(c.y));
    let b = encode(tone_curve(c.z));
    ldr[i] = r | (g << 8u) | (b << 16u) | (255u << 24u);
}
