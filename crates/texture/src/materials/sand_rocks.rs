//! `sand_rocks`: rippled sand with clusters of rounded rocks. The sand is low: wind ripples
//! (periodic, meandering), slow undulation and grain. The rocks are three cellular layers
//! (large stones, cobbles, pebbles) of irregular elliptic domes; a low-frequency density field
//! decides which cells hold a rock, so the rocks gather in clusters with pebbles around them
//! and open sand between. Each rock has its own size, shape, orientation, height and colour,
//! and darkens the sand around its base.

use super::noise::{for_each_feature, hash, hash2, lerp, perlin, rand, smoothstep, unit, Fbm};
use super::descriptor::{Entry, MaterialInfo, Sampler};
use super::texel::{srgb, Detail, Texel};
use glam::{Vec2, Vec3};

/// Relief depth in texture units per unit of height.
const HEIGHT_SCALE: f32 = 0.06;

impl Entry for SandRocks {
    const INFO: MaterialInfo = MaterialInfo {
        name: "sand_rocks",
        description: "rippled sand with clusters of rounded rocks",
        height_scale: HEIGHT_SCALE,
    };

    /// The rock layers are laid out once per build, then every texel reads them.
    fn sampler() -> Sampler {
        let rocks = SandRocks::new();
        Box::new(move |u, v, d| rocks.texel(u, v, d))
    }
}

const SEED: u32 = 0x5a9d_0002;
/// Jitter of the rock centres within their cells.
const JITTER: f32 = 0.8;

/// One potential rock: the properties of the feature point of one cell.
#[derive(Clone, Copy, Debug)]
struct Rock {
    /// Whether this cell holds a rock (decided by the cluster density).
    present: bool,
    /// Base radius in cells.
    radius: f32,
    /// Rotation (cos, sin) of the rock's long axis.
    rot: Vec2,
    /// Ratio of the long to the short axis.
    stretch: f32,
    /// Harmonics of the outline (cos 2θ, sin 2θ, cos 3θ, sin 3θ weights).
    lobes: [f32; 4],
    /// Height of the dome above the sand.
    amp: f32,
    /// Colour in linear light.
    color: Vec3,
    /// Centre in texture space.
    centre: Vec2,
    /// Largest extent of the outline in texture units, once settled.
    reach: f32,
}

/// A periodic cellular layer of rocks of one size class.
struct Layer {
    cells: u32,
    seed: u32,
    rocks: Vec<Rock>,
}

/// Rock colours (sRGB): greys, brownish and bluish stones.
fn palette(i: u32) -> Vec3 {
    match i % 6 {
        0 => srgb(128, 122, 114),
        1 => srgb(104, 97, 90),
        2 => srgb(150, 140, 124),
        3 => srgb(88, 84, 82),
        4 => srgb(138, 118, 98),
        _ => srgb(112, 112, 116),
    }
}

/// Where rocks gather: a smooth periodic field roughly in [-1, 1].
fn cluster(u: f32, v: f32) -> f32 {
    Fbm::new(3, 3, SEED + 11).octaves(3).fbm(u, v) * 1.6
}

impl Layer {
    /// Places the rocks of one size class on a periodic `cells × cells` lattice: a cell holds a
    /// rock where the cluster density exceeds `threshold` (radii in `radius`, in cells; dome
    /// heights in `amp`). Rocks are then settled largest first: each one shrinks so as not to
    /// cut into a rock already placed (of this layer or of the `bigger` ones), and is dropped
    /// if that leaves too little of it. So rocks touch and pile up, but never interpenetrate.
    fn new(
        cells: u32,
        seed: u32,
        threshold: f32,
        radius: (f32, f32),
        amp: (f32, f32),
        bigger: &[Layer],
    ) -> Self {
        let mut rocks = Vec::with_capacity((cells * cells) as usize);
        let mut centres = Vec::with_capacity(rocks.capacity());
        for iy in 0..cells {
            for ix in 0..cells {
                let id = hash2(ix, iy, seed);
                // The feature's position, as `for_each_feature` places it.
                let jx = 0.5 + JITTER * (unit(id) - 0.5);
                let jy = 0.5 + JITTER * (unit(hash(id)) - 0.5);
                let (fu, fv) = ((ix as f32 + jx) / cells as f32, (iy as f32 + jy) / cells as f32);
                centres.push(Vec2::new(fu, fv));
                let density = cluster(fu, fv);
                let present = density + 0.35 * (rand(id, 0) - 0.5) > threshold;
                // Denser clusters have bigger rocks.
                let big = smoothstep(threshold, threshold + 0.8, density);
                let angle = std::f32::consts::TAU * rand(id, 1);
                let c = palette((rand(id, 7) * 6.0) as u32).lerp(palette(id), 0.4 * rand(id, 8));
                rocks.push(Rock {
                    present,
                    radius: lerp(radius.0, radius.1, 0.5 * rand(id, 2) + 0.5 * big),
                    rot: Vec2::new(angle.cos(), angle.sin()),
                    stretch: 1.0 + 0.6 * rand(id, 3),
                    lobes: [
                        0.12 * (rand(id, 4) - 0.5),
                        0.12 * (rand(id, 5) - 0.5),
                        0.10 * (rand(id, 6) - 0.5),
                        0.10 * (rand(id, 9) - 0.5),
                    ],
                    amp: lerp(amp.0, amp.1, rand(id, 10)) * (0.8 + 0.2 * big),
                    color: c * (0.85 + 0.3 * rand(id, 11)),
                    centre: Vec2::new(fu, fv),
                    reach: 0.0,
                });
            }
        }
        // Settle: largest first (ties broken by cell index, so the order is fixed).
        let mut order: Vec<usize> = (0..rocks.len()).filter(|&i| rocks[i].present).collect();
        order.sort_by(|&a, &b| rocks[b].radius.total_cmp(&rocks[a].radius).then(a.cmp(&b)));
        let mut placed: Vec<usize> = Vec::with_capacity(order.len());
        let others: Vec<&Rock> = bigger.iter().flat_map(|l| l.rocks.iter()).filter(|r| r.present).collect();
        for i in order {
            let r = &rocks[i];
            // Largest extent of the outline, in texture units.
            let full = r.radius * (1.0 + r.lobes.iter().map(|l| l.abs()).sum::<f32>()) / cells as f32;
            let mut reach = full;
            for other in placed.iter().map(|&j| &rocks[j]).chain(others.iter().copied()) {
                let gap = periodic_distance(r.centre, other.centre) - 0.75 * other.reach;
                reach = reach.min(gap);
            }
            let keep = reach / full;
            let rock = &mut rocks[i];
            if keep < 0.45 {
                rock.present = false;
                continue;
            }
            rock.radius *= keep;
            rock.amp *= keep.sqrt();
            rock.reach = reach;
            placed.push(i);
        }
        Self { cells, seed, rocks }
    }
}

/// Distance between two points of the unit torus (texture space with wrap addressing).
fn periodic_distance(a: Vec2, b: Vec2) -> f32 {
    let d = (a - b).abs();
    d.min(Vec2::ONE - d).length()
}

/// The rock (if any) standing highest at one point.
#[derive(Clone, Copy, Debug)]
struct Hit {
    /// Height of the rock surface (or `f32::MIN`).
    top: f32,
    /// Dome profile of that rock in [0, 1] (0 at its outline).
    profile: f32,
    /// Colour of that rock.
    color: Vec3,
    /// Identity of that rock (for its surface pattern).
    id: u32,
    /// Smallest normalised distance `t` to any rock's outline (1 = on it): sand near rocks
    /// is shaded.
    near: f32,
}

/// Intersects the point `(u, v)` with the rocks of `layer`, updating `hit`.
fn rocks_at(layer: &Layer, u: f32, v: f32, hit: &mut Hit) {
    for_each_feature(u, v, layer.cells, layer.cells, JITTER, layer.seed, |f| {
        let rock = &layer.rocks[(f.cell[1] * layer.cells + f.cell[0]) as usize];
        if !rock.present {
            return;
        }
        // Point relative to the rock centre, in the rock's own frame, in cells.
        let p = -f.delta;
        let local = Vec2::new(
            p.x * rock.rot.x + p.y * rock.rot.y,
            (-p.x * rock.rot.y + p.y * rock.rot.x) * rock.stretch,
        );
        let r = local.length();
        let dir = if r > 1e-6 { local / r } else { Vec2::X };
        // Irregular outline: the radius varies with the angle (cos/sin of 2θ and 3θ).
        let (c, s) = (dir.x, dir.y);
        let (c2, s2) = (c * c - s * s, 2.0 * c * s);
        let (c3, s3) = (c * c2 - s * s2, s * c2 + c * s2);
        let l = rock.lobes;
        let radius = rock.radius * (1.0 + l[0] * c2 + l[1] * s2 + l[2] * c3 + l[3] * s3);
        let t = r / radius;
        hit.near = hit.near.min(t);
        if t < 1.0 {
            // A dome flattened slightly at the top, steep at the foot.
            let profile = (1.0 - t * t).sqrt().powf(0.8);
            let top = 0.06 + rock.amp * profile;
            if top > hit.top {
                *hit = Hit { top, profile, color: rock.color, id: f.id, near: hit.near };
            }
        }
    });
}

/// The sand-and-rocks material: its rocks, placed once, then sampled per texel.
pub(super) struct SandRocks {
    layers: Vec<Layer>,
}

impl SandRocks {
    /// Places the rocks of every layer.
    fn new() -> Self {
        // Large stones, cobbles and pebbles: cells per tile, seed, cluster threshold, radius
        // range (cells), dome height range.
        type Spec = (u32, u32, f32, (f32, f32), (f32, f32));
        const SPECS: [Spec; 3] = [
            (5, SEED + 1, 0.2, (0.5, 0.75), (0.7, 0.94)),
            (11, SEED + 2, 0.0, (0.4, 0.7), (0.45, 0.7)),
            (26, SEED + 3, -0.3, (0.35, 0.6), (0.2, 0.35)),
        ];
        let mut layers: Vec<Layer> = Vec::with_capacity(SPECS.len());
        for (cells, seed, threshold, radius, amp) in SPECS {
            let layer = Layer::new(cells, seed, threshold, radius, amp, &layers);
            layers.push(layer);
        }
        Self { layers }
    }

    /// One texel of sand and rocks at texture coordinates `(u, v)`.
    fn texel(&self, u: f32, v: f32, d: &Detail) -> Texel {
        texel(&self.layers, u, v, d)
    }
}

fn texel(layers: &[Layer], u: f32, v: f32, d: &Detail) -> Texel {
    let lim = d.max_cells;
    // --- sand -----------------------------------------------------------------------------
    // Wind ripples: crests along a direction with whole periods per tile, meandering by a
    // periodic warp; asymmetric profile (gentle windward, steeper lee side).
    let warp = Fbm::new(3, 3, SEED + 20).octaves(3).fbm(u, v);
    let phase = 3.0 * u + 13.0 * v + 1.1 * warp;
    let s = 0.5 + 0.5 * (std::f32::consts::TAU * phase).sin();
    let ripple = s * s.sqrt();
    let undulation = Fbm::new(4, 4, SEED + 21).octaves(3).fbm(u, v);
    let grain = perlin(u, v, lim, lim, SEED + 22);
    let fine = Fbm::new(48, 48, SEED + 23).octaves(3).limit(lim).fbm(u, v);
    let sand_h = 0.1 + 0.06 * ripple + 0.05 * undulation + 0.012 * fine + 0.006 * grain;

    // --- rocks ----------------------------------------------------------------------------
    let mut hit = Hit { top: f32::MIN, profile: 0.0, color: Vec3::ZERO, id: 0, near: f32::MAX };
    for layer in layers {
        rocks_at(layer, u, v, &mut hit);
    }
    // --- colour ---------------------------------------------------------------------------
    let sand_c =
        srgb(198, 172, 130) * (0.92 + 0.12 * ripple + 0.18 * fine + 0.14 * grain) * (1.0 + 0.15 * undulation);
    let dark_grains = smoothstep(0.55, 0.8, grain.abs());
    let sand_c = sand_c.lerp(srgb(96, 84, 70), 0.6 * dark_grains);
    // Sand is darker (damp, shaded) close to a rock's foot.
    let shade = 1.0 - 0.35 * (1.0 - smoothstep(1.0, 1.3, hit.near));
    let sand_c = sand_c * shade;
    if hit.top == f32::MIN {
        // Open sand: no rock here, skip the rock surface.
        return Texel { albedo: sand_c.clamp(Vec3::ZERO, Vec3::ONE), height: sand_h };
    }

    let rough = Fbm::new(20, 20, hit.id % 977 + SEED).octaves(4).limit(lim).fbm(u, v);
    let rock_h = hit.top + 0.05 * rough * hit.profile.sqrt();
    let mottle = Fbm::new(10, 10, SEED + 24).octaves(4).limit(lim).fbm(u, v);
    let speck = smoothstep(0.3, 0.6, perlin(u, v, lim.min(300), lim.min(300), SEED + 25));
    let rock_c = hit.color
        * (1.0 + 0.35 * mottle + 0.4 * rough)
        * (1.0 - 0.3 * speck)
        * lerp(0.55, 1.0, smoothstep(0.0, 0.4, hit.profile));

    // The rock shows where it rises above the sand; the colour blends over a small height
    // difference, about a texel at the steep foot of a rock.
    let w = smoothstep(-0.01, 0.01, rock_h - sand_h);
    Texel { albedo: sand_c.lerp(rock_c, w).clamp(Vec3::ZERO, Vec3::ONE), height: sand_h.max(rock_h) }
}
