//! The shared AVX2 fetches of the packed map for eight lanes: the whole bilinear cell (depth
//! and cone ratio) in four 64-bit gathers, or the depth alone from the 16-bit depth plane in
//! two 32-bit gathers.

/// The bilinear cell of texel coordinates `(x, y)` for eight lanes: the fractions within it and
/// the padded-grid index of its first texel (`⌊y⌋ & mask_y` rows of `stride` plus
/// `⌊x⌋ & mask_x`), as the scalar `PackedRelief` locates it. Shared by [`gather_cell`] and
/// [`plane_depth`]; a macro for the reason they are.
macro_rules! cell_index {
    ($x:expr, $y:expr, $mask_x:expr, $mask_y:expr, $stride_v:expr) => {{
        let x0 = _mm256_floor_ps($x);
        let y0 = _mm256_floor_ps($y);
        let (fx, fy) = (_mm256_sub_ps($x, x0), _mm256_sub_ps($y, y0));
        let xi = _mm256_and_si256(_mm256_cvttps_epi32(x0), $mask_x);
        let yi = _mm256_and_si256(_mm256_cvttps_epi32(y0), $mask_y);
        (fx, fy, _mm256_add_epi32(_mm256_mullo_epi32(yi, $stride_v), xi))
    }};
}
pub(crate) use cell_index;

/// The four packed texels around texel coordinates `(x, y)` for eight lanes at once (AVX2), as
/// the scalar `PackedRelief` fetch reads them: returns `(fx, fy, t00, t10, t01, t11)`, the
/// fractions and the texels `(x, y)`, `(x + 1, y)`, `(x, y + 1)`, `(x + 1, y + 1)`. `mask_x` and
/// `mask_y` wrap the indices (power-of-two sides), so every gather stays inside the padded map;
/// `lane_order` must be `_mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7)`. A macro rather than a
/// function so that it expands inside each `#[target_feature]` kernel (AVX2 and AVX-512 builds)
/// and is compiled, and inlined, with that kernel's features. Must be expanded in an `unsafe`
/// context with `std::arch::x86_64::*` in scope.
macro_rules! gather_cell {
    ($base:expr, $stride:expr, $x:expr, $y:expr, $mask_x:expr, $mask_y:expr, $stride_v:expr, $lane_order:expr) => {{
        let (fx, fy, idx) = $crate::simd::avx2::gather::cell_index!($x, $y, $mask_x, $mask_y, $stride_v);
        // Texels (x, y) and (x + 1, y) are adjacent: one 64-bit gather element fetches both.
        // Lanes (0, 1, 4, 5) go to the first gather and (2, 3, 6, 7) to the second, so that the
        // shuffles below put them back in order.
        let perm = _mm256_permutevar8x32_epi32(idx, $lane_order);
        let (ia, ib) = (_mm256_castsi256_si128(perm), _mm256_extracti128_si256::<1>(perm));
        let row0 = $base as *const i64;
        let row1 = $base.add($stride as usize) as *const i64;
        let r0a = _mm256_castsi256_ps(_mm256_i32gather_epi64::<4>(row0, ia));
        let r0b = _mm256_castsi256_ps(_mm256_i32gather_epi64::<4>(row0, ib));
        let r1a = _mm256_castsi256_ps(_mm256_i32gather_epi64::<4>(row1, ia));
        let r1b = _mm256_castsi256_ps(_mm256_i32gather_epi64::<4>(row1, ib));
        let t00 = _mm256_castps_si256(_mm256_shuffle_ps::<0b10_00_10_00>(r0a, r0b));
        let t10 = _mm256_castps_si256(_mm256_shuffle_ps::<0b11_01_11_01>(r0a, r0b));
        let t01 = _mm256_castps_si256(_mm256_shuffle_ps::<0b10_00_10_00>(r1a, r1b));
        let t11 = _mm256_castps_si256(_mm256_shuffle_ps::<0b11_01_11_01>(r1a, r1b));
        (fx, fy, t00, t10, t01, t11)
    }};
}
pub(crate) use gather_cell;

/// The packed map's bilinear sample at texel coordinates `(x, y)` for eight lanes, computed as
/// `PackedRelief::sample_texel` computes it (bit-identical): returns `(depth, ratio, dx0, dx1,
/// dy, fy)`, the depth and the cone ratio, and the 16-bit depth differences along x on the
/// cell's two rows, down its x-interpolated column, and the y fraction (what the gradient is
/// made of). The arguments are [`gather_cell`]'s. A macro for the reason that one is.
macro_rules! packed_sample {
    ($base:expr, $stride:expr, $x:expr, $y:expr, $mask_x:expr, $mask_y:expr, $stride_v:expr, $lane_order:expr) => {{
        let (fx, fy, t00, t10, t01, t11) = $crate::simd::avx2::gather::gather_cell!(
            $base,
            $stride,
            $x,
            $y,
            $mask_x,
            $mask_y,
            $stride_v,
            $lane_order
        );
        let hi16 = |t: __m256i| _mm256_cvtepi32_ps(_mm256_srli_epi32::<16>(t));
        let (d00, d10, d01, d11) = (hi16(t00), hi16(t10), hi16(t01), hi16(t11));
        let dx0 = _mm256_sub_ps(d10, d00);
        let dx1 = _mm256_sub_ps(d11, d01);
        let top = _mm256_add_ps(d00, _mm256_mul_ps(dx0, fx));
        let bottom = _mm256_add_ps(d01, _mm256_mul_ps(dx1, fx));
        let dy = _mm256_sub_ps(bottom, top);
        let depth_step = _mm256_set1_ps(crate::maps::packed::DEPTH_STEP);
        let depth = _mm256_mul_ps(_mm256_add_ps(top, _mm256_mul_ps(dy, fy)), depth_step);
        let code = _mm256_and_si256(t00, _mm256_set1_epi32(0xffff));
        let ratio = _mm256_mul_ps(_mm256_cvtepi32_ps(code), _mm256_set1_ps(crate::maps::packed::RATIO_STEP));
        (depth, ratio, dx0, dx1, dy, fy)
    }};
}
pub(crate) use packed_sample;

/// The two 32-bit words of eight lanes' cells in the 16-bit depth plane: at plane index `idx`
/// (a texel and its right neighbour) and one padded row further on. `loads`: sixteen scalar
/// loads put into two vectors; `gathers`: two eight-lane hardware gathers, the same words. On an
/// AMD Zen 3 core the loads are the faster (its gathers are microcoded): the relief bench's
/// whole frame, both forms built into one program and timed in 12 alternating pairs per view
/// at the lab's four angles, medians −5 to −8 % for POM-32, 0 to −7 % for steep parallax, +1
/// to −5 % for adaptive POM, +5 to −5 % for relief mapping. The kernels built for AVX-512 keep
/// the gathers, with which they were measured on a Zen 4. A macro for the reason
/// [`gather_cell`] is one.
macro_rules! plane_words {
    (gathers, $depths:expr, $below:expr, $idx:expr) => {{
        (_mm256_i32gather_epi32::<2>($depths, $idx), _mm256_i32gather_epi32::<2>($below, $idx))
    }};
    (loads, $depths:expr, $below:expr, $idx:expr) => {{
        let mut ix = [0i32; 8];
        _mm256_storeu_si256(ix.as_mut_ptr() as *mut __m256i, $idx);
        let (d, b) = ($depths as *const u16, $below as *const u16);
        // A word at a texel: 2-byte aligned; the index is a wrapped, non-negative texel index.
        macro_rules! at {
            ($p:expr, $k:expr) => {
                ($p.add(ix[$k] as usize) as *const i32).read_unaligned()
            };
        }
        // The eight lanes' words from plane row pointer `p`.
        macro_rules! words {
            ($p:expr) => {
                _mm256_setr_epi32(
                    at!($p, 0),
                    at!($p, 1),
                    at!($p, 2),
                    at!($p, 3),
                    at!($p, 4),
                    at!($p, 5),
                    at!($p, 6),
                    at!($p, 7),
                )
            };
        }
        (words!(d), words!(b))
    }};
}
pub(crate) use plane_words;

/// The packed map's bilinear depth at texel coordinates `(x, y)` for eight lanes from its
/// 16-bit depth plane ([`PackedRelief::depths`](crate::maps::packed::PackedRelief::depths)),
/// computed as `PackedRelief::sample_texel` computes the depth (bit-identical): one 32-bit word
/// holds a texel and its right neighbour (the padded grid needs no wrap there), so a cell takes
/// two words per lane where [`gather_cell`] takes four 64-bit ones, and the plane is half the
/// packed texels' size. `fetch` is `loads` or `gathers` ([`plane_words`]); `depths` and `below`
/// point at the plane and one padded row further on, as `*const i32`; the rest are
/// [`gather_cell`]'s. A macro for the reason that one is.
macro_rules! plane_depth {
    ($fetch:ident, $depths:expr, $below:expr, $x:expr, $y:expr, $mask_x:expr, $mask_y:expr, $stride_v:expr) => {{
        let (fx, fy, idx) = $crate::simd::avx2::gather::cell_index!($x, $y, $mask_x, $mask_y, $stride_v);
        let (r0, r1) = $crate::simd::avx2::gather::plane_words!($fetch, $depths, $below, idx);
        let low = _mm256_set1_epi32(0xffff);
        let d00 = _mm256_cvtepi32_ps(_mm256_and_si256(r0, low));
        let d10 = _mm256_cvtepi32_ps(_mm256_srli_epi32::<16>(r0));
        let d01 = _mm256_cvtepi32_ps(_mm256_and_si256(r1, low));
        let d11 = _mm256_cvtepi32_ps(_mm256_srli_epi32::<16>(r1));
        let top = _mm256_add_ps(d00, _mm256_mul_ps(_mm256_sub_ps(d10, d00), fx));
        let bottom = _mm256_add_ps(d01, _mm256_mul_ps(_mm256_sub_ps(d11, d01), fx));
        let depth_step = _mm256_set1_ps(crate::maps::packed::DEPTH_STEP);
        _mm256_mul_ps(_mm256_add_ps(top, _mm256_mul_ps(_mm256_sub_ps(bottom, top), fy)), depth_step)
    }};
}
pub(crate) use plane_depth;

/// The constants of the packed map's eight-lane bilinear depth fetch ([`packed_depth`]).
#[derive(Clone, Copy)]
pub(crate) struct DepthConsts {
    /// The 16-bit depth plane, and one padded row further on.
    pub depths: *const i32,
    pub below: *const i32,
    pub wf: std::arch::x86_64::__m256,
    pub hf: std::arch::x86_64::__m256,
    pub half: std::arch::x86_64::__m256,
    pub lo: std::arch::x86_64::__m256,
    pub hi: std::arch::x86_64::__m256,
    pub mask_x: std::arch::x86_64::__m256i,
    pub mask_y: std::arch::x86_64::__m256i,
    pub stride_v: std::arch::x86_64::__m256i,
}

impl DepthConsts {
    /// The constants for `map`, whose sides must be powers of two (`masks()` is `Some`).
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    pub(crate) unsafe fn new(map: &crate::maps::packed::PackedRelief) -> Self {
        use std::arch::x86_64::*;
        let (mxk, myk) = map.masks().expect("power-of-two map");
        // The gathers read texels of the unpadded grid: a 32-bit read there, and one padded row
        // further on, stays inside the plane (one entry longer than the grid).
        DepthConsts {
            depths: map.depths().as_ptr() as *const i32,
            below: map.depths().as_ptr().add(map.stride()) as *const i32,
            wf: _mm256_set1_ps(map.width() as f32),
            hf: _mm256_set1_ps(map.height() as f32),
            half: _mm256_set1_ps(0.5),
            lo: _mm256_set1_ps(-1.0e7),
            hi: _mm256_set1_ps(1.0e7),
            mask_x: _mm256_set1_epi32(mxk),
            mask_y: _mm256_set1_epi32(myk),
            stride_v: _mm256_set1_epi32(map.stride() as i32),
        }
    }
}

/// The packed map's bilinear depth at UV `(u, v)` for eight lanes, computed as
/// `PackedRelief::depth` computes it (bit-identical), from the depth plane
/// ([`plane_depth`], its words fetched by `fetch`, `loads` or `gathers`); `k` is a
/// [`DepthConsts`]. A macro for the reason [`gather_cell`] is one.
macro_rules! packed_depth {
    ($fetch:ident, $k:expr, $u:expr, $v:expr) => {{
        let k: &DepthConsts = &$k;
        let x = _mm256_min_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_mul_ps($u, k.wf), k.half), k.lo), k.hi);
        let y = _mm256_min_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_mul_ps($v, k.hf), k.half), k.lo), k.hi);
        $crate::simd::avx2::gather::plane_depth!(
            $fetch, k.depths, k.below, x, y, k.mask_x, k.mask_y, k.stride_v
        )
    }};
}
pub(crate) use packed_depth;
