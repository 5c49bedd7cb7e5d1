//! The fused frame's allocations do not grow with the frame: once warm, a frame makes the
//! same small number of allocations (the triangle setup's few vectors) at 64×40 as at
//! 1280×800, so nothing is allocated per pixel or per row. Counted by a wrapping global
//! allocator, on one thread.

use renderlab_core::scene::{bricks_wall, BRICKS_WALL_CENTRE};
use renderlab_core::{Camera, Scene, SceneObject};
use renderlab_relief::fused::{render_fused, FusedFrame};
use renderlab_relief::maps::complexity::ComplexityParams;
use renderlab_relief::{KernelChoice, ReliefMaterial, Technique};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded to the system allocator unchanged.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_warm_frame_allocates_the_same_few_times_at_any_size() {
    let m = renderlab_texture::materials::material("bricks", 64).expect("built-in material");
    let mats = [ReliefMaterial::new(&m, &ComplexityParams::default(), true)];
    let scene =
        Scene::new(vec![SceneObject { name: "wall2".into(), mesh: bricks_wall(), material: 0 }], vec![m]);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    for name in ["basic", "pom:32", "adaptive", "cone-newton", "pom-shadow"] {
        let t = Technique::parse(name).expect("technique");
        let k = t.kernel(KernelChoice::Auto).expect("kernel");
        let count = |w: u32, h: u32| {
            let cam = Camera::orbit(BRICKS_WALL_CENTRE, 6.0, 45.0, w, h);
            let mut frame = FusedFrame::default();
            pool.install(|| {
                for _ in 0..2 {
                    render_fused(&scene, &cam, &mats, t, k, true, &mut frame).expect("renders");
                }
                let before = ALLOCATIONS.load(Ordering::Relaxed);
                render_fused(&scene, &cam, &mats, t, k, true, &mut frame).expect("renders");
                ALLOCATIONS.load(Ordering::Relaxed) - before
            })
        };
        let (small, large) = (count(64, 40), count(1280, 800));
        assert_eq!(small, large, "{name}: allocations grow with the frame");
        assert!(large <= 32, "{name}: {large} allocations in a frame");
    }
}
