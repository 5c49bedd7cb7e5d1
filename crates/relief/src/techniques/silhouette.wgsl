// Silhouette POM, the GPU twin of `silhouette.rs`: POM's layered march along the ray bent by
// the pixel's curvature (`ray_ctx.curvature`, 1/UV: the ray's depth below the curved top is
// t − c·t² with c = ½ (κ_T dp.x² + κ_B dp.y²) / height_scale), over [0, T] where the ray
// reaches the relief's bottom or, when 4c > 1, comes back out of the top (a miss if it has
// met nothing); a step leaving the patch's UV rectangle (`ray_ctx.uv_min/uv_max`) before a
// hit, or a hit outside it, is a miss too (depth −1). With no curvature and no bounds it is
// POM's march, operation for operation. Parameter 0: LAYERS.

// Whether `uv` lies in the patch's UV rectangle (false for NaN).
fn silhouette_contains(uv: vec2<f32>) -> bool {
    return all(uv >= ray_ctx.uv_min) && all(uv <= ray_ctx.uv_max);
}

fn silhouette_miss() -> Hit {
    return Hit(vec2<f32>(0.0), -1.0, 0u);
}

fn trace(uv0: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    if !silhouette_contains(uv0) {
        return silhouette_miss();
    }
    let n = max(param(0u), 1u);
    let dp = uv_per_depth(view_ts);
    let k = ray_ctx.curvature;
    var c = 0.5 * (k.x * dp.x * dp.x + k.y * dp.y * dp.y) / material.height_scale;
    // Non-finite (NaN fails the comparison): no curvature, as on the CPU.
    if !(abs(c) <= 3.4e38) {
        c = 0.0;
    }
    var span = 1.0;
    var exits = false;
    if c != 0.0 {
        if 4.0 * c <= 1.0 {
            span = 2.0 / (1.0 + sqrt(1.0 - 4.0 * c));
        } else {
            span = 1.0 / c;
            exits = true;
        }
    }
    let dt = span * (1.0 / f32(n));
    let step = dp * dt;
    var uv = uv0;
    var map = depth_at(uv);
    var prev_uv = uv;
    var prev_map = map;
    var i = 0u;
    var t = 0.0;
    var depth = t - c * t * t;
    while depth < map && i < n {
        prev_uv = uv;
        prev_map = map;
        i += 1u;
        t = f32(i) * dt;
        uv = uv0 + step * f32(i);
        map = depth_at(uv);
        depth = t - c * t * t;
        if depth < map && !silhouette_contains(uv) {
            return silhouette_miss();
        }
    }
    let crossed = i < n || depth >= map;
    if !crossed && exits {
        return silhouette_miss();
    }
    let pt = t - dt;
    let prev_depth = select(pt - c * pt * pt, 0.0, i == 0u);
    let hit = interpolate(March(prev_uv, prev_map, prev_depth, uv, map, depth), n);
    if !silhouette_contains(hit.uv) {
        return silhouette_miss();
    }
    return hit;
}
