// The maps as the techniques read them: the GPU twins of `HeightField::depth`,
// `ReliefInputs::complexity_at`, `ConeMap::ratio` and `PackedRelief::sample_texel`, each
// reading the numbers the CPU reads (see the crate's `material` module for the formats).

// The depth map (`1 − height`), bilinear with repeat wrap, as `HeightField::depth`.
fn depth_at(uv: vec2<f32>) -> f32 {
    return textureSampleLevel(depth_map, map_sampler, uv, 0.0).r;
}

// The complexity map at `uv`, nearest texel with repeat wrap, as
// `ReliefInputs::complexity_at` (floor, then wrap; non-finite coordinates give 0).
fn complexity_at(uv: vec2<f32>) -> f32 {
    let size = vec2<i32>(textureDimensions(complexity_map));
    let p = floor(uv * vec2<f32>(size));
    // Beyond ±2^30 (or NaN) the CPU's answer is its wrap of a huge index; such UVs never
    // occur on the scene's surfaces, so they read 0 as non-finite ones do.
    if !(all(abs(p) < vec2<f32>(1073741824.0))) {
        return 0.0;
    }
    let q = ((vec2<i32>(p) % size) + size) % size;
    return textureLoad(complexity_map, q, 0).r;
}

// The relaxed cone ratio for a ray above `uv`: the nearest texel of the cone map with repeat
// wrap, as `ConeMap::ratio` (`floor(uv · size) mod size`; the ratio holds for the texel's
// whole cell, so it is never interpolated).
fn cone_ratio(uv: vec2<f32>) -> f32 {
    let size = vec2<i32>(textureDimensions(cone_map));
    let p = floor(uv * vec2<f32>(size));
    // As in `complexity_at`: coordinates beyond ±2^30 never occur on the scene's surfaces.
    if !(all(abs(p) < vec2<f32>(1073741824.0))) {
        return 0.0;
    }
    let q = ((vec2<i32>(p) % size) + size) % size;
    return textureLoad(cone_map, q, 0).r;
}

// One fetch from the packed map (`Sample`): bilinear depth, the patch's depth gradient per
// texel, and the cone ratio of the bilinear cell.
struct Packed {
    depth: f32,
    ratio: f32,
    ddx: f32,
    ddy: f32,
}

// The packed map at texel coordinates `(x, y)` (`uv · size − ½`), with the operations of
// `PackedRelief::sample_texel`: the four texels of the cell from the padded grid (no wrap of
// the second index), the 16-bit depths interpolated as whole numbers and scaled after, the
// ratio of the cell's top-left texel.
fn packed_at(x: f32, y: f32) -> Packed {
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    // The unpadded size: the texture holds one wrapped column and row more.
    let n = vec2<i32>(textureDimensions(packed_map)) - vec2<i32>(1);
    let xw = ((i32(x0) % n.x) + n.x) % n.x;
    let yw = ((i32(y0) % n.y) + n.y) % n.y;
    let t00 = textureLoad(packed_map, vec2<i32>(xw, yw), 0).r;
    let t10 = textureLoad(packed_map, vec2<i32>(xw + 1, yw), 0).r;
    let t01 = textureLoad(packed_map, vec2<i32>(xw, yw + 1), 0).r;
    let t11 = textureLoad(packed_map, vec2<i32>(xw + 1, yw + 1), 0).r;
    let d00 = f32(t00 >> 16u);
    let d10 = f32(t10 >> 16u);
    let d01 = f32(t01 >> 16u);
    let d11 = f32(t11 >> 16u);
    let dx0 = d10 - d00;
    let dx1 = d11 - d01;
    let top = d00 + dx0 * fx;
    let bottom = d01 + dx1 * fx;
    let dy = bottom - top;
    return Packed(
        (top + dy * fy) * PACKED_DEPTH_STEP,
        f32(t00 & 0xffffu) * PACKED_RATIO_STEP,
        (dx0 + (dx1 - dx0) * fy) * PACKED_DEPTH_STEP,
        dy * PACKED_DEPTH_STEP,
    );
}
