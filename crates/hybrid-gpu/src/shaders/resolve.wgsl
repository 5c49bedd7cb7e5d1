// The G-buffer resolve: every pixel's opaque surface packed into the G-buffer; and, for
// read-back, one translucent layer (`frame.ssr_steps.w`) into `layer_points` (the frame
// itself resolves the translucent layers where it blends them).

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(2) var<storage, read_write> layer_points: array<GPoint>;

@compute @workgroup_size(8, 8, 1)
fn resolve_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    gbuf[pixel_index(id.x, id.y)] = pack_surface(surface_at(id.x, id.y, 0u));
}

@compute @workgroup_size(8, 8, 1)
fn resolve_layer_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    layer_points[pixel_index(id.x, id.y)] = pack_surface(surface_at(id.x, id.y, frame.ssr_steps.w));
}
