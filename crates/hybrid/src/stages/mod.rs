//! The ray-traced stages. Each reads the [`GBuffer`](renderlab_scene::GBuffer) and writes
//! one slot of [`LightingTerms`](renderlab_scene::LightingTerms) (translucency: the final
//! image), pixel rows in parallel, every pixel with its own random stream; each returns the
//! number of rays it traced.

pub mod ao;
pub mod gi;
pub mod reflections;
pub mod shadows;
pub mod translucency;

use rayon::prelude::*;

/// Runs `f(pixel, &mut out[pixel])` for every pixel, rows in parallel, and sums the counts
/// it returns. Each pixel's work depends only on its index, and integer sums do not depend
/// on their order, so the result is the same for any number of threads.
pub(crate) fn par_pixels<T: Send>(out: &mut [T], width: u32, f: impl Fn(usize, &mut T) -> u64 + Sync) -> u64 {
    let w = width.max(1) as usize;
    out.par_chunks_mut(w)
        .enumerate()
        .map(|(y, row)| row.iter_mut().enumerate().map(|(x, o)| f(y * w + x, o)).sum::<u64>())
        .sum()
}
