// The room's picture copied pixel for pixel into egui's pass (see blit.rs): a triangle
// covering the viewport (the picture's rectangle, set by egui before the callback), each
// fragment loading the texel under it. No filtering, no blending.
//
// Then the HUD panels' backgrounds (look_and_feel.rs), one instanced quad per panel over the
// whole window: each fragment loads the picture's texel again and lays the panel's fill and
// border over it (a rounded-box distance at the pixel's centre, a one-pixel ramp at the
// edges), so only the panels' pixels pay for them and nothing is blended.

@group(0) @binding(0) var picture: texture_2d<f32>;

struct Panel {
    // min.xy, max.xy in framebuffer pixels
    rect: vec4<f32>,
    // premultiplied, in the target's encoding
    fill: vec4<f32>,
    stroke: vec4<f32>,
    // x: corner radius, y: border width (pixels)
    shape: vec4<f32>,
}

struct Panels {
    // xy: the framebuffer's size, zw: the picture's top-left corner in it (pixels)
    screen: vec4<f32>,
    panels: array<Panel, 8>,
}

@group(0) @binding(1) var<uniform> hud: Panels;

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

struct PanelOut {
    @builtin(position) pos: vec4<f32>,
    @location(0) @interpolate(flat) index: u32,
}

// A panel's quad (two triangles, six vertices) in a viewport covering the framebuffer.
@vertex
fn vs_panel(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> PanelOut {
    let corner = array<vec2<f32>, 6>(
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0),
        vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0),
    )[v];
    let r = hud.panels[i].rect;
    let px = mix(r.xy, r.zw, corner);
    let ndc = px / hud.screen.xy * 2.0 - 1.0;
    var out: PanelOut;
    out.pos = vec4<f32>(ndc.x, -ndc.y, 0.0, 1.0);
    out.index = i;
    return out;
}

// Signed distance from p to a box of half-size h centred at 0 with corners of radius r.
fn rounded_box(p: vec2<f32>, h: vec2<f32>, r: f32) -> f32 {
    let q = abs(p) - h + vec2<f32>(r);
    return length(max(q, vec2<f32>(0.0))) + min(max(q.x, q.y), 0.0) - r;
}

@fragment
fn fs_panel(in: PanelOut) -> @location(0) vec4<f32> {
    let p = hud.panels[in.index];
    let size = vec2<i32>(textureDimensions(picture));
    let texel = clamp(vec2<i32>(floor(in.pos.xy - hud.screen.zw)), vec2<i32>(0), size - 1);
    let color = textureLoad(picture, texel, 0).rgb;
    let h = 0.5 * (p.rect.zw - p.rect.xy);
    let d = rounded_box(in.pos.xy - 0.5 * (p.rect.xy + p.rect.zw), h, min(p.shape.x, min(h.x, h.y)));
    let inside = clamp(0.5 - d, 0.0, 1.0);
    let border = clamp(d + p.shape.y + 0.5, 0.0, 1.0) * step(0.001, p.shape.y);
    let c = mix(p.fill, p.stroke, border) * inside;
    return vec4<f32>(color * (1.0 - c.a) + c.rgb, 1.0);
}
