// The surface at a pixel: a drawn triangle (from layer 0 of `ids`: the opaque visibility
// buffer; layer k: translucent layer k) resolved into a `Surface` as
// `HybridScene::shading_point` resolves it. The barycentrics at the pixel centre are those
// of the camera ray's crossing of the triangle's plane (the perspective-correct
// barycentrics the CPU rasterizer computes, in f32), weights of the drawn triangle's second
// and third vertex, applied to the mesh's own vertex order as the CPU's geometry pass
// applies them. (Under a mirroring instance the drawn triangle is re-wound, so these
// weights land on the swapped vertices and the point is not the ray's hit; the CPU's
// geometry pass does the same, and the two must change together.)

@group(1) @binding(13) var ids: texture_2d_array<u32>;

// Bilinear lookup with repeat wrapping, texel centres at half-integers (`Texture::sample`).
fn texel(info: vec4u, x: i32, y: i32) -> vec4f {
    let w = i32(info.y);
    let h = i32(info.z);
    let xx = ((x % w) + w) % w;
    let yy = ((y % h) + h) % h;
    return texels[info.x + u32(yy * w + xx)];
}

fn sample_texture(t: u32, uv: vec2f) -> vec4f {
    let info = texture_info[t];
    let x = uv.x * f32(info.y) - 0.5;
    let y = uv.y * f32(info.z) - 0.5;
    if !(is_finite(x) && is_finite(y)) {
        return texels[info.x];
    }
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    // Far outside [0, 1] the wrap is taken on i32; the CPU's on i64 (textures repeat, so
    // only coordinates beyond 2^31 texels differ).
    let xi = i32(clamp(x0, -2147483520.0, 2147483520.0));
    let yi = i32(clamp(y0, -2147483520.0, 2147483520.0));
    let a = texel(info, xi, yi);
    let b = texel(info, xi + 1, yi);
    let c = texel(info, xi, yi + 1);
    let d = texel(info, xi + 1, yi + 1);
    let ab = a * (1.0 - fx) + b * fx;
    let cd = c * (1.0 - fx) + d * fx;
    return ab * (1.0 - fy) + cd * fy;
}

fn xform_point(inst: Instance, p: vec3f) -> vec3f {
    return inst.c0.xyz * p.x + inst.c1.xyz * p.y + inst.c2.xyz * p.z + inst.c3.xyz;
}

fn xform_vector(inst: Instance, v: vec3f) -> vec3f {
    return inst.c0.xyz * v.x + inst.c1.xyz * v.y + inst.c2.xyz * v.z;
}

fn xform_normal(inst: Instance, v: vec3f) -> vec3f {
    return inst.n0.xyz * v.x + inst.n1.xyz * v.y + inst.n2.xyz * v.z;
}

// Barycentrics (second, third vertex) where the ray from `o` along `d` meets the plane of
// the triangle (a, b, c).
fn ray_barycentrics(o: vec3f, d: vec3f, a: vec3f, b: vec3f, c: vec3f) -> vec2f {
    let e1 = b - a;
    let e2 = c - a;
    let p = cross(d, e2);
    let det = dot(e1, p);
    let inv = 1.0 / det;
    let s = o - a;
    let u = dot(s, p) * inv;
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    return vec2f(u, v);
}

fn resolve(drawn: u32, dir: vec3f) -> Surface {
    let r = triangle_refs[drawn];
    // Barycentrics against the drawn (world) triangle.
    let wa = world_positions[draw_indices[3u * drawn]].xyz;
    let wb = world_positions[draw_indices[3u * drawn + 1u]].xyz;
    let wc = world_positions[draw_indices[3u * drawn + 2u]].xyz;
    let bary = ray_barycentrics(frame.eye.xyz, dir, wa, wb, wc);
    return shading_point(r.x, r.y, bary, dir, drawn + 1u);
}

// What `ids.y` holds for a surface found by a ray rather than drawn: not 0 (a surface is
// there), and no drawn triangle.
const HIT_NOT_DRAWN: u32 = 0xffffffffu;

// `HybridScene::shading_point` of a ray's hit (`Accel::surface`): mesh triangle `tri` of scene
// instance `instance`, `bary` the weights of its second and third vertex in the mesh's own
// order (the ray tracer's `u`, `v`), seen along `dir`.
fn surface_from_hit(instance: u32, tri: u32, bary: vec2f, dir: vec3f) -> Surface {
    return shading_point(instance, tri, bary, dir, HIT_NOT_DRAWN);
}

// The shading point of mesh triangle `tri` of instance `instance` at barycentrics `bary` seen
// along `dir`; `drawn` goes to `ids.y` (the drawn triangle + 1, or HIT_NOT_DRAWN).
fn shading_point(instance: u32, tri: u32, bary: vec2f, dir: vec3f, drawn: u32) -> Surface {
    let inst = instances[instance];
    let ib = inst.refs.y + 3u * tri;
    let va = vertices[inst.refs.x + indices[ib]];
    let vb = vertices[inst.refs.x + indices[ib + 1u]];
    let vc = vertices[inst.refs.x + indices[ib + 2u]];
    let w0 = 1.0 - bary.x - bary.y;
    let p_obj = va.position_u.xyz * w0 + vb.position_u.xyz * bary.x + vc.position_u.xyz * bary.y;
    let n_obj = va.normal_v.xyz * w0 + vb.normal_v.xyz * bary.x + vc.normal_v.xyz * bary.y;
    let t_obj = va.tangent.xyz * w0 + vb.tangent.xyz * bary.x + vc.tangent.xyz * bary.y;
    let uv = vec2f(va.position_u.w, va.normal_v.w) * w0 + vec2f(vb.position_u.w, vb.normal_v.w) * bary.x
        + vec2f(vc.position_u.w, vc.normal_v.w) * bary.y;
    let position = xform_point(inst, p_obj);
    var geometric = normalize_or_zero(xform_normal(inst, cross(vb.position_u.xyz - va.position_u.xyz,
        vc.position_u.xyz - va.position_u.xyz)));
    var normal = normalize_or_zero(xform_normal(inst, n_obj));
    if all(normal == vec3f(0.0)) {
        normal = geometric;
    }
    let m = materials[inst.refs.z];
    var base = m.base_rough.xyz;
    var roughness = m.base_rough.w;
    var metallic = m.emissive_metal.w;
    var emissive = m.emissive_metal.xyz;
    if m.textures.x != NONE {
        base = base * sample_texture(m.textures.x, uv).xyz;
    }
    if m.textures.y != NONE {
        let mr = sample_texture(m.textures.y, uv);
        roughness = clamp(roughness * mr.y, 0.0, 1.0);
        metallic = clamp(metallic * mr.z, 0.0, 1.0);
    }
    if m.textures.z != NONE {
        var tangent = xform_vector(inst, t_obj);
        tangent = normalize_or_zero(tangent - normal * dot(normal, tangent));
        if any(tangent != vec3f(0.0)) {
            let sign = select(1.0, -1.0, (bitcast<u32>(va.tangent.w) >> 31u) == 1u);
            let bitangent = cross(normal, tangent) * sign;
            let t = sample_texture(m.textures.z, uv).xyz * 2.0 - vec3f(1.0);
            let mapped = normalize_or_zero(tangent * t.x + bitangent * t.y + normal * t.z);
            if any(mapped != vec3f(0.0)) {
                normal = mapped;
            }
        }
    }
    let front = dot(geometric, dir) < 0.0;
    if !front {
        geometric = -geometric;
        normal = -normal;
        if m.transmission_ior.z == 0.0 {
            emissive = vec3f(0.0);
        }
    }
    if dot(normal, dir) > 0.0 {
        normal = geometric;
    }
    var out: Surface;
    out.p = vec4f(position, uv.x);
    out.n = vec4f(normal, uv.y);
    out.g = vec4f(geometric, roughness);
    out.c = vec4f(base, metallic);
    out.e = vec4f(emissive, m.transmission_ior.x);
    out.ids = vec4u(inst.refs.z, drawn, select(0u, 1u, front), bitcast<u32>(m.transmission_ior.y));
    return out;
}

// The surface of layer `layer` of the visibility ids at pixel (x, y); invalid (`ids.y` 0)
// where nothing was drawn.
fn surface_at(x: u32, y: u32, layer: u32) -> Surface {
    let t = textureLoad(ids, vec2i(i32(x), i32(y)), i32(layer), 0).x;
    var s: Surface;
    if t != 0u {
        s = resolve(t - 1u, view_dir(x, y));
    }
    return s;
}
