//! What each input and output of the exported shaders means, keyed by the names of
//! [`reflect`](super::reflect): which map a texture holds and how it is encoded, what each
//! uniform member sets and in which unit, what the vertex attributes and fragment outputs
//! are, what the compute entry points read and write and who writes their inputs. The
//! README's tables are naga's reflection joined with this table; a test refuses a shader
//! input without a description here, and a description that no shader has.

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
    ("Frame.lit", "0: albedo alone (unlit); 1: ambient + Lambert + Blinn–Phong; 2: lit with soft self-shadows toward the light; 3: lit with horizon self-shadows toward a sun-sized light"),
    ("Frame.shadow_samples", "samples along the light ray of the soft shadows (a count; read when lit = 2), or the most samples along the light's azimuth of the horizon shadows (read when lit = 3)"),
    ("Frame.ray_base", "compute entry points only: xyz the direction, world space, of the camera ray through pixel position (0, 0), the image's top-left corner; the ray through pixel position p (pixels right and down from that corner, centres at +0.5) is eye + s·(ray_base + p.x·ray_dx + p.y·ray_dy), s the view depth in world units (the direction's component along the view axis is 1, so ray_base = forward − right·tan(fov_y/2)·aspect + up·tan(fov_y/2), unit forward, right and up); must describe the camera of view_proj (w unused)"),
    ("Frame.ray_dx", "compute entry points only: xyz the change of the camera ray's direction per pixel to the right, world space: right · 2·tan(fov_y/2)·aspect / width (w unused)"),
    ("Frame.ray_dy", "compute entry points only: xyz the change of the camera ray's direction per pixel down the image (rows count downward): −up · 2·tan(fov_y/2) / height (w unused)"),
    ("Frame.background", "rgb: linear colour where no surface shows (a unused); not read by cs_color or cs_debug: the engine's visibility pass writes it into out_color where the visibility buffer has no surface (renderlab's writes alpha 0 there); the fragment entry points leave the background to the engine's clear"),
    ("Frame.size", "the frame's width and height in pixels: the visibility buffer's row length and row count, and the size of out_color, out_uv and out_layers; compute invocations outside it return at once (fragment entry points ignore it)"),
    ("Frame.depth_range", "near and far clipping distances along the view axis, world units (the planes of view_proj); read by neither pipeline's entry points here: for the engine's visibility pass, which keeps surfaces between them as the rasterizer does"),
    ("map_sampler", "linear min, mag and mip filtering, repeat wrap in u and v; reads albedo_map and normal_map at a level the shader computes, depth_map at level 0"),
    // The relief frame: group 1, one per material.
    ("material", "the material's constants (struct `Material`, members below); one per material"),
    ("Material.height_scale", "depth scale in UV per unit of depth: a ray that descends the whole relief (depth 0 → 1) moves height_scale · V.xy / V.z in UV (the thesis's HeightScale)"),
    ("Material.albedo_levels", "mip level count of albedo_map, as a float (the shader clamps its level of detail to it)"),
    ("Material.normal_levels", "mip level count of normal_map, as a float"),
    ("Material.index", "the material's index in the engine's material list, the number mesh_objects' y holds; a cs_color or cs_debug dispatch shades exactly the pixels whose object has this material and leaves every other pixel untouched (fragment entry points ignore it: the engine draws each material's triangles itself)"),
    ("albedo_map", "albedo in linear RGB (sRGB images are decoded to linear before upload; an engine may use an sRGB texture format instead, which the sampler decodes); Rgba32Float with every mip level; alpha unused"),
    ("normal_map", "tangent-space unit normals as signed values (x along +u, y along +v, z out of the surface; not the 0..1 image encoding); Rgba32Float with every mip level; renormalised after filtering"),
    ("depth_map", "depth = 1 − height in [0, 1] (0 = top of the relief, 1 = its deepest point); R32Float, one level, sampled bilinearly with repeat wrap"),
    ("complexity_map", "the thesis's Sobel complexity map of the height map, in [0, 1]; R32Float, read at the nearest texel (textureLoad) with repeat wrap; adaptive techniques take their layer counts from it"),
    ("cone_map", "relaxed cone ratios, horizontal UV distance per unit of depth, in [0, 1]; R32Float, read at the nearest texel (textureLoad) with repeat wrap, never interpolated; only cone techniques read it (bind a 1×1 texture otherwise)"),
    ("Material.pyramid_levels", "levels of the min-depth pyramid in pyramid_map (at least 1); the leap technique starts its march at the top one"),
    ("pyramid_map", "the min-depth pyramid of the depth map, its levels side by side in one R32Float texture read with textureLoad: level 0 (w × h cells, cell (i, j) the smallest of depth texels (i, j), (i+1, j), (i, j+1), (i+1, j+1), wrapped) at the origin, level k ≥ 1 ((w >> k) × (h >> k), each the smallest of a 2 × 2 block of level k − 1) at (w, h − 2·(h >> k)); the texture is (w + w/2) × h, or w × h with one level; levels stop where a side stops halving exactly; only the leap technique reads it"),
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
    ("DebugOut.uv", "the displaced texture coordinate where the technique's ray met the height field in xy, the pixel-depth offset (distance from the eye to the displaced hit, world units) in z, w 0 (an Rgba32Float target: the same format as the compute pipeline's storage texture, which Vulkan's basic storage set has and Rg32Float is not in)"),
    ("OffsetColor.color", "colour in linear light, as fs_color's (fs_color_pdo: fs_color with the pixel-depth offset)"),
    ("OffsetColor.depth", "the displaced hit's depth-buffer value (frag_depth): later depth tests, such as objects that cut into the relief, see the relief instead of the flat mesh; writing it turns early depth testing off on most hardware"),
    ("OffsetDebug.color", "colour in linear light, as fs_color's"),
    ("OffsetDebug.uv", "as DebugOut.uv"),
    ("OffsetDebug.layers", "as DebugOut.layers"),
    ("OffsetDebug.depth", "as OffsetColor.depth"),
    ("DebugOut.layers", "layers or steps the technique planned for this pixel, 0 where it has none (an R32Uint target)"),
    // The relief frame's compute entry points: group 2.
    ("vis_buffer", "the visibility buffer, written by the engine's own visibility pass before the cs_* dispatches (a rasterized pass writing object and triangle IDs, or ray casting); one vec2<u32> (8 bytes) per pixel, row-major from the top row (index y · Frame.size.x + x): x the object (its index in mesh_objects), or 0xffffffff where no surface shows; y the triangle's index within that object (its vertices mesh_indices[mesh_objects[x].x + 3y + k], k = 0, 1, 2); the front-most front face between the near and far planes at the pixel centre, as a rasterizer would keep it (the entry points intersect the pixel's camera ray with that triangle's plane themselves)"),
    ("mesh_vertices", "every vertex of the scene, 12 f32 (48 bytes) each, tightly packed: position xyz (world units), normal xyz, uv, tangent xyzw, as VertexIn; the fragment pipeline's vertex buffer bound as storage"),
    ("mesh_indices", "three u32 per triangle, absolute indices into mesh_vertices (already offset by the object's first vertex), each object's triangles contiguous, counter-clockwise front faces; the fragment pipeline's index buffer bound as storage"),
    ("mesh_objects", "one vec2<u32> per object, indexed by vis_buffer's x: x the object's first index in mesh_indices, y its material's index (compared with Material.index)"),
    ("out_color", "colour in linear light with alpha 1 (as fs_color's result), Rgba32Float storage texture of Frame.size; texel (x, y) is pixel (x, y), row 0 the top row; written by cs_color and cs_debug at the pixels of their dispatch's material only; the engine's visibility pass writes the background where no surface shows"),
    ("out_uv", "the displaced texture coordinate (as DebugOut.uv) in xy, the pixel-depth offset in z, w 0, Rgba32Float storage texture of Frame.size; written by cs_debug only, at its material's pixels (renderlab's visibility pass writes 0 where no surface shows)"),
    ("out_layers", "layers or steps the technique planned (as DebugOut.layers), R32Uint storage texture of Frame.size; written by cs_debug only, at its material's pixels (renderlab's visibility pass writes 0 where no surface shows)"),
    ("cs_color.id", "global_invocation_id: xy the pixel (right and down from the top-left), one invocation per pixel in 8×8 workgroups; dispatch (⌈width/8⌉, ⌈height/8⌉, 1) workgroups once per material, with that material's group 1 bound"),
    ("cs_debug.id", "global_invocation_id: xy the pixel, as cs_color's; the same dispatch"),
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
