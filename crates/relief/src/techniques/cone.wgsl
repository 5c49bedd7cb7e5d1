// Relaxed cone stepping, the GPU twin of `cone.rs` (its tracer `march::cone_step`): cone
// steps on the relaxed cone map until the ray is below the surface (or, out of steps, a short
// linear march toward the bottom), then the bracketed crossing refined by bisection or by
// Illinois false position. One ray's state machine of the CPU (`Lane::advance`) written as
// its three phases in sequence, with the same operations in the same order.
// Parameters 0, 1, 2: STEPS, REFINE_STEPS, REFINEMENT (0 binary, 1 secant).

// The hit at depth `t` along the ray.
fn cone_hit(uv0: vec2<f32>, dp: vec2<f32>, t: f32, steps: u32) -> Hit {
    return Hit(uv0 + dp * t, t, steps);
}

// The false-position estimate inside the bracket `[a, b]` (`Lane::interp`).
fn cone_interp(a: f32, fa: f32, b: f32, fb: f32) -> f32 {
    let den = fb - fa;
    if den > 1e-12 {
        return clamp((a * fb - b * fa) / den, a, b);
    }
    return 0.5 * (a + b);
}

fn trace(uv0: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let steps = param(0u);
    let refine_steps = param(1u);
    let secant = param(2u) == 1u;
    let dp = uv_per_depth(view_ts);
    let s = sqrt(dot(dp, dp));
    // Secant mode stops within CONE_TOLERANCE_TEXELS of the surface, along the surface.
    var eps = 0.0;
    if secant {
        let size = textureDimensions(depth_map);
        let texels_per_depth = s * f32(max(size.x, size.y));
        eps = clamp(CONE_TOLERANCE_TEXELS / max(texels_per_depth, 1e-3), 1e-6, 1e-3);
    }
    // The last depth known above the surface with f = t − D there, the first known below.
    var t = 0.0;
    var a = 0.0;
    var fa = -1.0;
    var b = 1.0;
    var fb = 0.0;
    // Cone steps.
    var bracketed = false;
    var tail_from = 0.0;
    for (var i = 0u; i < steps; i += 1u) {
        let uv = uv0 + dp * t;
        let map = depth_at(uv);
        let f = t - map;
        if f >= 0.0 {
            b = t;
            fb = f;
            bracketed = true;
            break;
        }
        if -f <= eps {
            return cone_hit(uv0, dp, t, steps);
        }
        a = t;
        fa = f;
        let r = cone_ratio(uv);
        var step = map - t;
        if s > 0.0 {
            step = r * (map - t) / (s + r);
        }
        t = min(t + max(step, 1e-4), 1.0);
        tail_from = t;
    }
    // Out of cone steps: samples from the last cone position (inclusive) to the bottom.
    if !bracketed {
        for (var i = 1u; i <= CONE_TAIL + 1u; i += 1u) {
            let ti = tail_from + (1.0 - tail_from) * f32(i - 1u) / f32(CONE_TAIL);
            let f = ti - depth_at(uv0 + dp * ti);
            if f >= 0.0 || i > CONE_TAIL {
                b = ti;
                fb = max(f, 0.0);
                break;
            }
            a = ti;
            fa = f;
        }
    }
    if b <= 0.0 {
        return cone_hit(uv0, dp, 0.0, steps);
    }
    if refine_steps == 0u {
        return cone_hit(uv0, dp, b, steps);
    }
    // Refinement; `side` is Illinois's memory of which end moved last.
    var side = 0;
    for (var k = 0u; k < refine_steps; k += 1u) {
        var c = 0.5 * (a + b);
        if secant {
            c = cone_interp(a, fa, b, fb);
        }
        let fc = c - depth_at(uv0 + dp * c);
        if secant && abs(fc) <= eps {
            return cone_hit(uv0, dp, c, steps);
        }
        if fc >= 0.0 {
            b = c;
            fb = fc;
            if side == -1 && secant {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side == 1 && secant {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    var t_end = 0.5 * (a + b);
    if secant {
        t_end = cone_interp(a, fa, b, fb);
    }
    return cone_hit(uv0, dp, t_end, steps);
}
