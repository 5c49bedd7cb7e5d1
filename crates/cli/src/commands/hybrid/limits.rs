//! What a hybrid frame's size must satisfy before any work: each side in range, and the
//! frame (with the scene, once loaded) within the renderer's memory budget.

use anyhow::{anyhow, bail, Result};
use renderlab_hybrid::memory;
use renderlab_lab::hybrid_lab::scenes;

/// The largest side `--resolution` accepts.
const MAX_SIDE: u32 = 16384;

/// Checks a `--resolution` (parsed by [`parse_size`]): each side in 1..=[`MAX_SIDE`], and
/// the frame within the renderer's memory budget (`bench`: a run's frame and reference at
/// once), refused in one line before any work.
pub(super) fn resolution((w, h): (u32, u32), bench: bool) -> Result<(u32, u32)> {
    if w > MAX_SIDE || h > MAX_SIDE {
        bail!("--resolution {w}x{h}: each side must lie in 1..={MAX_SIDE}");
    }
    check_memory("--resolution", w, h, bench)?;
    scenes::check_resolution(w, h).map_err(|e| anyhow!("--resolution: {e}"))?;
    Ok((w, h))
}

/// Refuses a frame whose estimated peak memory ([`memory::estimate`]) exceeds
/// [`memory::BUDGET`], naming the largest frame of that aspect that fits.
pub(super) fn check_memory(what: &str, w: u32, h: u32, bench: bool) -> Result<()> {
    let kind = if bench { memory::Run::Bench } else { memory::Run::Render };
    let need = memory::estimate(kind, u64::from(w) * u64::from(h));
    if need > memory::BUDGET {
        let (fw, fh) = memory::largest_frame(kind, w, h);
        bail!(
            "{what} {w}x{h} needs about {:.1} GiB, over the {} GiB memory budget; the largest frame of this aspect is {fw}x{fh} ({} Mpixel at most)",
            renderlab_core::memory::gib(need),
            memory::BUDGET >> 30,
            memory::max_pixels(kind) / 1_000_000
        );
    }
    Ok(())
}

/// Refuses a scene whose meshes' `triangles` and frame together exceed [`memory::BUDGET`]
/// ([`memory::estimate_with_scene`]), once the scene is loaded and before the renderer
/// builds anything for it.
pub(super) fn check_scene_memory(spec: &str, triangles: u64, w: u32, h: u32) -> Result<()> {
    let need = memory::estimate_with_scene(memory::Run::Render, u64::from(w) * u64::from(h), triangles);
    if need > memory::BUDGET {
        bail!(
            "{spec}: {triangles} triangles at {w}x{h} need about {:.1} GiB, over the {} GiB memory budget (about {} bytes per triangle); use a smaller frame or a lighter scene",
            renderlab_core::memory::gib(need),
            memory::BUDGET >> 30,
            memory::PER_TRIANGLE
        );
    }
    Ok(())
}
