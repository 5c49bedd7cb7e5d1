// The lighting pass: `direct` of every opaque pixel (zero where the sky shows), as the
// CPU's `direct_lighting` with the shadow maps (or unshadowed where the frame has none).

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(3) var<storage, read_write> direct: array<vec4f>;

@compute @workgroup_size(8, 8, 1)
fn direct_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    var c = vec3f(0.0);
    if gp_valid(sp) {
        c = shade_direct(sp, -view_dir(id.x, id.y));
    }
    direct[i] = vec4f(c, 0.0);
}
