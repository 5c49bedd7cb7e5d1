// Ray-traced translucency (the CPU's `translucency::run`), after the composition and forward
// translucent pass: every pixel whose nearest translucent layer is no rougher than
// `values.x` overwrites the final image with one path followed through the glass
// (`follow`, at most `counts.x` rays leaving translucent surfaces); rougher pixels keep the
// forward pass's result, the CPU's fallback.

@group(1) @binding(7) var<storage, read_write> hdr: array<vec4f>;

// What happens at a dielectric interface (`translucency::interface`).
struct Dielectric {
    fresnel: f32,
    refracted: Refracted,
    reflected: vec3f,
}

// translucency::interface: seen from the unit `v` on the side of the unit normal `m`, from
// outside when `entering`; Schlick's Fresnel with F0 from the ior, the cosine taken on the
// thinner side; 1 under total internal reflection.
fn dielectric(v: vec3f, m: vec3f, ior: f32, entering: bool) -> Dielectric {
    var eta = ior;
    if entering {
        eta = 1.0 / ior;
    }
    var out: Dielectric;
    out.reflected = mirror_dir(v, m);
    out.refracted = refract_dir(v, m, eta);
    out.fresnel = 1.0;
    if out.refracted.ok {
        var c = -dot(out.refracted.dir, m);
        if entering {
            c = dot(v, m);
        }
        let r = (ior - 1.0) / (ior + 1.0);
        out.fresnel = fresnel_schlick(clamp(c, 0.0, 1.0), vec3f(r * r)).x;
    }
    return out;
}

// translucency::follow: one path from the translucent surface `sp` seen from the unit `v0`.
// At each translucent surface: its emission and direct light, then (while rays remain) a
// reflection or a refraction about its normal — a GGX visible normal where it is at least
// 0.02 and at most `max_roughness` rough — chosen by Fresnel, a refraction tinted by
// transmission × base colour. An opaque hit adds its emission, direct light and ambient term
// and ends the path; an escape adds the sky; an exhausted path adds nothing more.
fn follow(sp: Surface, v0: vec3f, max_rays: u32, max_roughness: f32, rng: ptr<function, vec2u>, rays: ptr<function, u32>) -> vec3f {
    var radiance = vec3f(0.0);
    var throughput = vec3f(1.0);
    var at = sp;
    var v = v0;
    radiance += throughput * (at.e.xyz + direct_light(at, v, 1u, rng, rays));
    for (var used = 0u; used < max_rays; used++) {
        var m = at.n.xyz;
        if at.g.w >= 0.02 && at.g.w <= max_roughness {
            let v_local = frame_to_local(at.n.xyz, v);
            if v_local.z > 0.0 {
                m = frame_to_world(at.n.xyz, ggx_visible_normal(v_local, ggx_alpha(at.g.w), rng_vec2(rng)));
            }
        }
        let ifc = dielectric(v, m, gp_ior(at), at.ids.z == 1u);
        var dir = ifc.reflected;
        if ifc.refracted.ok {
            if rng_f32(rng) >= ifc.fresnel {
                throughput *= at.e.w * at.c.xyz;
                dir = ifc.refracted.dir;
            }
        }
        let origin = offset_origin(at, dir);
        *rays += 1u;
        let h = rt_closest(origin, dir, 0.0, F32_MAX, 0xffu);
        if h.instance == RT_NO_HIT {
            return radiance + throughput * frame.sky.xyz;
        }
        let next = surface_from_hit(h.instance, h.primitive, vec2f(h.u, h.v), dir);
        if !instance_translucent(h.instance) {
            let hv = -dir;
            radiance += throughput * (next.e.xyz + direct_light(next, hv, 1u, rng, rays) + ambient_term(next, hv));
            return radiance;
        }
        at = next;
        v = -dir;
        radiance += throughput * (at.e.xyz + direct_light(at, v, 1u, rng, rays));
    }
    return radiance;
}

@compute @workgroup_size(8, 8, 1)
fn rt_translucency_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y || frame.params.x == 0u {
        return;
    }
    let sp = surface_at(id.x, id.y, 1u);
    if !gp_valid(sp) || sp.g.w > rtp.values.x {
        return;
    }
    let i = pixel_index(id.x, id.y);
    var rng = rng_new(rtp.counts.zw, i);
    var rays = 0u;
    let c = follow(sp, -view_dir(id.x, id.y), rtp.counts.x, rtp.values.x, &rng, &rays);
    hdr[i] = vec4f(c, 0.0);
    count_rays(rays);
}
