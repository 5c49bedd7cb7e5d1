//! The vector kernel's plain AVX2 copy, which CPUs without AVX-512 run: on a CPU with AVX-512
//! the other tests run the copy compiled for its registers, so this binary turns that copy off
//! (`RENDERLAB_NO_AVX512`, before the first query) and holds the AVX2 copy to the scalar
//! twin bit for bit on the benchmark blob's views: single rays and packets, closest hits and
//! occlusion, through a mesh and through instances.

use renderlab_trace::kernel::{available, wide_registers, Kernel, NO_AVX512};
use renderlab_trace::workload::{blob, placements, secondary_rays_to, view_rays, BLOBS_VIEW, BLOB_VIEW};
use renderlab_trace::{Blas, Instance, Ray, Tlas, PACKET};

#[test]
fn the_avx2_copy_equals_the_scalar_twin() {
    std::env::set_var(NO_AVX512, "1");
    if !available(Kernel::Simd) {
        eprintln!("skipped: this CPU has no AVX2 and FMA");
        return;
    }
    assert!(!wide_registers(), "{NO_AVX512} did not select the AVX2 copy");
    let (pos, tris) = blob();
    let simd = Blas::build(&pos, &tris).unwrap().with_kernel(Kernel::Simd);
    let scalar = Blas::build(&pos, &tris).unwrap().with_kernel(Kernel::Scalar);
    // Every 7th primary ray, the bounces and shadow rays from their hits.
    let primary: Vec<Ray> = view_rays(&BLOB_VIEW).into_iter().step_by(7).collect();
    let (bounce, shadow) = secondary_rays_to(&scalar, &pos, &tris, &primary, BLOB_VIEW.light);
    assert!(bounce.len() > primary.len() / 4 && shadow.len() == bounce.len());
    let place = placements();
    let instances: Vec<Instance> = place.iter().map(|&t| Instance::new(0, t)).collect();
    let tlas =
        |k: Kernel| Tlas::build(vec![Blas::build(&pos, &tris).unwrap().with_kernel(k)], &instances).unwrap();
    let (tlas_simd, tlas_scalar) = (tlas(Kernel::Simd), tlas(Kernel::Scalar));
    let mut hits = 0;
    for rays in [&primary, &bounce, &shadow] {
        for (k, chunk) in rays.chunks(PACKET).enumerate() {
            let (closest, any) = (simd.closest_packet(chunk), simd.any_packet(chunk));
            for (i, ray) in chunk.iter().enumerate() {
                let want = scalar.closest_hit(ray);
                assert_eq!(simd.closest_hit(ray), want, "packet {k} ray {i}");
                assert_eq!(closest[i], want, "packet {k} lane {i}");
                assert_eq!(any[i], scalar.any_hit(ray), "packet {k} lane {i}");
                hits += want.is_some() as usize;
            }
        }
    }
    assert!(hits > primary.len() / 4, "only {hits} hits");
    // The 48 copies as instances, seen from their own view.
    let mut instanced_hits = 0;
    let rays: Vec<Ray> = view_rays(&BLOBS_VIEW).into_iter().step_by(7).collect();
    for (k, chunk) in rays.chunks(PACKET).enumerate() {
        let (closest, any) = (tlas_simd.closest_packet(chunk), tlas_simd.any_packet(chunk));
        for (i, ray) in chunk.iter().enumerate() {
            let want = tlas_scalar.closest_hit(ray);
            assert_eq!(tlas_simd.closest_hit(ray), want, "instanced packet {k} ray {i}");
            assert_eq!(closest[i], want, "instanced packet {k} lane {i}");
            assert_eq!(any[i], want.is_some(), "instanced packet {k} lane {i}");
            instanced_hits += want.is_some() as usize;
        }
    }
    assert!(instanced_hits > rays.len() / 4, "only {instanced_hits} instanced hits");
}
