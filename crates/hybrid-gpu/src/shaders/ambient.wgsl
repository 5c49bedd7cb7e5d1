// The ambient pass: the view-axis depth buffer of the opaque layer (`view_depth`), the
// ambient diffuse term (`ambient_diffuse`: sky × diffuse albedo) and SSAO (`ssao`: a
// golden-angle spiral kernel in the normal's hemisphere, turned per pixel by an angle
// hashed from the pixel index, each sample occluded when the depth buffer at its
// projection is nearer by more than the bias and less than the radius).

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(4) var<storage, read_write> ambient: array<vec4f>;
@group(1) @binding(12) var<storage, read_write> depth: array<f32>;

@compute @workgroup_size(8, 8, 1)
fn depth_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    var d = F32_MAX;
    if gp_valid(sp) {
        d = dot(sp.p.xyz - frame.eye.xyz, frame.forward.xyz);
    }
    depth[i] = d;
}

// Wang's 32-bit integer hash (`ao::hash`).
fn wang_hash(x0: u32) -> u32 {
    var x = (x0 ^ 61u) ^ (x0 >> 16u);
    x = x * 9u;
    x = x ^ (x >> 4u);
    x = x * 0x27d4eb2du;
    return x ^ (x >> 15u);
}

// Sample k of the SSAO kernel (`ao::kernel`).
fn kernel_sample(k: u32, samples: u32) -> vec3f {
    let golden = PI * (3.0 - sqrt(5.0));
    let t = (f32(k) + 0.5) / f32(samples);
    let sin_t = sqrt(t * (1.0 - 0.15 * 0.15));
    let cos_t = sqrt(1.0 - sin_t * sin_t);
    let phi = golden * f32(k);
    let dir = vec3f(sin_t * cos(phi), sin_t * sin(phi), cos_t);
    let f = f32(k) / f32(samples);
    return dir * (0.1 + 0.9 * f * f);
}

fn ssao(i: u32, sp: Surface) -> f32 {
    let samples = frame.params.w;
    if samples == 0u {
        return 1.0;
    }
    let n = sp.n.xyz;
    // glam's `any_orthonormal_pair`.
    let sign = select(1.0, -1.0, (bitcast<u32>(n.z) >> 31u) == 1u);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let tx = vec3f(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bx = vec3f(b, sign + n.y * n.y * a, -n.y);
    let angle = f32(wang_hash(i)) * (2.0 * PI / 4294967296.0);
    let rot = vec2f(cos(angle), sin(angle));
    let w = f32(frame.size.x);
    let h = f32(frame.size.y);
    let radius = frame.shadow.z;
    var occluded = 0u;
    for (var k = 0u; k < samples; k++) {
        let s = kernel_sample(k, samples);
        let local = vec3f(rot.x * s.x - rot.y * s.y, rot.y * s.x + rot.x * s.y, s.z);
        let q = sp.p.xyz + (tx * local.x + bx * local.y + n * local.z) * radius;
        let c = frame.view_proj * vec4f(q, 1.0);
        if c.w <= 0.0 {
            continue;
        }
        let sx = (c.x / c.w + 1.0) * 0.5 * w;
        let sy = (1.0 - c.y / c.w) * 0.5 * h;
        if !(sx >= 0.0 && sy >= 0.0 && sx < w && sy < h) {
            continue;
        }
        let d = depth[u32(sy) * frame.size.x + u32(sx)];
        let gap = dot(q - frame.eye.xyz, frame.forward.xyz) - d;
        if gap > frame.shadow.w && gap < radius {
            occluded += 1u;
        }
    }
    return 1.0 - f32(occluded) / f32(samples);
}

@compute @workgroup_size(8, 8, 1)
fn ambient_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    var out = vec4f(0.0, 0.0, 0.0, 1.0);
    if gp_valid(sp) {
        out = vec4f(frame.sky.xyz * diffuse_albedo(sp, -view_dir(id.x, id.y)), 1.0);
    }
    ambient[i] = out;
}

// SSAO into the ambient term's w (after `ambient_main` or a ray-traced GI pass, which leave
// it 1: AO off).
@compute @workgroup_size(8, 8, 1)
fn ssao_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    if gp_valid(sp) {
        ambient[i].w = ssao(i, sp);
    }
}
