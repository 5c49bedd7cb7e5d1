//! Frame rendering by technique: checks that a technique can run on the given materials and
//! kernel, dispatches it to its tracer once per frame (so the per-pixel loop is
//! monomorphised), and renders the matching reference.

pub mod horizon;
pub mod material;
pub mod patch;
pub mod shade;
pub mod shadow;

use crate::error::ReliefError;
use crate::kernel::Kernel;
use crate::march::exact::ExactTrace;
use crate::techniques::descriptor::WithTracer;
use crate::techniques::Technique;
use crate::trace::{ReliefTechnique, Shading};
use glam::Vec3;
use material::ReliefMaterial;
use renderlab_core::scene::Lighting;
use shade::{render_frame, render_frame_into, trace_frame, Frame, FrameInput, ShadeOptions, ShadowMode};

/// Shading options for `technique` under `lighting`.
pub fn options(technique: Technique, lighting: Lighting, background: Vec3) -> ShadeOptions {
    ShadeOptions { lighting, shading: technique.shading(), shadow: technique.shadow(), background }
}

/// Checks that `technique` can run on `kernel` here and that every material has the maps it
/// reads there; the error names the kernel or the missing map.
pub fn check(technique: Technique, kernel: Kernel, materials: &[ReliefMaterial]) -> Result<(), ReliefError> {
    use crate::kernel::KernelChoice;
    technique.kernel(KernelChoice::Exactly(kernel))?;
    for map in technique.descriptor().needs(kernel) {
        if let Some(m) = materials.iter().find(|m| !m.inputs().has(map)) {
            return Err(ReliefError::MissingMap {
                technique: technique.name(),
                map: map.name(),
                material: m.name.clone(),
            });
        }
    }
    Ok(())
}

/// Renders `technique` on `kernel`. With `count`, height fetches are tallied.
pub fn render(
    input: FrameInput,
    materials: &[ReliefMaterial],
    technique: Technique,
    kernel: Kernel,
    lighting: Lighting,
    background: Vec3,
    count: bool,
) -> Result<Frame, ReliefError> {
    let mut frame = Frame::blank(input.width, input.height, background);
    render_into(input, materials, technique, kernel, lighting, background, count, &mut frame)?;
    Ok(frame)
}

/// [`render`] into a frame kept from an earlier call (resized if its size differs): the same
/// pixels, without allocating the frame's buffers again. Timing loops use it, as a renderer
/// reuses its framebuffers.
#[allow(clippy::too_many_arguments)] // `render`'s arguments and the frame to fill.
pub fn render_into(
    input: FrameInput,
    materials: &[ReliefMaterial],
    technique: Technique,
    kernel: Kernel,
    lighting: Lighting,
    background: Vec3,
    count: bool,
    frame: &mut Frame,
) -> Result<(), ReliefError> {
    struct Render<'a, 'f> {
        input: FrameInput<'a>,
        materials: &'a [ReliefMaterial],
        opt: ShadeOptions,
        count: bool,
        frame: &'f mut Frame,
    }
    impl WithTracer for Render<'_, '_> {
        type Output = ();
        fn run<T: ReliefTechnique>(self, t: &T) {
            render_frame_into(self.input, self.materials, t, &self.opt, self.count, self.frame)
        }
    }
    check(technique, kernel, materials)?;
    let opt = options(technique, lighting, background);
    technique.with_tracer(kernel, Render { input, materials, opt, count, frame });
    Ok(())
}

/// The ground truth for `technique`: the exact intersection with the bilinear height field,
/// shaded the same way (unlit stays unlit; soft shadows become exact hard shadows).
pub fn render_reference(
    input: FrameInput,
    materials: &[ReliefMaterial],
    technique: Technique,
    lighting: Lighting,
    background: Vec3,
) -> Frame {
    let mut opt = options(technique, lighting, background);
    if opt.shading == Shading::LitShadowed {
        opt.shadow = ShadowMode::Exact;
    }
    render_frame(input, materials, &ExactTrace, &opt, false)
}

/// Runs only `technique`'s trace on `kernel` over the frame (see [`trace_frame`]); returns a
/// checksum.
pub fn trace_only(
    input: FrameInput,
    materials: &[ReliefMaterial],
    technique: Technique,
    kernel: Kernel,
) -> Result<f64, ReliefError> {
    struct TraceOnly<'a> {
        input: FrameInput<'a>,
        materials: &'a [ReliefMaterial],
    }
    impl WithTracer for TraceOnly<'_> {
        type Output = f64;
        fn run<T: ReliefTechnique>(self, t: &T) -> f64 {
            trace_frame(self.input, self.materials, t)
        }
    }
    check(technique, kernel, materials)?;
    Ok(technique.with_tracer(kernel, TraceOnly { input, materials }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::complexity::ComplexityParams;
    use glam::{Mat3, Vec2};
    use renderlab_core::SurfacePoint;

    /// A frame of `w × h` pixels, every `skip`-th one background, the rest looking at the
    /// material at `angle` degrees from the normal with UV spread over one tile and a bit.
    fn points(w: u32, h: u32, angle: f32, skip: u32) -> Vec<Option<SurfacePoint>> {
        let (s, c) = angle.to_radians().sin_cos();
        (0..w * h)
            .map(|i| {
                (i % skip != 0).then(|| SurfacePoint {
                    uv: Vec2::new((i % w) as f32 / w as f32 * 1.3, (i / w) as f32 / h as f32 * 1.1),
                    duv_dx: Vec2::new(1.3 / w as f32, 0.0),
                    duv_dy: Vec2::new(0.0, 1.1 / h as f32),
                    tbn: Mat3::IDENTITY,
                    view_ts: Vec3::new(s, 0.0, c),
                    light_ts: Vec3::new(0.3, 0.4, 0.866).normalize(),
                    position: Vec3::ZERO,
                    depth: 1.0,
                    object: 0,
                    material: 0,
                })
            })
            .collect()
    }

    fn input(w: u32, h: u32, points: &[Option<SurfacePoint>]) -> FrameInput<'_> {
        FrameInput::new(w, h, points)
    }

    #[test]
    fn a_reused_frame_gives_the_fresh_frame_bit_for_bit() {
        let m = renderlab_texture::materials::material("bricks", 64).expect("built-in material");
        let mats = [ReliefMaterial::new(&m, &ComplexityParams::default(), false)];
        let (w, h) = (37, 23);
        let lighting = Lighting::default();
        let bg = Vec3::new(0.1, 0.2, 0.3);
        let first = points(w, h, 10.0, 3);
        let second = points(w, h, 70.0, 4);
        let mut reused = render(
            input(w, h, &first),
            &mats,
            Technique::parse("pom:8").unwrap(),
            Kernel::Scalar,
            lighting,
            bg,
            true,
        )
        .expect("renders");
        let t = Technique::parse("steep:16").unwrap();
        render_into(input(w, h, &second), &mats, t, Kernel::Scalar, lighting, bg, true, &mut reused)
            .expect("renders");
        let fresh =
            render(input(w, h, &second), &mats, t, Kernel::Scalar, lighting, bg, true).expect("renders");
        assert_eq!(reused.image, fresh.image);
        assert_eq!(reused.uv, fresh.uv);
        assert_eq!(reused.depth, fresh.depth);
        assert_eq!(reused.layers, fresh.layers);
        assert_eq!(reused.mask, fresh.mask);
        assert_eq!(reused.fetches, fresh.fetches);
        // A frame of another size is replaced, not misread.
        let mut small = Frame::blank(3, 2, bg);
        render_into(input(w, h, &second), &mats, t, Kernel::Scalar, lighting, bg, true, &mut small)
            .expect("renders");
        assert_eq!(small.image, fresh.image);
    }
}
