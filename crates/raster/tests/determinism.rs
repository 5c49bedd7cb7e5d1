//! The output is bit-identical whatever the number of threads.

mod common;

use common::{room, room_camera, wall_camera, wall_scene};
use renderlab_core::{Camera, Scene, SurfacePoint};
use renderlab_raster::{overdraw, rasterize_into, GBuffer, RasterStats};

/// Every bit of a G-buffer, so that −0.0 vs 0.0 or NaN payloads would count as differences.
fn bits(g: &GBuffer) -> Vec<u32> {
    bits_of(g.pixels())
}

fn bits_of(pixels: &[Option<SurfacePoint>]) -> Vec<u32> {
    let mut out = Vec::new();
    for p in pixels {
        match p {
            None => out.push(u32::MAX),
            Some(SurfacePoint {
                uv,
                duv_dx,
                duv_dy,
                tbn,
                view_ts,
                light_ts,
                position,
                depth,
                object,
                material,
            }) => {
                let floats = uv
                    .to_array()
                    .into_iter()
                    .chain(duv_dx.to_array())
                    .chain(duv_dy.to_array())
                    .chain(tbn.to_cols_array())
                    .chain(view_ts.to_array())
                    .chain(light_ts.to_array())
                    .chain(position.to_array())
                    .chain([*depth]);
                out.extend(floats.map(f32::to_bits));
                out.extend([*object, *material]);
            }
        }
    }
    out
}

fn run_with_threads(n: usize, scene: &Scene, cam: &Camera) -> (Vec<u32>, RasterStats, Vec<u32>) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
    pool.install(|| {
        let mut g = GBuffer::default();
        let stats = rasterize_into(scene, cam, &mut g);
        (bits(&g), stats, overdraw(scene, cam))
    })
}

#[test]
fn thesis_room_is_bit_identical_for_1_2_and_3_threads() {
    let scene = room();
    let cam = room_camera(416, 263);
    let reference = run_with_threads(1, &scene, &cam);
    assert!(reference.1.covered > 416 * 263 / 2, "{:?}", reference.1);
    for n in [2, 3] {
        let other = run_with_threads(n, &scene, &cam);
        assert!(other.0 == reference.0, "{n} threads: G-buffer differs");
        assert_eq!(other.1, reference.1, "{n} threads: counters differ");
        assert!(other.2 == reference.2, "{n} threads: overdraw differs");
    }
}

#[test]
fn benchmark_wall_is_bit_identical_for_1_2_and_3_threads() {
    let scene = wall_scene();
    for angle in [45.0, 80.0] {
        let cam = wall_camera(angle, 333, 211);
        let reference = run_with_threads(1, &scene, &cam);
        for n in [2, 3] {
            assert!(run_with_threads(n, &scene, &cam) == reference, "{angle}°, {n} threads");
        }
    }
}

#[test]
fn thesis_room_frame_is_consistent() {
    let scene = room();
    let cam = room_camera(320, 200);
    let mut g = GBuffer::default();
    let stats = rasterize_into(&scene, &cam, &mut g);
    assert_eq!(stats.triangles, 8);
    assert_eq!(stats.covered as usize, g.covered());
    let mut seen = [0usize; 4];
    for p in g.pixels().iter().flatten() {
        assert!(p.view_ts.z > 0.0, "view_ts {}", p.view_ts);
        assert_eq!(p.material, scene.objects[p.object as usize].material);
        // B is the direction in which v grows: on the walls that is downward.
        if p.object != 3 {
            assert!(p.tbn.y_axis.y < -0.999, "B = {}", p.tbn.y_axis);
        }
        seen[p.object as usize] += 1;
    }
    assert!(seen.iter().all(|&n| n > 100), "{seen:?}");
}

/// Row by row through [`RowRaster`], bands in reverse order on one reused scratch: the same
/// bits, rows and counts as the whole G-buffer.
fn streamed(scene: &Scene, cam: &Camera) -> (Vec<u32>, u64) {
    let r = renderlab_raster::RowRaster::new(scene, cam);
    let (w, h) = (cam.width as usize, cam.height as usize);
    let mut g = vec![None; w * h];
    let mut scratch = renderlab_raster::RowScratch::default();
    let mut covered = 0;
    let mut seen = vec![false; h];
    for band in (0..r.band_count()).rev() {
        covered += r
            .band(band, &mut scratch, |y, row| {
                assert_eq!(row.len(), w);
                assert!(!seen[y as usize], "row {y} twice");
                seen[y as usize] = true;
                g[y as usize * w..(y as usize + 1) * w].copy_from_slice(row);
            })
            .covered;
    }
    assert!(seen.iter().all(|&s| s), "every row once");
    (bits_of(&g), covered)
}

#[test]
fn streamed_rows_equal_the_whole_gbuffer() {
    for (scene, cam) in [(room(), room_camera(301, 187)), (wall_scene(), wall_camera(70.0, 257, 161))] {
        let whole = run_with_threads(1, &scene, &cam);
        let (rows, covered) = streamed(&scene, &cam);
        assert_eq!(rows, whole.0);
        assert_eq!(covered, whole.1.covered);
    }
}

/// The covered pixels' shade points through [`RowRaster::band_points`] are the G-buffer's
/// surface points, field for field, at the same columns.
#[test]
fn streamed_points_equal_the_gbuffer() {
    for (scene, cam) in [(room(), room_camera(301, 187)), (wall_scene(), wall_camera(80.0, 257, 161))] {
        let g = renderlab_raster::rasterize(&scene, &cam);
        let r = renderlab_raster::RowRaster::new(&scene, &cam);
        let mut scratch = renderlab_raster::RowScratch::default();
        let mut seen = 0;
        for band in 0..r.band_count() {
            r.band_points(band, &mut scratch, |y, xs, points| {
                let row = g.row(y);
                let expected: Vec<(u32, renderlab_core::ShadePoint)> = row
                    .iter()
                    .enumerate()
                    .filter_map(|(x, p)| p.as_ref().map(|p| (x as u32, p.into())))
                    .collect();
                let got: Vec<(u32, renderlab_core::ShadePoint)> =
                    xs.iter().copied().zip(points.iter().copied()).collect();
                assert_eq!(got, expected, "row {y}");
                seen += xs.len();
            });
        }
        assert_eq!(seen, g.covered());
    }
}

/// Without the view direction, the streamed points cover the same pixels with the same UV,
/// footprint and material as the G-buffer's.
#[test]
fn streamed_points_without_view_keep_the_rest() {
    for (scene, cam) in [(room(), room_camera(301, 187)), (wall_scene(), wall_camera(80.0, 257, 161))] {
        let g = renderlab_raster::rasterize(&scene, &cam);
        let r = renderlab_raster::RowRaster::new(&scene, &cam).without_view();
        let mut scratch = renderlab_raster::RowScratch::default();
        let mut seen = 0;
        for band in 0..r.band_count() {
            r.band_points(band, &mut scratch, |y, xs, points| {
                let key = |p: &renderlab_core::ShadePoint| (p.uv, p.duv_dx, p.duv_dy, p.material);
                let expected: Vec<_> = g
                    .row(y)
                    .iter()
                    .enumerate()
                    .filter_map(|(x, p)| p.as_ref().map(|p| (x as u32, key(&p.into()))))
                    .collect();
                let got: Vec<_> = xs.iter().copied().zip(points.iter().map(key)).collect();
                assert_eq!(got, expected, "row {y}");
                seen += xs.len();
            });
        }
        assert_eq!(seen, g.covered());
    }
}
