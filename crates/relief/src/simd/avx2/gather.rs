//! The shared AVX2 fetch of the packed map: the bilinear cell of eight lanes in four 64-bit
//! gathers.

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
        let x0 = _mm256_floor_ps($x);
        let y0 = _mm256_floor_ps($y);
        let (fx, fy) = (_mm256_sub_ps($x, x0), _mm256_sub_ps($y, y0));
        let xi = _mm256_and_si256(_mm256_cvttps_epi32(x0), $mask_x);
        let yi = _mm256_and_si256(_mm256_cvttps_epi32(y0), $mask_y);
        let idx = _mm256_add_epi32(_mm256_mullo_epi32(yi, $stride_v), xi);
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
