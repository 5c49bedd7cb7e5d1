// Composition and the sorted forward translucent pass: the opaque image
// (`LightingTerms::compose`: emitted + direct + ambient · AO + specular, the sky where no
// surface is), then each pixel's translucent layers blended over it back to front
// (`forward_translucent`): `c ← layer + base_colour · transmitted · c`, each layer lit by
// the same direct light and shadows, the ambient term and a Fresnel reflection of the sky.
// The layers are resolved here from their visibility ids (`surface.wgsl`), not stored.
// `layer_direct` (a layer's direct light) is defined before this file: with the shadow maps
// (`shade_direct`) or, with ray-traced shadows, with a shadow ray per light sample.

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(3) var<storage, read_write> direct: array<vec4f>;
@group(1) @binding(4) var<storage, read_write> ambient: array<vec4f>;
@group(1) @binding(5) var<storage, read_write> specular: array<vec4f>;
@group(1) @binding(7) var<storage, read_write> hdr: array<vec4f>;

@compute @workgroup_size(8, 8, 1)
fn compose_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    var c = frame.sky.xyz;
    if gp_valid(sp) {
        c = sp.e.xyz + direct[i].xyz + ambient[i].xyz * ambient[i].w + specular[i].xyz;
    }
    let layers = frame.params.x;
    if layers > 0u && textureLoad(ids, vec2i(id.xy), 1, 0).x != 0u {
        let v = -view_dir(id.x, id.y);
        for (var k = layers; k > 0u; k--) {
            let lp = surface_at(id.x, id.y, k);
            if !gp_valid(lp) {
                continue;
            }
            let f = fresnel_schlick(max(dot(lp.n.xyz, v), 0.0), f0_of(lp));
            let transmitted = lp.e.w * (1.0 - (f.x + f.y + f.z) / 3.0);
            let radiance = lp.e.xyz + layer_direct(lp, v) + frame.sky.xyz * diffuse_albedo(lp, v) + f * frame.sky.xyz;
            c = radiance + lp.c.xyz * transmitted * c;
        }
    }
    hdr[i] = vec4f(c, 0.0);
}
