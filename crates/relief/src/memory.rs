//! How much memory a relief run takes, measured: peak resident memory fitted as
//! `FIXED + per texel · texels · materials + per pixel · pixels` to `/usr/bin/time -v` of the
//! `renderlab` binary (BENCHMARKS.md, "Memory"), each measured slope with 7% added. The
//! command line refuses, before any work, a texture size and frame whose estimate exceeds
//! [`renderlab_core::memory::BUDGET`].

use renderlab_core::memory::BUDGET;

/// The fit of one kind of relief run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReliefMemory {
    /// Bytes per texel of one material's maps (the material, its pyramids, depth field,
    /// complexity and 8-bit copies; on the GPU backend the device's copies too).
    pub per_texel: u64,
    /// Bytes per frame pixel.
    pub per_pixel: u64,
}

impl ReliefMemory {
    /// Everything but the maps and the frame.
    pub const FIXED: u64 = 64 << 20;
    /// `relief render` on the CPU: 120 B per texel, 196 per pixel measured.
    pub const RENDER_CPU: Self = Self { per_texel: 128, per_pixel: 208 };
    /// `relief render` on the GPU backend (lavapipe keeps the device's textures in host
    /// memory): 215 B per texel measured.
    pub const RENDER_GPU: Self = Self { per_texel: 232, per_pixel: 208 };
    /// `relief bench` on the CPU: 127 B per texel, 411 per pixel measured (the reference,
    /// the frames and images of every technique at an angle).
    pub const BENCH_CPU: Self = Self { per_texel: 136, per_pixel: 440 };
    /// `relief bench` with a GPU backend.
    pub const BENCH_GPU: Self = Self { per_texel: 232, per_pixel: 440 };

    /// The estimated peak bytes of a frame of `pixels` pixels alone (no maps).
    pub fn frame(self, pixels: u64) -> u64 {
        Self::FIXED.saturating_add(self.per_pixel.saturating_mul(pixels))
    }

    /// The estimated peak bytes of `materials` materials of `size`² texels and a frame of
    /// `pixels` pixels.
    pub fn estimate(self, size: u32, materials: u64, pixels: u64) -> u64 {
        let texels = u64::from(size) * u64::from(size) * materials;
        self.frame(pixels).saturating_add(self.per_texel.saturating_mul(texels))
    }

    /// The largest texture side whose `materials` materials fit [`BUDGET`] beside a frame of
    /// `pixels` pixels (0 where the frame alone exceeds it).
    pub fn largest_texture(self, materials: u64, pixels: u64) -> u32 {
        let rest = self.frame(pixels);
        if rest >= BUDGET {
            return 0;
        }
        (((BUDGET - rest) / (self.per_texel * materials.max(1))) as f64).sqrt() as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_texture_fits_and_one_more_texel_side_does_not() {
        for fit in [ReliefMemory::RENDER_CPU, ReliefMemory::RENDER_GPU, ReliefMemory::BENCH_CPU] {
            for (materials, pixels) in [(1, 1280 * 800), (4, 0), (1, 8192 * 8192)] {
                let side = fit.largest_texture(materials, pixels);
                if side == 0 {
                    assert!(fit.frame(pixels) >= BUDGET);
                    continue;
                }
                assert!(fit.estimate(side, materials, pixels) <= BUDGET);
                assert!(fit.estimate(side + 1, materials, pixels) > BUDGET);
            }
        }
        // The measured limits (BENCHMARKS.md): 8057 on the CPU with a 1280x800 frame.
        assert_eq!(ReliefMemory::RENDER_CPU.largest_texture(1, 1280 * 800), 8057);
    }
}
