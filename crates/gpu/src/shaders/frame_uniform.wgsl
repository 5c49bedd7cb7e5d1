// The relief frame's constants, shared by every module of both pipelines (the shading
// modules and the compute pipeline's visibility pass).

// What is constant over a frame (`FrameUniform` on the Rust side).
struct Frame {
    view_proj: mat4x4<f32>,
    // Eye position (xyz).
    eye: vec4<f32>,
    // Unit vector toward the light (xyz).
    to_light: vec4<f32>,
    // The technique's parameters in descriptor order (see `param`).
    params: vec4<u32>,
    // Ambient factor, Blinn–Phong exponent and strength.
    ambient: f32,
    specular_exponent: f32,
    specular_strength: f32,
    // 0: unlit (albedo alone); 1: lit; 2: lit with soft self-shadows; 3: lit with horizon
    // self-shadows.
    lit: u32,
    // Samples along the light ray of the soft shadows (`ShadowMode::Soft`), or the most
    // samples of the horizon shadows (`ShadowMode::Horizon`).
    shadow_samples: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    // The compute pipeline's camera rays: the ray through pixel position p (pixels from the
    // top-left corner, centres at +0.5) is eye + s·(ray_base + p.x·ray_dx + p.y·ray_dy), s
    // the view depth (the direction's component along the view axis is 1).
    ray_base: vec4<f32>,
    ray_dx: vec4<f32>,
    ray_dy: vec4<f32>,
    // Linear colour where no surface shows (rgb).
    background: vec4<f32>,
    // Frame size in pixels.
    size: vec2<u32>,
    // The near and far clipping distances (view depth).
    depth_range: vec2<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
