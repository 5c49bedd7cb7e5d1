// The fragment pipeline of the relief frame: the hardware rasterizes the mesh, and each
// fragment's surface comes from its perspective-correct interpolants (the twin of the CPU
// rasterizer's surface reconstruction, `renderlab_raster`). What engines use.

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
}

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    // Perspective-correct, like every attribute here (see `surface` for its derivatives).
    @location(0) uv: vec2<f32>,
    @location(1) world: vec3<f32>,
    @location(2) normal: vec3<f32>,
    @location(3) tangent: vec4<f32>,
    // The scene object: the draw's instance index.
    @location(4) @interpolate(flat) object: u32,
}

@vertex
fn vs_main(v: VertexIn, @builtin(instance_index) object: u32) -> Varyings {
    var out: Varyings;
    out.object = object;
    out.clip = frame.view_proj * vec4<f32>(v.position, 1.0);
    out.uv = v.uv;
    out.world = v.position;
    out.normal = v.normal;
    out.tangent = v.tangent;
    return out;
}

// The pixel's surface. The fragment position's w is q = 1/w, and h = uv·q is affine in screen
// space, so ∂uv/∂x = (∂h/∂x − uv·∂q/∂x)/q exactly, as the CPU rasterizer computes it: the
// fine derivatives of an affine quantity are its slopes, where finite differences of uv
// itself would be off by its curvature. (Interpolating uv/w and 1/w without perspective
// would be wrong where the near plane clips a triangle: the clipper interpolates such
// attributes linearly in clip space.) Must run in uniform control flow.
fn surface(in: Varyings) -> Surface {
    let q = in.clip.w;
    let h = in.uv * q;
    let duv_dx = (dpdxFine(h) - in.uv * dpdxFine(q)) / q;
    let duv_dy = (dpdyFine(h) - in.uv * dpdyFine(q)) / q;
    // The world position's Jacobian the same way (world·q is affine in screen space too).
    let g = in.world * q;
    let dp_dx = (dpdxFine(g) - in.world * dpdxFine(q)) / q;
    let dp_dy = (dpdyFine(g) - in.world * dpdyFine(q)) / q;
    let scale = world_per_uv(dp_dx, dp_dy, duv_dx, duv_dy);
    // The normal's Jacobian the same way, then both per unit of u and v; only for a technique
    // that reads the curvature (`RAY_CONTEXT` is a constant: the branch is uniform and folds).
    var curvature = vec2<f32>(0.0);
    if RAY_CONTEXT {
        let m = in.normal * q;
        let dn_dx = (dpdxFine(m) - in.normal * dpdxFine(q)) / q;
        let dn_dy = (dpdyFine(m) - in.normal * dpdyFine(q)) / q;
        let dp = per_uv(dp_dx, dp_dy, duv_dx, duv_dy);
        let dn = per_uv(dn_dx, dn_dy, duv_dx, duv_dy);
        curvature = curvature_of(dp[0], dp[1], dn[0], dn[1], in.normal);
    }
    return surface_from(in.uv, duv_dx, duv_dy, in.world, in.normal, in.tangent, scale, curvature, in.object);
}

// The depth-buffer value of the point `distance` from the eye on the ray through `world`.
fn offset_clip_depth(world: vec3<f32>, distance: f32) -> f32 {
    let p = frame.eye.xyz + normalize(world - frame.eye.xyz) * distance;
    let clip = frame.view_proj * vec4<f32>(p, 1.0);
    return clip.z / clip.w;
}

// The image alone (timed runs). Alpha marks covered pixels (the clear leaves 0); a trace that
// missed the relief discards, so what lies behind shows.
@fragment
fn fs_color(in: Varyings) -> @location(0) vec4<f32> {
    let s = shade(surface(in));
    if !s.covered {
        discard;
    }
    return vec4<f32>(s.color, 1.0);
}

// The image with the debug targets: displaced UV with the pixel-depth offset (the displaced
// hit's distance from the eye, in z) and planned layer count.
struct DebugOut {
    @location(0) color: vec4<f32>,
    @location(1) uv: vec4<f32>,
    @location(2) layers: u32,
}

@fragment
fn fs_debug(in: Varyings) -> DebugOut {
    let s = shade(surface(in));
    if !s.covered {
        discard;
    }
    return DebugOut(vec4<f32>(s.color, 1.0), vec4<f32>(s.uv, s.view_depth, 0.0), s.layers);
}

// `fs_color` with the pixel-depth offset: the depth buffer gets the displaced hit's depth, so
// that the depth test (objects that intersect the relief, later depth-reading passes) sees the
// relief. Writing the depth turns early depth testing off on most hardware: what it costs is
// measured, not assumed.
struct OffsetColor {
    @location(0) color: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

@fragment
fn fs_color_pdo(in: Varyings) -> OffsetColor {
    let s = shade(surface(in));
    if !s.covered {
        discard;
    }
    return OffsetColor(vec4<f32>(s.color, 1.0), offset_clip_depth(in.world, s.view_depth));
}

// `fs_debug` with the pixel-depth offset.
struct OffsetDebug {
    @location(0) color: vec4<f32>,
    @location(1) uv: vec4<f32>,
    @location(2) layers: u32,
    @builtin(frag_depth) depth: f32,
}

@fragment
fn fs_debug_pdo(in: Varyings) -> OffsetDebug {
    let s = shade(surface(in));
    if !s.covered {
        discard;
    }
    let depth = offset_clip_depth(in.world, s.view_depth);
    return OffsetDebug(vec4<f32>(s.color, 1.0), vec4<f32>(s.uv, s.view_depth, 0.0), s.layers, depth);
}
