// A frame's opaque surfaces as a stage tested on its own reads them: one record of six vec4s
// per pixel, row-major, uploaded from the CPU's G-buffer (rt/surfaces.rs).

struct RtSurface {
    // xyz: world position; w: flags (bit 0: a surface is there; bit 1: its front face).
    position: vec4<f32>,
    // xyz: unit shading normal, facing the viewer; w: material index (bits).
    normal: vec4<f32>,
    // xyz: unit geometric normal, facing the viewer; w: roughness.
    geometric: vec4<f32>,
    // xyz: base colour; w: metallic.
    base: vec4<f32>,
    // xyz: emitted radiance; w: transmission.
    emissive: vec4<f32>,
    // xy: texture coordinates; z: index of refraction; w: unused.
    extra: vec4<f32>,
}

const SURFACE_PRESENT: u32 = 1u;
const SURFACE_FRONT: u32 = 2u;

fn surface_present(s: RtSurface) -> bool {
    return (bitcast<u32>(s.position.w) & SURFACE_PRESENT) != 0u;
}

// ShadingPoint::offset_origin: the point a secondary ray toward `dir` leaves from, pushed off
// along the geometric normal on dir's side by 1e-4 · (1 + the position's largest magnitude).
fn offset_origin(s: RtSurface, dir: vec3<f32>) -> vec3<f32> {
    let p = s.position.xyz;
    let scale = 1e-4 * (1.0 + max(abs(p.x), max(abs(p.y), abs(p.z))));
    let n = select(-s.geometric.xyz, s.geometric.xyz, dot(dir, s.geometric.xyz) >= 0.0);
    return p + n * scale;
}
