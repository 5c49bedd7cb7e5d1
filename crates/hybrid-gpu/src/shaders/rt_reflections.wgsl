// Ray-traced reflections (the CPU's `reflections::run`), after the lit image and SSR: every
// opaque pixel no rougher than `values.x` overwrites its specular term with one reflected
// path of up to `counts.x` bounces (`gather`) times its split-sum specular weight; rougher
// pixels keep the SSR result. rt/stages.rs puts MIRROR_ROUGHNESS (the CPU's) before this file.

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(5) var<storage, read_write> specular: array<vec4f>;

// reflections::reflected_dir: the mirror direction below MIRROR_ROUGHNESS, else the
// reflection of `v` about a GGX visible normal; a direction below the face falls back to the
// mirror direction, or the reflection about the face normal.
fn reflected_dir(sp: Surface, v: vec3f, rng: ptr<function, vec2u>) -> vec3f {
    let mirror = mirror_dir(v, sp.n.xyz);
    var l = mirror;
    if sp.g.w >= MIRROR_ROUGHNESS {
        let v_local = frame_to_local(sp.n.xyz, v);
        if v_local.z > 0.0 {
            let m = frame_to_world(sp.n.xyz, ggx_visible_normal(v_local, ggx_alpha(sp.g.w), rng_vec2(rng)));
            l = mirror_dir(v, m);
        }
    }
    if dot(l, sp.g.xyz) <= 0.0 {
        if dot(mirror, sp.g.xyz) > 0.0 {
            l = mirror;
        } else {
            l = mirror_dir(v, sp.g.xyz);
        }
    }
    return normalize_exact(l);
}

// reflections::gather: the radiance arriving at `sp` along its reflected path. Each hit
// gives its emission, direct light (one random sample per area light) and ambient term; the
// path goes on, weighted by the hit's specular weight, while bounces remain and the hit is
// no rougher than `max_roughness`, and otherwise ends with the sky times that weight. An
// escaping ray sees the sky.
fn gather(sp: Surface, v0: vec3f, bounces: u32, max_roughness: f32, rng: ptr<function, vec2u>, rays: ptr<function, u32>) -> vec3f {
    var radiance = vec3f(0.0);
    var throughput = vec3f(1.0);
    var at = sp;
    var v = v0;
    for (var bounce = 1u; bounce <= bounces; bounce++) {
        let dir = reflected_dir(at, v, rng);
        *rays += 1u;
        let hit = trace_surface(offset_origin(at, dir), dir);
        if !gp_valid(hit) {
            return radiance + throughput * frame.sky.xyz;
        }
        let hv = -dir;
        radiance += throughput * (hit.e.xyz + direct_light(hit, hv, 1u, rng, rays) + ambient_term(hit, hv));
        let weight = specular_weight(hit, dot(hit.n.xyz, hv));
        if bounce == bounces || hit.g.w > max_roughness {
            return radiance + throughput * weight * frame.sky.xyz;
        }
        throughput *= weight;
        at = hit;
        v = hv;
    }
    return radiance;
}

@compute @workgroup_size(8, 8, 1)
fn rt_reflections_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    if !gp_valid(sp) || sp.g.w > rtp.values.x {
        return;
    }
    var rng = rng_new(rtp.counts.zw, i);
    var rays = 0u;
    let v = -view_dir(id.x, id.y);
    let gathered = gather(sp, v, rtp.counts.x, rtp.values.x, &rng, &rays);
    specular[i] = vec4f(specular_weight(sp, dot(sp.n.xyz, v)) * gathered, 0.0);
    count_rays(rays);
}
