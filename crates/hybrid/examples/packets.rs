//! The stages' rays traced in packets against ray by ray, side by side, on the built-in
//! scenes: the shadow stage's shadow rays, the reflection stage's first reflected rays and
//! the path-traced reference's camera rays. Run by hand:
//!
//! ```text
//! cargo run --release -p renderlab-hybrid --example packets -- [WIDTHxHEIGHT] [ROUNDS]
//! ```
//!
//! (default 1280x720, 5 rounds). Each scene gets a ray-cast G-buffer from its first camera;
//! every round times each way once, alternating, on one thread (CPU time of that thread),
//! and the medians are printed with their ratio. Both ways give the same values bit for
//! bit (checked before timing).

use glam::Vec3;
use renderlab_core::Camera;
use renderlab_hybrid::accel::closest_ray;
use renderlab_hybrid::lighting::direct_light;
use renderlab_hybrid::rng::Rng;
use renderlab_hybrid::stages::context::par_pixels;
use renderlab_hybrid::stages::shadows;
use renderlab_hybrid::stages::tiles::{par_tiles, Closest};
use renderlab_hybrid::Accel;
use renderlab_scene::procedural::{builtin, names};
use renderlab_scene::{GBuffer, HybridScene};
use renderlab_trace::Hit;
use std::time::Duration;

/// This thread's CPU time (so that other processes sharing the cores do not count).
fn thread_cpu() -> Duration {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `ts` is a valid timespec to write to.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = thread_cpu();
    let out = f();
    (out, (thread_cpu() - t).as_secs_f64() * 1e3)
}

fn gbuffer(scene: &HybridScene, accel: &Accel, cam: Camera) -> GBuffer {
    let mut g = GBuffer::empty(cam);
    for i in 0..g.opaque.len() {
        g.opaque[i] = accel.surface(scene, cam.position, g.view_dir(i)).filter(|sp| sp.transmission == 0.0);
    }
    g
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (w, h) = args
        .first()
        .and_then(|s| s.split_once('x'))
        .and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?)))
        .unwrap_or((1280u32, 720u32));
    let rounds: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(5);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a thread pool");
    println!("{w}x{h}, {rounds} rounds, one thread; ms of thread CPU time, medians");
    println!("| scene | triangles | rays | ray by ray ms | packets ms | packets / ray by ray |");
    println!("|---|---|---|---|---|---|");
    pool.install(|| {
        for name in names() {
            let scene = builtin(name).expect("a built-in scene");
            let accel = Accel::build(&scene).expect("a valid scene");
            let cam = Camera { width: w, height: h, ..scene.cameras[0].camera };
            let g = gbuffer(&scene, &accel, cam);
            let n = g.opaque.len();
            let tris: usize = scene.meshes.iter().map(|m| m.triangles.len()).sum();

            let shadow_single = |out: &mut Vec<Vec3>| {
                par_pixels(out, w, |i, o| {
                    let Some(sp) = &g.opaque[i] else { return 0 };
                    let mut rng = Rng::new(3, i as u64, shadows::STREAM);
                    let mut rays = 0;
                    *o = direct_light(&scene, &accel, sp, -g.view_dir(i), 1, &mut rng, &mut rays);
                    rays
                })
            };
            let shadow_packets = |out: &mut Vec<Vec3>| shadows::run(&scene, &accel, &g, 1, 3, out);
            let camera_single = |out: &mut Vec<Option<Hit>>| {
                par_pixels(out, w, |i, o| {
                    *o = accel.closest(cam.position, g.view_dir(i), f32::INFINITY);
                    1
                })
            };
            let camera_packets = |out: &mut Vec<Option<Hit>>| {
                par_tiles(
                    out,
                    w,
                    &accel,
                    Closest,
                    |i, b| {
                        b.push(closest_ray(cam.position, g.view_dir(i), f32::INFINITY), ());
                        Some(())
                    },
                    |_, o, (), _, hits| {
                        *o = hits[0];
                        1
                    },
                )
            };

            let (mut a, mut b) = (vec![Vec3::ZERO; n], vec![Vec3::ZERO; n]);
            let rays = shadow_single(&mut a);
            assert_eq!(rays, shadow_packets(&mut b));
            assert!(a
                .iter()
                .zip(&b)
                .all(|(x, y)| x.to_array().map(f32::to_bits) == y.to_array().map(f32::to_bits)));
            let (mut ha, mut hb) = (vec![None; n], vec![None; n]);
            camera_single(&mut ha);
            camera_packets(&mut hb);
            assert!(ha == hb);

            let (mut ts, mut tp, mut cs, mut cp) = (vec![], vec![], vec![], vec![]);
            for _ in 0..rounds {
                ts.push(timed(|| shadow_single(&mut a)).1);
                tp.push(timed(|| shadow_packets(&mut b)).1);
                cs.push(timed(|| camera_single(&mut ha)).1);
                cp.push(timed(|| camera_packets(&mut hb)).1);
            }
            let row = |what: &str, rays: u64, s: Vec<f64>, p: Vec<f64>| {
                let (s, p) = (median(s), median(p));
                println!("| {name} {what} | {tris} | {rays} | {s:.1} | {p:.1} | {:.2} |", p / s);
            };
            row("shadow rays (stage, 1 per light)", rays, ts, tp);
            row("camera rays (reference's first)", n as u64, cs, cp);
        }
    });
}
