//! Whitted's adaptive supersampling (1980): rays through the corners of each pixel; where the
//! four corners differ, the pixel is split into four and the quarters are treated the same way,
//! down to a depth limit.
//!
//! Corners lie on a lattice `2^depth` times finer than the pixels, named by integer coordinates
//! `(i, j)`: the image-plane point `(i, j) / 2^depth`. A corner is shared by every pixel and
//! sub-pixel that touches it and is traced exactly once (a [`OnceLock`] per corner: a thread
//! that needs a corner another thread is tracing waits for it). A corner's colour depends only
//! on its position, so the image is the same whoever traces it, on any number of threads.
//!
//! **Difference metric.** The four corners of a square differ when, in some channel, the
//! largest and smallest of their display values (linear radiance clamped to [0, 1] and
//! encoded with a gamma of 2 — close to sRGB, as the eye sees it, and cheap) are at least
//! `threshold` apart. A square is then split
//! unless it is at the depth limit. A pixel is also split when one of its four neighbours
//! (left, right, above, below) has corners that differ: a regular lattice aliases patterns
//! finer than a pixel (a checkerboard near the horizon), and a pixel whose corners agree by
//! chance in such a busy region would otherwise keep a wrong colour. This widening of
//! Whitted's test costs no rays at the pixel level, since every pixel's corners are traced
//! anyway. Threshold 0 therefore splits every square; an infinite threshold none. A square that is not split takes the mean of its four corners; a split one,
//! the mean of its quarters.
//!
//! The image is traced in bands of tile rows, one after the other (the tiles of a band in
//! parallel). A band keeps its pixel corners in a dense grid and the sub-pixel corners on pixel
//! edges, which two pixels share, in a map; the corners inside a pixel live only while that
//! pixel is worked on. A band hands the corners of the row it shares to the next one and is then
//! dropped, so memory stays proportional to a band, not to the image.

use crate::color::Rgb;
use crate::integrator::{Integrator, RayStats};
use crate::sampling::sobol::Sampler;
use crate::sampling::uniform;
use crate::scene::{Beam, Scene};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// The deepest subdivision allowed: 2^8 = 256 sub-pixels per pixel side.
pub const MAX_DEPTH: u32 = 8;

/// The corners a pixel uses when split at every level down to `depth`, as
/// [`BandCorners::pixel`] counts them: 4, and 5 more for each split.
pub fn corners_fully_split(depth: u32) -> u64 {
    4 + 5 * (4u64.pow(depth) - 1) / 3
}

/// Settings of adaptive supersampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    /// Corners whose display values differ by at least this much get split (≥ 0).
    pub threshold: f32,
    /// How many times a pixel may be halved (0..=MAX_DEPTH).
    pub depth: u32,
    /// Quadtree over the screen: blocks of `2^block` pixels a side start with one corner
    /// each and are split where their corners differ, down to pixels (0: start at pixels).
    pub block: u32,
}

impl Default for Adaptive {
    fn default() -> Self {
        Self {
            threshold: 0.1,
            depth: 3,
            block: 0,
        }
    }
}

const SHARDS: usize = 16;

/// Corners by lattice position, each traced once.
type CornerSlots = HashMap<(u32, u32), Arc<OnceLock<Rgb>>, FastHash>;

/// Corners shared between threads, behind sharded locks.
#[derive(Default)]
struct SharedCorners {
    shards: [Mutex<CornerSlots>; SHARDS],
}

impl SharedCorners {
    /// The slot of corner `(i, j)`, made empty when it is new.
    fn slot(&self, i: u32, j: u32) -> Arc<OnceLock<Rgb>> {
        let shard = (i ^ j.rotate_left(7)) as usize % SHARDS;
        let mut map = self.shards[shard].lock().unwrap_or_else(|e| e.into_inner());
        map.entry((i, j)).or_default().clone()
    }
}

/// A cheap hasher for lattice coordinates (a multiply and a rotate per word).
#[derive(Clone, Copy, Default)]
struct FastHash;

impl std::hash::BuildHasher for FastHash {
    type Hasher = FastHasher;
    fn build_hasher(&self) -> FastHasher {
        FastHasher(0)
    }
}

struct FastHasher(u64);

impl std::hash::Hasher for FastHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u32(&mut self, v: u32) {
        self.write_u64(u64::from(v));
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(29) ^ v).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// The corners of one band of the image (pixel rows `y0..y1`): the pixel corners in a dense
/// grid (rows `y0 − 1` to `y1 + 1`, for the neighbour test), the sub-pixel corners on pixel
/// edges (shared by two pixels) in a shared map. Corners inside a pixel belong to it alone and
/// are kept by [`BandCorners::pixel`] while it works.
pub struct Band {
    /// First and last row of pixel corners in the grid.
    first: u32,
    last: u32,
    columns: u32,
    pixel_corners: Vec<OnceLock<Rgb>>,
    edge_corners: SharedCorners,
}

impl Band {
    /// The band of pixel rows `y0..y1` of a `width × height` image. `above`, the band just
    /// above (if any), hands over the corners the two share.
    pub fn new(
        (width, height): (u32, u32),
        (y0, y1): (u32, u32),
        depth: u32,
        above: Option<Band>,
    ) -> Band {
        let columns = width + 1;
        let (first, last) = (y0.saturating_sub(1), (y1 + 1).min(height));
        let mut pixel_corners: Vec<OnceLock<Rgb>> = Vec::new();
        pixel_corners.resize_with(
            columns as usize * (last - first + 1) as usize,
            OnceLock::new,
        );
        let mut edge_corners = SharedCorners::default();
        if let Some(above) = above {
            let c = columns as usize;
            for (k, from) in above.pixel_corners.into_iter().enumerate() {
                let row = above.first + (k / c) as u32;
                if (first..=last).contains(&row) {
                    pixel_corners[(row - first) as usize * c + k % c] = from;
                }
            }
            // Of the sub-pixel corners above, only those on the shared row are needed here.
            let seam = y0 << depth;
            for (to, from) in edge_corners
                .shards
                .iter_mut()
                .zip(above.edge_corners.shards)
            {
                let mut from = from.into_inner().unwrap_or_else(|e| e.into_inner());
                from.retain(|&(_, j), _| j == seam);
                *to.get_mut().unwrap_or_else(|e| e.into_inner()) = from;
            }
        }
        Band {
            first,
            last,
            columns,
            pixel_corners,
            edge_corners,
        }
    }
}

/// What the pixels of one band need to find their corners.
#[derive(Clone, Copy)]
pub struct BandCorners<'a> {
    /// The scene traced.
    pub scene: &'a Scene,
    /// How a corner's colour is computed.
    pub integrator: &'a Integrator,
    /// The settings.
    pub adaptive: Adaptive,
    /// The band's corners.
    pub band: &'a Band,
    /// A beam holding every corner ray this is asked for (see [`corner_beam`]), or none:
    /// the corners' hits are found through it, the same bit for bit.
    pub beam: Option<&'a Beam>,
    /// With a shutter, the tile's copy of the scene from [`Scene::instants`], to trace each
    /// corner at instants across the shutter.
    pub instants: Option<&'a Mutex<Scene>>,
}

/// The beam of the corner rays that the pixels and blocks of the screen rectangle
/// `[x0, x1) × [y0, y1)` (blocks of `2^block` pixels starting at `(x0, y0)`) may trace: their
/// own corners, and those of the pixels beside them (see `busy_neighbour`); `None` for a
/// camera without one (a thin lens).
pub fn corner_beam(
    scene: &Scene,
    (x0, y0): (u32, u32),
    (x1, y1): (u32, u32),
    block: u32,
) -> Option<Beam> {
    let size = 1u32 << block;
    // A block starting inside the rectangle may reach past it; neighbours reach one pixel out.
    let reach = |a0: u32, a1: u32| a0 + (a1 - a0).div_ceil(size) * size;
    let (xe, ye) = (reach(x0, x1), reach(y0, y1));
    let frustum = scene.camera.frustum(
        (x0 as f32 - 1.5, y0 as f32 - 1.5),
        (xe as f32 + 1.5, ye as f32 + 1.5),
    )?;
    Some(scene.beam(&frustum))
}

/// The hash dimension of a corner's instants.
const CORNER_TIME: u32 = 4;
/// Instants a corner is traced at with a shutter.
const CORNER_INSTANTS: u32 = 8;

/// Corners inside the pixel being worked on.
type Inner = HashMap<(u32, u32), Rgb, FastHash>;

impl BandCorners<'_> {
    /// The colour at lattice corner `(i, j)`: with a shutter, its mean over
    /// [`CORNER_INSTANTS`] instants stratified across it, so that the corners (and the
    /// contrast between them that decides the splits) are of the blurred image.
    fn trace(&self, i: u32, j: u32, stats: &mut RayStats) -> Rgb {
        let key = (u64::from(j) << 32) | u64::from(i);
        let (Some(instants), Some(shutter)) = (self.instants, self.scene.shutter()) else {
            return self.trace_in(self.scene, i, j, key, stats);
        };
        let mut copy = instants.lock().unwrap_or_else(|e| e.into_inner());
        let mut sum = Rgb::BLACK;
        for k in 0..CORNER_INSTANTS {
            let u = (k as f32 + uniform(0, key, k, CORNER_TIME)) / CORNER_INSTANTS as f32;
            copy.put_at(shutter.at(u));
            sum += self.trace_in(&copy, i, j, key, stats);
        }
        sum * (1.0 / CORNER_INSTANTS as f32)
    }

    /// The colour at lattice corner `(i, j)` (`key`) in `scene`.
    fn trace_in(&self, scene: &Scene, i: u32, j: u32, key: u64, stats: &mut RayStats) -> Rgb {
        let step = (1u32 << self.adaptive.depth) as f32;
        let ray = scene.camera.ray(i as f32 / step, j as f32 / step);
        stats.camera += 1;
        // Adaptive sampling takes deterministic integrators only; the sampler is for the type.
        let mut sampler = Sampler::new(0, key, 0);
        let value = self
            .integrator
            .radiance_in(scene, self.beam, &ray, &mut sampler, stats);
        if value.is_finite() {
            value
        } else {
            stats.nonfinite += 1;
            Rgb::BLACK
        }
    }

    /// The colour at lattice corner `(i, j)`, traced if no one has yet.
    fn corner(&self, i: u32, j: u32, inner: &mut Inner, stats: &mut RayStats) -> Rgb {
        let d = self.adaptive.depth;
        let mask = (1u32 << d) - 1;
        let (on_column, on_row) = (i & mask == 0, j & mask == 0);
        if on_column && on_row {
            let (x, y) = (i >> d, (j >> d) - self.band.first);
            let slot = &self.band.pixel_corners[(y * self.band.columns + x) as usize];
            *slot.get_or_init(|| self.trace(i, j, stats))
        } else if on_column || on_row {
            let slot = self.band.edge_corners.slot(i, j);
            *slot.get_or_init(|| self.trace(i, j, stats))
        } else {
            *inner
                .entry((i, j))
                .or_insert_with(|| self.trace(i, j, stats))
        }
    }

    /// The colour of pixel `(x, y)` and the number of corners it used.
    pub fn pixel(&self, x: u32, y: u32, stats: &mut RayStats) -> (Rgb, u32) {
        let size = 1u32 << self.adaptive.depth;
        let mut inner = Inner::default();
        let mut used = 4;
        let busy = self.busy_neighbour(x, y, &mut inner, stats);
        let value = self.square(x * size, y * size, size, busy, &mut inner, stats, &mut used);
        (value, used)
    }

    /// Calls `put(x, y, colour, corners used)` for every pixel of the block of `size` pixels
    /// a side at `(x0, y0)`, clipped to the image: a block whose four corners agree is filled
    /// by bilinear interpolation between them (its pixels used no corner of their own); one
    /// whose corners differ, or that crosses the image's edge, is split, down to pixels, which
    /// are sampled as [`BandCorners::pixel`] does.
    pub fn block(
        &self,
        (x0, y0): (u32, u32),
        size: u32,
        stats: &mut RayStats,
        put: &mut dyn FnMut(u32, u32, Rgb, u32),
    ) {
        let (w, h) = (self.band.columns - 1, self.scene.camera.height());
        if x0 >= w || y0 >= h {
            return;
        }
        if size == 1 {
            let (value, used) = self.pixel(x0, y0, stats);
            put(x0, y0, value, used);
            return;
        }
        let inside = x0 + size <= w && y0 + size <= h;
        if inside {
            let step = self.adaptive.depth;
            let mut inner = Inner::default();
            let (i, j, s) = (x0 << step, y0 << step, size << step);
            let c = [
                self.corner(i, j, &mut inner, stats),
                self.corner(i + s, j, &mut inner, stats),
                self.corner(i, j + s, &mut inner, stats),
                self.corner(i + s, j + s, &mut inner, stats),
            ];
            if spread(&c) < self.adaptive.threshold {
                for y in y0..y0 + size {
                    for x in x0..x0 + size {
                        let u = (x - x0) as f32 + 0.5;
                        let v = (y - y0) as f32 + 0.5;
                        let (u, v) = (u / size as f32, v / size as f32);
                        let top = c[0] * (1.0 - u) + c[1] * u;
                        let bottom = c[2] * (1.0 - u) + c[3] * u;
                        put(x, y, top * (1.0 - v) + bottom * v, 0);
                    }
                }
                return;
            }
        }
        let h = size / 2;
        for (bx, by) in [(x0, y0), (x0 + h, y0), (x0, y0 + h), (x0 + h, y0 + h)] {
            self.block((bx, by), h, stats, put);
        }
    }

    /// True when a pixel beside `(x, y)` (left, right, above or below) has corners that differ:
    /// the pixel lies in a busy region even if its own corners agree by chance.
    fn busy_neighbour(&self, x: u32, y: u32, inner: &mut Inner, stats: &mut RayStats) -> bool {
        let size = 1u32 << self.adaptive.depth;
        let w = i64::from(self.band.columns - 1);
        let (x, y) = (i64::from(x), i64::from(y));
        // A neighbour's corner rows ny and ny + 1 must both be in the band's grid.
        let rows = i64::from(self.band.first)..i64::from(self.band.last);
        [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
            .into_iter()
            .filter(|&(nx, ny)| (0..w).contains(&nx) && rows.contains(&ny))
            .any(|(nx, ny)| {
                let (i, j) = (nx as u32 * size, ny as u32 * size);
                let c = [
                    self.corner(i, j, inner, stats),
                    self.corner(i + size, j, inner, stats),
                    self.corner(i, j + size, inner, stats),
                    self.corner(i + size, j + size, inner, stats),
                ];
                spread(&c) >= self.adaptive.threshold
            })
    }

    #[allow(clippy::too_many_arguments)]
    fn square(
        &self,
        i: u32,
        j: u32,
        size: u32,
        busy: bool,
        inner: &mut Inner,
        stats: &mut RayStats,
        used: &mut u32,
    ) -> Rgb {
        let c = [
            self.corner(i, j, inner, stats),
            self.corner(i + size, j, inner, stats),
            self.corner(i, j + size, inner, stats),
            self.corner(i + size, j + size, inner, stats),
        ];
        if size == 1 || (!busy && spread(&c) < self.adaptive.threshold) {
            return (c[0] + c[1] + c[2] + c[3]) * 0.25;
        }
        // A split makes 5 new corners: the edge midpoints and the centre.
        *used += 5;
        let h = size / 2;
        let quarters = [(i, j), (i + h, j), (i, j + h), (i + h, j + h)]
            .map(|(qi, qj)| self.square(qi, qj, h, false, inner, stats, used));
        (quarters[0] + quarters[1] + quarters[2] + quarters[3]) * 0.25
    }
}

/// The largest difference, over the channels, between the display values of the corners:
/// linear values clamped to [0, 1] and encoded with a gamma of 2 (close to sRGB, and cheap).
pub fn spread(corners: &[Rgb; 4]) -> f32 {
    let mut hi = [f32::MIN; 3];
    let mut lo = [f32::MAX; 3];
    for c in corners {
        for (k, v) in c.to_array().into_iter().enumerate() {
            let v = if v > 0.0 { v.min(1.0).sqrt() } else { 0.0 };
            hi[k] = hi[k].max(v);
            lo[k] = lo[k].min(v);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_is_the_largest_display_difference() {
        let grey = Rgb::new(0.25, 0.25, 0.25);
        assert_eq!(spread(&[grey; 4]), 0.0);
        let white = Rgb::new(1.0, 1.0, 1.0);
        // Values above 1 look white; NaN and negatives black.
        let s = spread(&[grey, grey, grey, Rgb::new(0.25, 2.0, 0.25)]);
        assert_eq!(s, spread(&[grey, grey, grey, Rgb::new(0.25, 1.0, 0.25)]));
        assert_eq!(s, 0.5);
        assert_eq!(
            spread(&[Rgb::new(f32::NAN, -1.0, 0.0), white, white, white]),
            1.0
        );
    }
}
