// Soft self-shadowing toward the light, the GPU twin of `renderlab_relief::render::shadow`:
// the light ray sampled from the hit up to the top surface, darkened by the deepest
// penetration of the surface above it, weighted down with distance. 1 lit … 0 shadowed.
fn soft_shadow(uv: vec2<f32>, depth: f32, light_ts: vec3<f32>, samples: u32) -> f32 {
    if light_ts.z <= 0.0 {
        return 0.0;
    }
    if depth <= 0.0 || samples == 0u {
        return 1.0;
    }
    let lz = max(light_ts.z, MIN_VIEW_Z);
    let dl = light_ts.xy / lz * material.height_scale;
    let n = f32(samples);
    let step = depth / n;
    var occlusion = 0.0;
    for (var i = 1u; i <= samples; i += 1u) {
        let risen = step * f32(i);
        let ray_depth = depth - risen;
        let map = depth_at(uv + dl * risen);
        let pen = (ray_depth - map) * (1.0 - f32(i) / (n + 1.0));
        occlusion = max(occlusion, pen);
    }
    return 1.0 - clamp(occlusion * SHADOW_SHARPNESS, 0.0, 1.0);
}

// Horizon self-shadowing toward a light disc of angular radius `radius`, the GPU twin of
// `renderlab_relief::render::horizon::horizon_shadow` (its module docs state the maths): the
// receiver re-seated on the surface at `uv`, the horizon toward the light marched in texel
// steps along the light's azimuth (a texel apart near the receiver, growing geometrically to
// the reach when `steps` do not cover it), and the fraction of the disc above the horizon.
// 1 lit … 0 shadowed.
fn horizon_shadow(uv: vec2<f32>, light_ts: vec3<f32>, steps: u32, radius_in: f32) -> f32 {
    if light_ts.z <= 0.0 {
        return 0.0;
    }
    let horiz = length(light_ts.xy);
    if steps == 0u || !(horiz > 1e-6 * light_ts.z) || !(material.height_scale > 0.0) {
        return 1.0;
    }
    let radius = select(0.0, radius_in, radius_in > 0.0);
    let size = vec2<f32>(textureDimensions(depth_map));
    let e = light_ts.xy / horiz;
    let c = max(abs(e.x) * size.x, abs(e.y) * size.y);
    let du = e / c;
    let theta = atan2(light_ts.z, horiz);
    let lo = theta - radius;
    let tan_lo = select(0.0, tan(lo), lo > 0.0);
    let hi = theta + radius;
    // Above the zenith the disc's top edge is never reached (+∞ on the CPU).
    let tan_hi = select(3.0e38, tan(hi), hi < 1.5707963267948966);
    let d0 = depth_at(uv);
    let rise = material.height_scale * c;
    let h_max = (d0 - HORIZON_DEPTH_BIAS) * rise;
    if !(h_max > 0.0) {
        return 1.0;
    }
    let cap = HORIZON_MAX_REACH_TILES * max(size.x, size.y);
    let r_end = select(cap, min(h_max / tan_lo, cap), tan_lo > 0.0);
    var n = steps;
    var m = max(steps / 4u, 1u);
    if r_end <= f32(steps) - 0.5 {
        n = clamp(u32(ceil(r_end + 0.5)), 1u, steps);
        m = n;
    }
    var q = 1.0;
    if n > m {
        q = pow(r_end / (f32(m) - 0.5), 1.0 / f32(n - m));
    }
    var t_max = 0.0;
    var r = 0.5;
    for (var i = 0u; i < n; i += 1u) {
        if i > 0u {
            r = select(r * q, r + 1.0, i < m);
        }
        if r * max(t_max, tan_lo) > h_max {
            break;
        }
        let d = depth_at(uv + du * r);
        t_max = max(t_max, (d0 - d - HORIZON_DEPTH_BIAS) * rise / r);
        if t_max >= tan_hi {
            return 0.0;
        }
    }
    let alpha = atan(t_max);
    var s = select(0.0, 1.0, alpha < theta);
    if radius > 0.0 {
        let x = clamp((alpha - theta) / radius, -1.0, 1.0);
        s = (acos(x) - x * sqrt(max(1.0 - x * x, 0.0))) * 0.3183098861837907;
    }
    return clamp(s, 0.0, 1.0);
}
