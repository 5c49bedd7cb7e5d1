//! What each input and output of the exported shaders means, keyed by the names of
//! [`reflect`](super::reflect): which map a texture holds and how it is encoded, what each
//! uniform member sets and in which unit, what the vertex attributes and fragment outputs
//! are. The README's tables are naga's reflection joined with this table; a test refuses a
//! shader input without a description here, and a description that no shader has.

/// `(key, description)` for every input and output of the exported shaders.
pub const DESCRIPTIONS: &[(&str, &str)] = &[
    // The relief frame: group 0.
    ("frame", "the frame's constants (struct `Frame`, members below); one per frame"),
    ("Frame.view_proj", "world → clip matrix, column-major; clip space as WebGPU's (y up, z in [0, 1]); the mesh has no model matrix (positions are world positions)"),
    ("Frame.eye", "xyz: the camera's position, world units (w unused)"),
    ("Frame.to_light", "xyz: unit vector toward the directional light, world space (w unused)"),
    ("Frame.params", "the technique's parameters in its registry order (listed in the shader's section); counts are whole numbers, choices are indices; unused components 0"),
    ("Frame.ambient", "ambient factor: the fraction of the albedo seen without light (dimensionless, 0..1)"),
    ("Frame.specular_exponent", "Blinn–Phong exponent (dimensionless; whole numbers up to 256 are raised by repeated squaring, as on the CPU)"),
    ("Frame.specular_strength", "Blinn–Phong specular strength (dimensionless, added to the linear colour)"),
    ("Frame.lit", "0: albedo alone (unlit); 1: ambient + Lambert + Blinn–Phong; 2: lit with soft self-shadows toward the light"),
    ("Frame.shadow_samples", "samples along the light ray of the soft shadows (a count; read when lit = 2)"),
    ("map_sampler", "linear min, mag and mip filtering, repeat wrap in u and v; reads albedo_map and normal_map at a level the shader computes, depth_map at level 0"),
    // The relief frame: group 1, one per material.
    ("material", "the material's constants (struct `Material`, members below); one per material"),
    ("Material.height_scale", "depth scale in UV per unit of depth: a ray that descends the whole relief (depth 0 → 1) moves height_scale · V.xy / V.z in UV (the thesis's HeightScale)"),
    ("Material.albedo_levels", "mip level count of albedo_map, as a float (the shader clamps its level of detail to it)"),
    ("Material.normal_levels", "mip level count of normal_map, as a float"),
    ("albedo_map", "albedo in linear RGB (sRGB images are decoded to linear before upload; an engine may use an sRGB texture format instead, which the sampler decodes); Rgba32Float with every mip level; alpha unused"),
    ("normal_map", "tangent-space unit normals as signed values (x along +u, y along +v, z out of the surface; not the 0..1 image encoding); Rgba32Float with every mip level; renormalised after filtering"),
    ("depth_map", "depth = 1 − height in [0, 1] (0 = top of the relief, 1 = its deepest point); R32Float, one level, sampled bilinearly with repeat wrap"),
    ("complexity_map", "the thesis's Sobel complexity map of the height map, in [0, 1]; R32Float, read at the nearest texel (textureLoad) with repeat wrap; adaptive techniques take their layer counts from it"),
    ("cone_map", "relaxed cone ratios, horizontal UV distance per unit of depth, in [0, 1]; R32Float, read at the nearest texel (textureLoad) with repeat wrap, never interpolated; only cone techniques read it (bind a 1×1 texture otherwise)"),
    ("packed_map", "depth and cone ratio packed per texel: high 16 bits depth in steps of PACKED_DEPTH_STEP (1/65535), low 16 bits ratio in steps of PACKED_RATIO_STEP; R32Uint on a padded (w + 1) × (h + 1) grid whose last column and row repeat the first; read texel by texel and interpolated by the shader"),
    // The relief frame's vertex stage.
    ("VertexIn.position", "vertex position, world units"),
    ("VertexIn.normal", "surface normal, world space (need not be unit length)"),
    ("VertexIn.uv", "texture coordinate; 1 = one tile of the maps, which repeat"),
    ("VertexIn.tangent", "xyz: direction of increasing u, world space; w: handedness ±1 (bitangent = w · N × T)"),
    ("Varyings.clip", "clip-space position; in the fragment stage the window position, whose w is 1/w_clip (used for the exact UV derivatives)"),
    ("Varyings.uv", "texture coordinate, perspective-correct"),
    ("Varyings.world", "world position, for the view vector"),
    ("Varyings.normal", "world normal, interpolated"),
    ("Varyings.tangent", "world tangent and handedness, interpolated"),
    // The relief frame's fragment outputs.
    ("fs_color.result", "colour in linear light (not tone-mapped, not sRGB-encoded; write it to a float target such as Rgba16Float); alpha 1 marks drawn pixels"),
    ("DebugOut.color", "colour in linear light, as fs_color's"),
    ("DebugOut.uv", "the displaced texture coordinate where the technique's ray met the height field (an Rg32Float target)"),
    ("DebugOut.layers", "layers or steps the technique planned for this pixel, 0 where it has none (an R32Uint target)"),
    // The texture filters' frame.
    ("filter_params", "the filter frame's constants (struct `Filter`, members below)"),
    ("Filter.background", "rgb: linear colour where no surface shows (a unused)"),
    ("Filter.mode", "0: the sampler at level 0 (nearest, bilinear); 1: textureSampleGrad with the pixel's UV Jacobian (trilinear); 2: EWA in the shader; 3: the sampler with the 2×2 quad's implicit derivatives (anisotropic)"),
    ("Filter.wrap", "0: repeat; 1: clamp to edge (EWA's own addressing; the sampler must agree)"),
    ("Filter.ewa_sigma", "EWA's Gaussian pixel filter: standard deviation in pixels"),
    ("Filter.ewa_cut", "EWA's truncation radius, in multiples of σ (1..4)"),
    ("Filter.ewa_ecc", "EWA's largest major/minor axis ratio (1..64); more eccentric footprints get a wider minor axis"),
    ("Filter.ewa_texels", "EWA's texel budget per lookup (a count, 16..4096); a larger footprint moves up the mip pyramid"),
    ("filter_tex", "the texture to filter in linear RGB, Rgba32Float with every mip level"),
    ("filter_sampler", "the filter's sampler: nearest or linear as the mode needs, anisotropy up to 16 for mode 3, the wrap of Filter.wrap; EWA uses it only for its fallback"),
    ("surface_uv", "per pixel: (u, v) reduced to one period, and (U, V) not reduced; Rgba32Float, read at the pixel (textureLoad)"),
    ("surface_jacobian", "per pixel: (∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y), UV per pixel; Rgba32Float"),
    ("surface_hit", "per pixel: r = 1 where the surface shows, else 0; R32Float"),
    ("vs_main.i", "vertex index 0, 1, 2 of one full-screen triangle (draw 3 vertices without a vertex buffer)"),
    ("vs_main.result", "clip-space position of the full-screen triangle"),
    ("fs_main.position", "window position (pixel centres at +0.5), which addresses the per-pixel surface textures"),
    ("fs_main.result", "filtered colour in linear light; alpha 1 where the surface shows, 0 on the background"),
];

/// The description of `key`, if the table has one.
pub fn describe(key: &str) -> Option<&'static str> {
    DESCRIPTIONS.iter().find(|(k, _)| *k == key).map(|(_, d)| *d)
}
