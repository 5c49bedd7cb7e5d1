//! First-person movement through the room: walking (W/S/A/D) on the floor, jumping under
//! gravity (Space), mouse look, and collisions with the walls.
//!
//! The player is a vertical cylinder of radius [`RADIUS`] standing on the floor with the eye
//! [`EYE_HEIGHT`] above it. Seen from above, every wall is a segment, and the floor a
//! rectangle: the thesis's invisible border walls around the walking area. A move is cut into
//! sub-steps no longer than half the radius, and after each the player is pushed out of every
//! wall segment it overlaps (the closest point of the segment at least `RADIUS` away) and
//! back inside the floor: since a sub-step is shorter than the radius, the player cannot
//! cross a wall between two checks.
//!
//! Conventions: yaw 0 looks along −Z (at the bricks wall, as the thesis's start position
//! does); yaw grows turning left; pitch is up from the horizon, within ±[`MAX_PITCH_DEG`].

use glam::{Vec2, Vec3, Vec3Swizzles};
use renderlab_core::{Camera, Scene};

/// The player's radius in world units (smaller than the thesis's 1.5 so that a wall's relief
/// can be looked at from close by).
pub const RADIUS: f32 = 0.5;
/// Eye height above the floor: the thesis's benchmark cameras stand at the bricks wall's
/// centre height, 2.25 units above the floor.
pub const EYE_HEIGHT: f32 = 2.25;
/// Walking speed in units per second.
pub const WALK_SPEED: f32 = 4.0;
/// Upward speed at the start of a jump (units per second).
pub const JUMP_SPEED: f32 = 5.0;
/// Gravity (units per second²), the thesis's physics space's.
pub const GRAVITY: f32 = 9.81;
/// Largest look angle above or below the horizon.
pub const MAX_PITCH_DEG: f32 = 89.0;
/// Longest time step simulated at once (a stalled frame does not launch the player).
pub const MAX_DT: f32 = 0.1;

/// A wall seen from above: the segment its base covers on the floor plane (x, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall {
    /// One end (x, z).
    pub a: Vec2,
    /// The other end (x, z).
    pub b: Vec2,
}

impl Wall {
    /// The point of the segment closest to `p`.
    pub fn closest(&self, p: Vec2) -> Vec2 {
        let d = self.b - self.a;
        let t = ((p - self.a).dot(d) / d.length_squared().max(1e-12)).clamp(0.0, 1.0);
        self.a + d * t
    }

    /// Whether the segment from `p` to `q` crosses this wall (touching counts).
    pub fn crossed_by(&self, p: Vec2, q: Vec2) -> bool {
        let cross = |o: Vec2, u: Vec2, v: Vec2| (u - o).perp_dot(v - o);
        let (d1, d2) = (cross(self.a, self.b, p), cross(self.a, self.b, q));
        let (d3, d4) = (cross(p, q, self.a), cross(p, q, self.b));
        d1 * d2 <= 0.0 && d3 * d4 <= 0.0 && (d1 != 0.0 || d2 != 0.0)
    }
}

/// What the player collides with: the walls and the floor.
#[derive(Clone, Debug, PartialEq)]
pub struct Room {
    /// The walls, seen from above.
    pub walls: Vec<Wall>,
    /// Height of the floor.
    pub floor_y: f32,
    /// The floor's corner of least x and z.
    pub min: Vec2,
    /// The floor's corner of greatest x and z.
    pub max: Vec2,
}

impl Room {
    /// The room of `scene`: an object whose vertices all share one height is floor (the
    /// walkable rectangle is their bounds in x and z, at the highest such height), every other
    /// object is a wall (the two vertices farthest apart in x, z give its segment). A scene
    /// without a floor gets the walls' bounds and the lowest vertex as its floor.
    pub fn from_scene(scene: &Scene) -> Self {
        let mut walls = Vec::new();
        let (mut floor_y, mut min, mut max) =
            (f32::NEG_INFINITY, Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
        let (mut all_min, mut all_max, mut lowest) =
            (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY), f32::INFINITY);
        for object in &scene.objects {
            let points: Vec<Vec3> = object.mesh.vertices.iter().map(|v| v.position).collect();
            if points.is_empty() {
                continue;
            }
            let (lo_y, hi_y) =
                points.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), p| (l.min(p.y), h.max(p.y)));
            lowest = lowest.min(lo_y);
            for p in &points {
                all_min = all_min.min(p.xz());
                all_max = all_max.max(p.xz());
            }
            if hi_y - lo_y < 1e-4 {
                floor_y = floor_y.max(hi_y);
                for p in &points {
                    min = min.min(p.xz());
                    max = max.max(p.xz());
                }
            } else {
                let mut best = (points[0].xz(), points[0].xz(), -1.0);
                for (i, p) in points.iter().enumerate() {
                    for q in &points[i + 1..] {
                        let d = p.xz().distance_squared(q.xz());
                        if d > best.2 {
                            best = (p.xz(), q.xz(), d);
                        }
                    }
                }
                walls.push(Wall { a: best.0, b: best.1 });
            }
        }
        if floor_y.is_infinite() {
            (floor_y, min, max) = (lowest, all_min, all_max);
        }
        Self { walls, floor_y, min, max }
    }

    /// Moves a player's footprint centre from `from` toward `to`, stopping at walls and the
    /// floor's edge, and returns where it ends.
    pub fn slide(&self, from: Vec2, to: Vec2) -> Vec2 {
        let delta = to - from;
        if delta == Vec2::ZERO {
            // Standing still never moves the player (a bookmark may stand closer to a wall
            // than the radius: the thesis's 80° camera does).
            return from;
        }
        let steps = (delta.length() / (RADIUS * 0.5)).ceil().clamp(1.0, 10_000.0) as u32;
        let mut p = self.settle(from);
        for _ in 0..steps {
            p = self.settle(p + delta / steps as f32);
        }
        p
    }

    /// Pushes `p` out of every wall it overlaps and back inside the floor.
    pub fn settle(&self, mut p: Vec2) -> Vec2 {
        // A few rounds: pushing out of one wall may push into another in a corner.
        for _ in 0..4 {
            for w in &self.walls {
                let c = w.closest(p);
                let d = p.distance(c);
                if d < RADIUS {
                    let away = if d > 1e-6 { (p - c) / d } else { (w.b - w.a).perp().normalize_or(Vec2::X) };
                    p = c + away * RADIUS;
                }
            }
            p = p.clamp(self.min + RADIUS, (self.max - RADIUS).max(self.min + RADIUS));
        }
        p
    }
}

/// One frame's input.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Input {
    /// Forward (+1, W) or back (−1, S).
    pub forward: f32,
    /// Right (+1, D) or left (−1, A).
    pub right: f32,
    /// Whether Space is down.
    pub jump: bool,
    /// Turn left in degrees (mouse motion to the left × sensitivity).
    pub yaw_deg: f32,
    /// Look up in degrees.
    pub pitch_deg: f32,
}

/// The player: where it stands and where it looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Player {
    /// Feet position (the eye is `eye_height` above).
    pub feet: Vec3,
    /// Vertical speed (units per second, up positive).
    pub vertical_speed: f32,
    /// Heading in degrees (0 looks along −Z).
    pub yaw_deg: f32,
    /// Look angle above the horizon in degrees.
    pub pitch_deg: f32,
    /// Eye height above the feet ([`EYE_HEIGHT`] unless a bookmark's camera stands higher).
    pub eye_height: f32,
}

impl Player {
    /// A player whose eye and view are `camera`'s: its feet on the floor, its eye height the
    /// camera's height above the floor (at least [`EYE_HEIGHT`]), exactly where the camera
    /// is (the first move pushes it out of a wall it stands too close to). The room's
    /// bookmarks are the thesis's cameras.
    pub fn from_camera(room: &Room, camera: &Camera) -> Self {
        let f = camera.forward.normalize_or(Vec3::NEG_Z);
        let xz = camera.position.xz();
        Self {
            feet: Vec3::new(xz.x, room.floor_y, xz.y),
            eye_height: (camera.position.y - room.floor_y).max(EYE_HEIGHT),
            vertical_speed: 0.0,
            yaw_deg: (-f.x).atan2(-f.z).to_degrees(),
            pitch_deg: f.y.clamp(-1.0, 1.0).asin().to_degrees().clamp(-MAX_PITCH_DEG, MAX_PITCH_DEG),
        }
    }

    /// The unit view direction.
    pub fn forward(&self) -> Vec3 {
        let (yaw, pitch) = (self.yaw_deg.to_radians(), self.pitch_deg.to_radians());
        Vec3::new(-yaw.sin() * pitch.cos(), pitch.sin(), -yaw.cos() * pitch.cos())
    }

    /// The eye position.
    pub fn eye(&self) -> Vec3 {
        self.feet + Vec3::Y * self.eye_height
    }

    /// Whether the player stands on the floor.
    pub fn on_ground(&self, room: &Room) -> bool {
        self.feet.y <= room.floor_y + 1e-4
    }

    /// Advances the player by `dt` seconds of `input` in `room`. Non-finite input is ignored.
    pub fn step(&mut self, room: &Room, input: Input, dt: f32) {
        let finite = |v: f32| if v.is_finite() { v } else { 0.0 };
        let dt = finite(dt).clamp(0.0, MAX_DT);
        self.yaw_deg = (self.yaw_deg + finite(input.yaw_deg)).rem_euclid(360.0);
        self.pitch_deg = (self.pitch_deg + finite(input.pitch_deg)).clamp(-MAX_PITCH_DEG, MAX_PITCH_DEG);
        let yaw = self.yaw_deg.to_radians();
        let ahead = Vec2::new(-yaw.sin(), -yaw.cos());
        let right = Vec2::new(yaw.cos(), -yaw.sin());
        let wish =
            ahead * finite(input.forward).clamp(-1.0, 1.0) + right * finite(input.right).clamp(-1.0, 1.0);
        let velocity = wish.normalize_or_zero() * WALK_SPEED;
        let xz = room.slide(self.feet.xz(), self.feet.xz() + velocity * dt);
        if input.jump && self.on_ground(room) {
            self.vertical_speed = JUMP_SPEED;
        }
        let mut y = self.feet.y + self.vertical_speed * dt;
        self.vertical_speed -= GRAVITY * dt;
        if y <= room.floor_y {
            y = room.floor_y;
            self.vertical_speed = 0.0;
        }
        self.feet = Vec3::new(xz.x, y, xz.y);
    }

    /// The camera seen from the player's eye, `width × height` pixels.
    pub fn camera(&self, width: u32, height: u32) -> Camera {
        let eye = self.eye();
        Camera::look_at(eye, eye + self.forward(), width, height)
    }
}

#[cfg(test)]
mod tests;
