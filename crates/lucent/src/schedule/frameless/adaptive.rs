//! Adaptive frameless rendering, after Dayal, Woolley, Watson and Luebke (2005): samples go
//! where the picture changes, and the screen is reconstructed from samples weighed by their
//! age and distance.
//!
//! **Sampling.** The screen is cut into tiles of 8 × 8 pixels. Each tile keeps two running
//! estimates (exponential moving averages over its samples): its *temporal change* — how fast
//! a pixel's colour changes, `|c_new − c_old| / Δt` between two samples of one pixel, per
//! second — and its *spatial contrast* — how much a new sample differs from its four
//! neighbours' latest ones (edges, which motion turns into change). A tile's priority is
//! `age · (floor + change + κ · contrast)`, with `age` the time since its latest sample: the
//! colour error a tile has gathered since it was last visited grows about like
//! `age · change`, and the floor keeps revisiting still tiles, where a change that has not yet
//! been sampled hides. A batch of requests is shared out over the tiles in proportion to
//! priority by systematic sampling (one random offset, evenly spaced picks of the cumulative
//! priorities), and within a tile the pixels take turns in a random order, so that a tile's
//! samples spread over it. One request in four instead follows the frameless order, so that
//! the whole screen is still covered evenly at a quarter of the rate. Where Dayal et al. split and merge a k-d tree of tiles to keep
//! their number fixed, a fixed grid of small tiles serves a CPU just as well: the priorities
//! are cheap to recompute for every batch.
//!
//! **Reconstruction.** Each pixel shows a weighted mean of the latest samples of itself and its
//! eight neighbours, `Σ w c / Σ w` with `w = exp(−d² / 2σ²) · exp(−age / τ)` — the adaptive
//! space–time filter of the paper in a small form. `τ`, how long a sample stays trustworthy,
//! is short where the sample's tile changes fast (`τ = 1 / (change / C + 1 / τ_max)`); `σ`, the spatial
//! reach, widens as the pixel's own sample lags behind its freshest neighbour's, against `τ`. A still region keeps its own,
//! sharp, samples; a moving edge takes the fresher samples of its neighbours over its stale
//! own: what double buffering shows a frame late and frameless shows smeared, adaptive shows
//! soft but current.

use super::stochastic::Order;
use super::{Sample, SampleRequest, spread};
use crate::Rgb;
use crate::sampling::{mix64, permute, uniform};
use rayon::prelude::*;

/// One request in this many follows the frameless order instead of the priorities: a floor of
/// even coverage, so that a change where nothing changed before is found within a few passes
/// however the priorities lean (Dayal et al. likewise keep part of the budget unsteered).
const COVER: usize = 4;
/// Side of a tile in pixels.
const TILE: u32 = 8;
/// Weight of the moving averages' newest value.
const BLEND: f32 = 0.25;
/// The priority every tile has without change, per second: a still tile is revisited about
/// as often as a tile whose colours change by this much a second.
const FLOOR: f32 = 0.02;
/// Weight of spatial contrast against temporal change in a tile's priority.
const KAPPA: f32 = 0.1;
/// Samples closer than this in time give no rate (two samples in one instant).
const MIN_DT: f64 = 1.0 / 1000.0;
/// The colour difference that makes a sample untrustworthy (`C` in the module docs).
const CHANGE_SCALE: f32 = 0.25;
/// The longest a sample is trusted, in seconds, in a still tile.
const TAU_MAX: f32 = 4.0;
/// The spatial reach of the filter (`σ` in pixels) for a fresh pixel and a stale one.
const SIGMA_MIN: f32 = 0.35;
const SIGMA_MAX: f32 = 1.2;

/// What one tile knows of itself.
#[derive(Clone, Copy, Debug)]
struct TileState {
    x0: u32,
    y0: u32,
    w: u32,
    h: u32,
    /// Moving average of its pixels' colour change, per second.
    change: f32,
    /// Moving average of its samples' contrast with their neighbours.
    contrast: f32,
    /// The instant of its latest sample.
    last: f64,
    /// Position in the tile's current order of pixels, and how many orders it went through.
    cursor: u32,
    pass: u32,
}

/// The adaptive frameless display.
#[derive(Clone, Debug)]
pub struct AdaptiveFrameless {
    width: u32,
    height: u32,
    seed: u64,
    batches: u64,
    tiles_x: u32,
    tiles: Vec<TileState>,
    /// Per pixel, its latest sample and when it was taken.
    value: Vec<Rgb>,
    time: Vec<f64>,
    /// The reconstructed picture.
    shown: Vec<Rgb>,
    /// Scratch: each pixel's sample's trust, `exp(−age / τ)`.
    trust: Vec<f32>,
    /// Scratch: the tiles' cumulative priorities.
    cdf: Vec<f64>,
    /// The frameless order that a share of the samples follows.
    cover: Order,
}

/// How much two colours differ: the largest difference of a channel, each clamped to the
/// displayable `[0, 1]` (a highlight brighter than white changes nothing on screen).
#[inline]
fn difference(a: Rgb, b: Rgb) -> f32 {
    let d = |x: f32, y: f32| (x.clamp(0.0, 1.0) - y.clamp(0.0, 1.0)).abs();
    d(a.r, b.r).max(d(a.g, b.g)).max(d(a.b, b.b))
}

impl AdaptiveFrameless {
    /// A black screen of `width × height`; `seed` chooses the random picks.
    pub fn new(width: u32, height: u32, seed: u64) -> Self {
        let tiles_x = width.div_ceil(TILE);
        let tiles_y = height.div_ceil(TILE);
        let mut tiles = Vec::with_capacity((tiles_x * tiles_y) as usize);
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                let (x0, y0) = (tx * TILE, ty * TILE);
                tiles.push(TileState {
                    x0,
                    y0,
                    w: TILE.min(width - x0),
                    h: TILE.min(height - y0),
                    change: 0.0,
                    contrast: 0.0,
                    last: f64::NEG_INFINITY,
                    cursor: 0,
                    pass: 0,
                });
            }
        }
        let n = (width as usize) * (height as usize);
        Self {
            width,
            height,
            seed,
            batches: 0,
            tiles_x,
            tiles,
            value: vec![Rgb::BLACK; n],
            time: vec![f64::NEG_INFINITY; n],
            shown: vec![Rgb::BLACK; n],
            trust: Vec::new(),
            cdf: Vec::new(),
            cover: Order::new(width * height, seed ^ 0x5eed),
        }
    }

    /// The screen's size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn tile_of(&self, pixel: u32) -> usize {
        let (x, y) = (pixel % self.width, pixel / self.width);
        ((y / TILE) * self.tiles_x + x / TILE) as usize
    }

    /// `count` requests shared out over the tiles by priority at `t0`, at instants spread over
    /// `[t0, t1)` in a random order (so that no tile is always served first).
    pub fn plan(&mut self, count: usize, t0: f64, t1: f64, out: &mut Vec<SampleRequest>) {
        if self.tiles.is_empty() || count == 0 {
            return;
        }
        self.cdf.clear();
        let mut total = 0.0f64;
        for t in &self.tiles {
            // A tile never sampled comes before every other.
            let age = if t.last.is_finite() {
                (t0 - t.last).max(MIN_DT)
            } else {
                1e9
            };
            total += age * f64::from(FLOOR + t.change + KAPPA * t.contrast);
            self.cdf.push(total);
        }
        let batch = self.batches;
        self.batches += 1;
        let offset = f64::from(uniform(self.seed, batch, 0, 0));
        let time_key = mix64(self.seed ^ batch.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let mut tile = 0;
        out.reserve(count);
        for i in 0..count {
            let slot = permute(i as u32, count as u32, time_key) as usize;
            let time = spread(t0, t1, slot, count);
            // Every COVER-th request covers the screen in frameless order.
            if i % COVER == COVER - 1
                && let Some(pixel) = self.cover.next()
            {
                out.push(SampleRequest { pixel, time });
                continue;
            }
            let target = (i as f64 + offset) / count as f64 * total;
            while tile + 1 < self.tiles.len() && self.cdf[tile] <= target {
                tile += 1;
            }
            let t = &mut self.tiles[tile];
            let n = t.w * t.h;
            let key = mix64(self.seed ^ mix64((tile as u64) << 32 | u64::from(t.pass)));
            let k = permute(t.cursor, n, key);
            t.cursor += 1;
            if t.cursor == n {
                t.cursor = 0;
                t.pass += 1;
            }
            let (x, y) = (t.x0 + k % t.w, t.y0 + k / t.w);
            out.push(SampleRequest {
                pixel: y * self.width + x,
                time,
            });
        }
    }

    /// Stores the samples and updates their tiles' change and contrast.
    pub fn accept(&mut self, samples: &[Sample]) {
        for s in samples {
            let p = s.pixel as usize;
            if p >= self.value.len() || s.time < self.time[p] {
                continue;
            }
            let (old, old_time) = (self.value[p], self.time[p]);
            let contrast = self.contrast(s.pixel, s.color);
            let ti = self.tile_of(s.pixel);
            let tile = &mut self.tiles[ti];
            if old_time.is_finite() {
                let dt = (s.time - old_time).max(MIN_DT);
                let rate = difference(s.color, old) / dt as f32;
                tile.change += BLEND * (rate - tile.change);
            }
            tile.contrast += BLEND * (contrast - tile.contrast);
            tile.last = tile.last.max(s.time);
            self.value[p] = s.color;
            self.time[p] = s.time;
        }
    }

    /// The largest difference between `c` and the latest samples of the four neighbours of
    /// `pixel` (0 where none has one).
    fn contrast(&self, pixel: u32, c: Rgb) -> f32 {
        let (x, y) = (pixel % self.width, pixel / self.width);
        let mut most = 0.0f32;
        let mut look = |q: u32| {
            if self.time[q as usize].is_finite() {
                most = most.max(difference(c, self.value[q as usize]));
            }
        };
        if x > 0 {
            look(pixel - 1);
        }
        if x + 1 < self.width {
            look(pixel + 1);
        }
        if y > 0 {
            look(pixel - self.width);
        }
        if y + 1 < self.height {
            look(pixel + self.width);
        }
        most
    }

    /// Reconstructs the picture at `now` (see the module docs).
    pub fn present(&mut self, now: f64) -> &[Rgb] {
        let (w, h) = (self.width as usize, self.height as usize);
        let tiles_x = self.tiles_x as usize;
        let tau_at = |tiles: &[TileState], x: usize, y: usize| {
            let tile = &tiles[(y / TILE as usize) * tiles_x + x / TILE as usize];
            1.0 / (tile.change / CHANGE_SCALE + 1.0 / TAU_MAX)
        };
        // Each sample's trust, once per pixel (not once per pixel and neighbour: the filter
        // runs at the display's rate).
        let (time, tiles) = (&self.time, &self.tiles);
        self.trust.resize(w * h, 0.0);
        self.trust
            .par_chunks_mut(w.max(1))
            .enumerate()
            .for_each(|(y, row)| {
                for (x, trust) in row.iter_mut().enumerate() {
                    let t = time[y * w + x];
                    *trust = if t.is_finite() {
                        (-((now - t).max(0.0) as f32) / tau_at(tiles, x, y)).exp()
                    } else {
                        0.0
                    };
                }
            });
        let (value, trust) = (&self.value, &self.trust);
        self.shown
            .par_chunks_mut(w.max(1))
            .enumerate()
            .for_each(|(y, row)| {
                for (x, out) in row.iter_mut().enumerate() {
                    let p = y * w + x;
                    let (ys, xs) = (
                        y.saturating_sub(1)..(y + 2).min(h),
                        x.saturating_sub(1)..(x + 2).min(w),
                    );
                    // How much older the pixel's own sample is than its freshest neighbour's:
                    // a picture that is old everywhere alike is kept sharp.
                    let mut freshest = time[p];
                    for qy in ys.clone() {
                        for qx in xs.clone() {
                            freshest = freshest.max(time[qy * w + qx]);
                        }
                    }
                    let lag = if time[p].is_finite() {
                        (freshest - time[p]) as f32
                    } else {
                        f32::INFINITY
                    };
                    let stale = 1.0 - (-lag / tau_at(tiles, x, y)).exp();
                    let sigma = SIGMA_MIN + (SIGMA_MAX - SIGMA_MIN) * stale;
                    let spatial = [
                        1.0,
                        (-0.5 / (sigma * sigma)).exp(),
                        (-1.0 / (sigma * sigma)).exp(),
                    ];
                    let (mut sum, mut weight) = (Rgb::BLACK, 0.0f32);
                    for qy in ys.clone() {
                        for qx in xs.clone() {
                            let q = qy * w + qx;
                            let d2 = (qx != x) as usize + (qy != y) as usize;
                            let wq = spatial[d2] * trust[q];
                            sum += value[q] * wq;
                            weight += wq;
                        }
                    }
                    *out = if weight > 0.0 { sum / weight } else { value[p] };
                }
            });
        &self.shown
    }

    /// Per pixel, the instant of its own latest sample.
    pub fn shown_times(&self) -> &[f64] {
        &self.time
    }

    /// Takes `image` as every pixel's sample at `time`.
    pub fn prime(&mut self, image: &[Rgb], time: f64) {
        self.value.copy_from_slice(image);
        self.shown.copy_from_slice(image);
        self.time.fill(time);
        for t in &mut self.tiles {
            t.last = time;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gray(v: f32) -> Rgb {
        Rgb::gray(v)
    }

    #[test]
    fn samples_go_where_the_picture_changes() {
        // 32×32: 16 tiles. The top-left tile flickers, the rest stays still.
        let (w, h) = (32, 32);
        let mut a = AdaptiveFrameless::new(w, h, 1);
        a.prime(&vec![gray(0.5); (w * h) as usize], 0.0);
        let mut counts = vec![0usize; 16];
        let mut out = Vec::new();
        for step in 0..200 {
            let (t0, t1) = (step as f64 * 0.01, (step + 1) as f64 * 0.01);
            out.clear();
            a.plan(64, t0, t1, &mut out);
            let samples: Vec<Sample> = out
                .iter()
                .map(|r| {
                    let (x, y) = (r.pixel % w, r.pixel / w);
                    let moving = x < 8 && y < 8;
                    let v = if moving && (r.time * 20.0) as i64 % 2 == 0 {
                        1.0
                    } else {
                        0.5
                    };
                    Sample {
                        pixel: r.pixel,
                        time: r.time,
                        color: gray(v),
                    }
                })
                .collect();
            if step >= 100 {
                for r in &out {
                    counts[a.tile_of(r.pixel)] += 1;
                }
            }
            a.accept(&samples);
        }
        let hot = counts[0];
        let still = counts[1..].iter().sum::<usize>() / 15;
        assert!(
            hot > 5 * still,
            "changing tile {hot} samples, still tiles {still} on average"
        );
        assert!(
            counts.iter().all(|&c| c > 0),
            "every tile is revisited: {counts:?}"
        );
    }

    #[test]
    fn a_still_picture_is_shown_sharp() {
        let (w, h) = (16, 16);
        let mut a = AdaptiveFrameless::new(w, h, 2);
        let image: Vec<Rgb> = (0..w * h).map(|p| gray(((p % w) / 4 % 2) as f32)).collect();
        a.prime(&image, 0.0);
        let shown = a.present(10.0).to_vec();
        let worst = shown
            .iter()
            .zip(&image)
            .map(|(&s, &i)| difference(s, i))
            .fold(0.0, f32::max);
        assert!(worst < 0.02, "still edges blur by {worst}");
    }

    #[test]
    fn fresh_neighbours_outweigh_a_stale_pixel_where_things_move() {
        let (w, h) = (8, 8);
        let mut a = AdaptiveFrameless::new(w, h, 3);
        a.prime(&vec![gray(0.0); 64], 0.0);
        a.tiles[0].change = 20.0; // the tile is known to change fast
        // Every pixel but the centre one (27) is resampled at t = 1 and now white.
        let samples: Vec<Sample> = (0..64)
            .filter(|&p| p != 27)
            .map(|p| Sample {
                pixel: p,
                time: 1.0,
                color: gray(1.0),
            })
            .collect();
        a.accept(&samples);
        a.tiles[0].change = 20.0;
        let shown = a.present(1.0)[27];
        assert!(
            shown.r > 0.9,
            "stale black pixel shows {shown:?} among fresh white ones"
        );
    }
}
