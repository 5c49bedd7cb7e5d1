// The reflection pass: the lit opaque image (`lit_opaque`: emitted + direct + ambient · AO,
// the sky where no surface is), then screen-space reflections of it
// (`screen_space_reflections`): the mirrored view ray marched linearly across the screen in
// `stride` pixel steps, its view depth interpolated perspective-correctly, the first
// crossing behind the depth buffer refined by bisection and accepted within the thickness
// on a surface facing the ray; the sky where nothing is found or the surface is too rough.
// The reflected radiance is weighted by the split-sum specular weight.

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(3) var<storage, read_write> direct: array<vec4f>;
@group(1) @binding(4) var<storage, read_write> ambient: array<vec4f>;
@group(1) @binding(5) var<storage, read_write> specular: array<vec4f>;
@group(1) @binding(6) var<storage, read_write> lit: array<vec4f>;
@group(1) @binding(12) var<storage, read_write> depth: array<f32>;

@compute @workgroup_size(8, 8, 1)
fn lit_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    var c = frame.sky.xyz;
    if gp_valid(sp) {
        c = sp.e.xyz + direct[i].xyz + ambient[i].xyz * ambient[i].w;
    }
    lit[i] = vec4f(c, 0.0);
}

// Pixel position (xy) and reciprocal view depth (z) of a world point.
fn project(p: vec3f) -> vec3f {
    let c = frame.view_proj * vec4f(p, 1.0);
    let s = vec2f((c.x / c.w + 1.0) * 0.5 * f32(frame.size.x), (1.0 - c.y / c.w) * 0.5 * f32(frame.size.y));
    return vec3f(s, 1.0 / c.w);
}

fn screen_exit(s0: vec2f, delta: vec2f, size: vec2f) -> f32 {
    var t = 1.0;
    for (var axis = 0; axis < 2; axis++) {
        let d = delta[axis];
        if d > 0.0 {
            t = min(t, (size[axis] - s0[axis]) / d);
        } else if d < 0.0 {
            t = min(t, -s0[axis] / d);
        }
    }
    return max(t, 0.0);
}

struct Step {
    ok: bool,
    k: u32,
    z: f32,
}

fn at(s0: vec2f, delta: vec2f, k0: f32, k1: f32, t: f32) -> Step {
    let s = s0 + delta * t;
    var out: Step;
    out.ok = s.x >= 0.0 && s.y >= 0.0 && s.x < f32(frame.size.x) && s.y < f32(frame.size.y);
    if out.ok {
        out.k = u32(s.y) * frame.size.x + u32(s.x);
        out.z = 1.0 / (k0 + (k1 - k0) * t);
    }
    return out;
}

fn offset_origin(sp: Surface, dir: vec3f) -> vec3f {
    let p = sp.p.xyz;
    let a = abs(p);
    let scale = 1e-4 * (1.0 + max(a.x, max(a.y, a.z)));
    var n = sp.g.xyz;
    if dot(dir, n) < 0.0 {
        n = -n;
    }
    return p + n * scale;
}

// The pixel the ray from `o` along unit `r` meets first, or NONE.
fn march(o: vec3f, r: vec3f) -> u32 {
    let z0 = dot(o - frame.eye.xyz, frame.forward.xyz);
    let dz = dot(r, frame.forward.xyz);
    let near = frame.right.w * 1.01;
    if z0 <= near {
        return NONE;
    }
    var len = frame.ssr.w;
    if z0 + dz * len < near {
        len = (near - z0) / dz;
    }
    let p0 = project(o);
    let p1 = project(o + r * len);
    if !(is_finite(p0.x) && is_finite(p0.y) && is_finite(p1.x) && is_finite(p1.y) && is_finite(p0.z) && is_finite(p1.z)) {
        return NONE;
    }
    let s0 = p0.xy;
    let k0 = p0.z;
    let exit = screen_exit(s0, p1.xy - s0, vec2f(f32(frame.size.x), f32(frame.size.y)));
    let delta = (p1.xy - s0) * exit;
    let k1 = k0 + (p1.z - k0) * exit;
    let longest = max(abs(delta.x), abs(delta.y));
    let steps = clamp(u32(ceil(longest / frame.ssr.y)), 1u, max(frame.ssr_steps.x, 1u));
    var prev = 0.0;
    for (var i = 1u; i <= steps; i++) {
        let t = f32(i) / f32(steps);
        let st = at(s0, delta, k0, k1, t);
        if !st.ok {
            return NONE;
        }
        if st.z >= depth[st.k] {
            var a = prev;
            var b = t;
            for (var j = 0u; j < frame.ssr_steps.y; j++) {
                let m = 0.5 * (a + b);
                let sm = at(s0, delta, k0, k1, m);
                if sm.ok && sm.z >= depth[sm.k] {
                    b = m;
                } else {
                    a = m;
                }
            }
            let sb = at(s0, delta, k0, k1, b);
            if !sb.ok {
                return NONE;
            }
            let hit = unpack_surface(gbuf[sb.k]);
            let front = gp_valid(hit) && dot(hit.n.xyz, r) < 0.0;
            if front && sb.z - depth[sb.k] < frame.ssr.z {
                return sb.k;
            }
        }
        prev = t;
    }
    return NONE;
}

@compute @workgroup_size(8, 8, 1)
fn ssr_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    var c = vec3f(0.0);
    if gp_valid(sp) {
        let v = -view_dir(id.x, id.y);
        let n_dot_v = dot(sp.n.xyz, v);
        let weight = specular_weight(sp, n_dot_v);
        c = weight * frame.sky.xyz;
        if sp.g.w <= frame.ssr.x {
            let r = normalize_or_zero(2.0 * n_dot_v * sp.n.xyz - v);
            let hit = march(offset_origin(sp, r), r);
            if hit != NONE {
                c = weight * lit[hit].xyz;
            }
        }
    }
    specular[i] = vec4f(c, 0.0);
}
