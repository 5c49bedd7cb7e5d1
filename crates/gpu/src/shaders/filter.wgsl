// The texture-filter frame: one full-screen triangle whose fragments read their pixel's
// surface (the texture lab's exact UV and UV Jacobian, computed on the CPU in f64 as its
// filters receive them) and filter the scene's texture with the hardware's sampler or with
// EWA written in WGSL (`ewa.wgsl`, beside the CPU's `ewa.rs`). So the GPU and the CPU filter
// the same coordinates and footprints, and their difference is the filter's alone.
//
// The hardware's anisotropic filter takes its footprint from the implicit derivatives of the
// coordinate over the 2×2 quad, as on a rasterized surface: the coordinate is the pixel's
// texture coordinate before the reduction to one period (so that no derivative crosses a
// tile seam), and the derivatives are the differences of the exact mapping between
// neighbouring pixels. (Explicit gradients would pass the Jacobian itself, but lavapipe's
// anisotropic filter ignores them and keeps the quad's.)

// What is constant over a frame (`FilterUniform` on the Rust side).
struct Filter {
    // Background colour (rgb) where no surface shows.
    background: vec4<f32>,
    // 0: the sampler on level 0 (nearest, bilinear); 1: the sampler with the footprint's
    // gradients (trilinear: the hardware chooses the level); 2: EWA; 3: the sampler with the
    // quad's implicit derivatives (anisotropic: the hardware chooses level and probes).
    mode: u32,
    // 0: repeat; 1: clamp to edge.
    wrap: u32,
    // EWA's pixel-filter σ (pixels) and cut (in σ), eccentricity clamp and texel budget,
    // clamped to their ranges.
    ewa_sigma: f32,
    ewa_cut: f32,
    ewa_ecc: f32,
    ewa_texels: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> filter_params: Filter;
// The texture with every level of the CPU's pyramid.
@group(0) @binding(1) var filter_tex: texture_2d<f32>;
// The filter's sampler (for EWA: bilinear within a level, used only for its fallback).
@group(0) @binding(2) var filter_sampler: sampler;
// Per pixel: (u, v) reduced to one period and (U, V) not reduced; (∂u/∂x, ∂v/∂x, ∂u/∂y,
// ∂v/∂y); 1 where the surface shows, else 0.
@group(0) @binding(3) var surface_uv: texture_2d<f32>;
@group(0) @binding(4) var surface_jacobian: texture_2d<f32>;
@group(0) @binding(5) var surface_hit: texture_2d<f32>;

// A triangle covering the frame (vertices 0, 1, 2).
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

// The filtered colour; alpha marks pixels showing the surface.
@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(floor(position.xy));
    let s = textureLoad(surface_uv, p, 0);
    // Implicit derivatives need every pixel of the quad, so this runs before the branches
    // (a uniform's value keeps the control flow uniform).
    var implicit = vec4<f32>(0.0);
    if filter_params.mode == 3u {
        implicit = textureSample(filter_tex, filter_sampler, s.zw);
    }
    if textureLoad(surface_hit, p, 0).r < 0.5 {
        return vec4<f32>(filter_params.background.rgb, 0.0);
    }
    let j = textureLoad(surface_jacobian, p, 0);
    var c: vec4<f32>;
    switch filter_params.mode {
        case 0u: {
            c = textureSampleLevel(filter_tex, filter_sampler, s.xy, 0.0);
        }
        case 1u: {
            c = textureSampleGrad(filter_tex, filter_sampler, s.xy, j.xy, j.zw);
        }
        case 2u: {
            c = ewa(s.xy, j.xy, j.zw);
        }
        default: {
            c = implicit;
        }
    }
    return vec4<f32>(c.rgb, 1.0);
}
