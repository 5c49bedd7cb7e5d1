use super::*;
use proptest::prelude::*;
use renderlab_measure::fixtures::{benchmark_camera, thesis_room, BENCH_ANGLES_DEG};

fn room() -> Room {
    Room::from_scene(&thesis_room(16).unwrap())
}

/// The distance from `p` to the nearest wall.
fn clearance(room: &Room, p: Vec2) -> f32 {
    room.walls.iter().map(|w| p.distance(w.closest(p))).fold(f32::INFINITY, f32::min)
}

#[test]
fn the_thesis_room_has_three_walls_and_a_floor() {
    let r = room();
    assert_eq!(r.walls.len(), 3);
    assert!((r.floor_y - -1.25).abs() < 1e-5, "{}", r.floor_y);
    assert!((r.min - Vec2::new(-12.0, 1.0)).abs().max_element() < 1e-4, "{}", r.min);
    assert!((r.max - Vec2::new(12.0, 13.0)).abs().max_element() < 1e-4, "{}", r.max);
}

#[test]
fn walking_into_the_bricks_wall_stops_a_radius_short() {
    let r = room();
    let mut p = Player::from_camera(&r, &benchmark_camera(0.0, 64, 40));
    for _ in 0..200 {
        p.step(&r, Input { forward: 1.0, ..Default::default() }, 0.05);
    }
    // The bricks wall is the plane z = 1; the player stops RADIUS in front of it.
    assert!((p.feet.z - (1.0 + RADIUS)).abs() < 1e-3, "{}", p.feet.z);
}

#[test]
fn bookmarks_give_back_the_thesis_cameras() {
    let r = room();
    let cameras = BENCH_ANGLES_DEG.map(|a| benchmark_camera(a, 64, 40));
    for (angle, c) in BENCH_ANGLES_DEG
        .iter()
        .map(|a| a.to_string())
        .chain(["room".into()])
        .zip(cameras.into_iter().chain([renderlab_measure::fixtures::room_camera(64, 40)]))
    {
        let back = Player::from_camera(&r, &c).camera(64, 40);
        assert!(back.position.distance(c.position) < 1e-4, "{angle}: {} vs {}", back.position, c.position);
        assert!(back.forward.distance(c.forward) < 1e-4, "{angle}: {} vs {}", back.forward, c.forward);
    }
}

#[test]
fn a_jump_rises_and_lands_back_on_the_floor() {
    let r = room();
    let mut p = Player::from_camera(&r, &benchmark_camera(0.0, 64, 40));
    p.step(&r, Input { jump: true, ..Default::default() }, 0.02);
    let mut peak = p.feet.y;
    for _ in 0..200 {
        p.step(&r, Input::default(), 0.02);
        peak = peak.max(p.feet.y);
    }
    // v²/2g = 25 / 19.62 ≈ 1.27 units; the explicit Euler step loses a little.
    assert!(peak - r.floor_y > 1.0 && peak - r.floor_y < 1.4, "peak {}", peak - r.floor_y);
    assert_eq!(p.feet.y, r.floor_y);
    assert!(p.on_ground(&r));
}

fn input() -> impl Strategy<Value = (Input, f32)> {
    (-1.5f32..1.5, -1.5f32..1.5, any::<bool>(), -40f32..40.0, -40f32..40.0, 0f32..0.2).prop_map(
        |(forward, right, jump, yaw_deg, pitch_deg, dt)| {
            (Input { forward, right, jump, yaw_deg, pitch_deg }, dt)
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// From any start inside the room, any sequence of inputs keeps the player inside: it never
    /// crosses a wall, never comes closer to one than its radius, never leaves the floor's
    /// rectangle and never sinks below the floor.
    #[test]
    fn the_player_never_passes_through_a_wall(
        x in -11.0f32..11.0, z in 2.0f32..12.0, yaw in 0f32..360.0,
        inputs in proptest::collection::vec(input(), 1..120),
    ) {
        let r = room();
        let start = Vec2::new(x, z);
        // Only starts in front of every wall (inside the room) and clear of them.
        let inside = r.walls.iter().all(|w| (w.b - w.a).perp_dot(start - w.a).signum()
            == (w.b - w.a).perp_dot(Vec2::new(0.0, 7.0) - w.a).signum());
        prop_assume!(inside && clearance(&r, start) >= RADIUS);
        let mut p = Player { feet: Vec3::new(x, r.floor_y, z), vertical_speed: 0.0, yaw_deg: yaw, pitch_deg: 0.0, eye_height: EYE_HEIGHT };
        for (i, dt) in inputs {
            let before = p.feet.xz();
            p.step(&r, i, dt);
            let after = p.feet.xz();
            for w in &r.walls {
                prop_assert!(!w.crossed_by(before, after), "crossed {w:?} from {before} to {after}");
            }
            prop_assert!(clearance(&r, after) >= RADIUS - 1e-3, "{after} is {} from a wall", clearance(&r, after));
            prop_assert!(after.cmpge(r.min).all() && after.cmple(r.max).all(), "{after} left the floor");
            prop_assert!(p.feet.y >= r.floor_y);
            prop_assert!(p.pitch_deg.abs() <= MAX_PITCH_DEG);
        }
    }
}
