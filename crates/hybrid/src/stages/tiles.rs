//! Coherent ray batches for the stages: the image walked in tiles of [`TILE_W`] × [`TILE_H`]
//! pixels, and the rays the pixels of a tile ask for traced together as packets
//! ([`renderlab_trace::Tlas::closest_packet`], [`renderlab_trace::Tlas::any_packet`]).
//!
//! A pixel's work is split around its rays: `setup` pushes the rays it needs (with what it
//! will need to know about each) and keeps its own state; the tile's rays are traced, the
//! `k`-th ray of every pixel in one run so that a packet holds rays of neighbouring pixels
//! asking the same thing (the same light sample, the first reflection); `finish` reads the
//! answers in the order the pixel pushed its rays. A packet query gives every ray the same
//! answer as the single-ray query, bit for bit, so a stage written this way gives the
//! image it gives ray by ray, for any number of threads (bands of [`TILE_H`] rows run in
//! parallel; each pixel's work depends only on its index).

use crate::accel::Accel;
use rayon::prelude::*;
use renderlab_trace::{Hit, Ray, PACKET};

/// Tile width in pixels.
pub const TILE_W: usize = 8;
/// Tile height in pixels: a tile is one packet of [`PACKET`] rays when every pixel asks one.
pub const TILE_H: usize = PACKET / TILE_W;

/// What a batch of rays asks the BVH.
pub trait PacketQuery: Sync {
    /// The answer for one ray.
    type Out: Copy + Default + Send;
    /// The answers for up to [`PACKET`] rays traced together; entries past `rays.len()` are
    /// unused.
    fn trace(&self, accel: &Accel, rays: &[Ray]) -> [Self::Out; PACKET];
}

/// The nearest hit of each ray ([`Accel::closest`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Closest;

impl PacketQuery for Closest {
    type Out = Option<Hit>;
    fn trace(&self, accel: &Accel, rays: &[Ray]) -> [Option<Hit>; PACKET] {
        accel.tlas().closest_packet(rays)
    }
}

/// Whether anything lies on each ray ([`Accel::occluded`], for shadow rays).
#[derive(Clone, Copy, Debug, Default)]
pub struct Occluded;

impl PacketQuery for Occluded {
    type Out = bool;
    fn trace(&self, accel: &Accel, rays: &[Ray]) -> [bool; PACKET] {
        accel.tlas().any_packet(rays)
    }
}

/// The rays a pixel asks for, each with what the pixel needs to know about it afterwards.
#[derive(Clone, Debug)]
pub struct RayBatch<A> {
    rays: Vec<Ray>,
    aux: Vec<A>,
}

impl<A> RayBatch<A> {
    fn new() -> Self {
        Self { rays: Vec::new(), aux: Vec::new() }
    }

    /// Asks for `ray`; `aux` comes back beside its answer.
    pub fn push(&mut self, ray: Ray, aux: A) {
        self.rays.push(ray);
        self.aux.push(aux);
    }

    fn len(&self) -> usize {
        self.rays.len()
    }

    fn truncate(&mut self, len: usize) {
        self.rays.truncate(len);
        self.aux.truncate(len);
    }

    fn clear(&mut self) {
        self.truncate(0);
    }
}

/// One pixel of a tile with work to finish: its index in the band, its state, and its rays'
/// range in the tile's batch.
struct Pending<S> {
    local: usize,
    state: S,
    start: usize,
    count: usize,
}

/// Runs every pixel of `out` (row-major, `width` wide) through `setup`, traces the rays it
/// pushed with `query` in packets, tile by tile, and hands them to `finish` with the pixel's
/// output; sums the counts `finish` returns. A pixel whose `setup` returns `None` has nothing
/// to do (its rays, if any, are dropped and `finish` is not called).
pub fn par_tiles<T, S, A, Q>(
    out: &mut [T],
    width: u32,
    accel: &Accel,
    query: Q,
    setup: impl Fn(usize, &mut RayBatch<A>) -> Option<S> + Sync,
    finish: impl Fn(usize, &mut T, S, &[A], &[Q::Out]) -> u64 + Sync,
) -> u64
where
    T: Send,
    A: Send,
    Q: PacketQuery,
{
    let w = width.max(1) as usize;
    out.par_chunks_mut(w * TILE_H)
        .enumerate()
        .map(|(band, rows)| {
            let first = band * TILE_H * w;
            let height = rows.len().div_ceil(w);
            let mut batch = RayBatch::new();
            let mut pending: Vec<Pending<S>> = Vec::with_capacity(TILE_W * TILE_H);
            let mut order = Vec::new();
            let mut packet = Vec::with_capacity(PACKET);
            let mut answers = Vec::new();
            let mut total = 0;
            for x0 in (0..w).step_by(TILE_W) {
                batch.clear();
                for y in 0..height {
                    for x in x0..(x0 + TILE_W).min(w) {
                        let local = y * w + x;
                        if local >= rows.len() {
                            continue;
                        }
                        let start = batch.len();
                        match setup(first + local, &mut batch) {
                            Some(state) => {
                                pending.push(Pending { local, state, start, count: batch.len() - start })
                            }
                            None => batch.truncate(start),
                        }
                    }
                }
                // The k-th ray of every pixel, then the (k+1)-th: packets of like rays.
                order.clear();
                let most = pending.iter().map(|p| p.count).max().unwrap_or(0);
                for k in 0..most {
                    order.extend(pending.iter().filter(|p| k < p.count).map(|p| p.start + k));
                }
                answers.clear();
                answers.resize(batch.len(), Q::Out::default());
                for chunk in order.chunks(PACKET) {
                    packet.clear();
                    packet.extend(chunk.iter().map(|&i| batch.rays[i]));
                    let got = query.trace(accel, &packet);
                    for (&i, a) in chunk.iter().zip(got) {
                        answers[i] = a;
                    }
                }
                for p in pending.drain(..) {
                    let range = p.start..p.start + p.count;
                    total += finish(
                        first + p.local,
                        &mut rows[p.local],
                        p.state,
                        &batch.aux[range.clone()],
                        &answers[range],
                    );
                }
            }
            total
        })
        .sum()
}
