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
}

@vertex
fn vs_main(v: VertexIn) -> Varyings {
    var out: Varyings;
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
    return surface_from(in.uv, duv_dx, duv_dy, in.world, in.normal, in.tangent);
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

// The image with the debug targets: displaced UV and planned layer count.
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
    return DebugOut(vec4<f32>(s.color, 1.0), vec4<f32>(s.uv, 0.0, 0.0), s.layers);
}
