//! The render driver: threads, progress, cancellation, checkpoints, shards and statistics.
//!
//! Tiles from the schedule are traced in parallel on a rayon pool of the requested size. Each
//! sample's position comes from [`crate::sampling`], a pure function of (seed, pixel, sample),
//! and each pixel's samples are added in the order of their indices, so the image is the same,
//! bit for bit, for any number of threads, any tile order, a render stopped and resumed, or
//! one split into shards.
//!
//! **Shards** split the work by tiles: shard `i` of `n` renders the tiles whose index (in
//! reading order) is `i` modulo `n`, all of their samples. Each pixel is therefore rendered
//! entirely by one shard, and shards merge exactly by adding their films.
//!
//! **Resuming** starts from a film that already holds some samples per pixel and adds the
//! missing ones, from the next sample index on.

use crate::Rgb;
use crate::film::Film;
use crate::film::filter::{Filter, FilterSampler};
use crate::film::splat::{Commits, FilterSampling, TileSplats};
use crate::integrator::{Integrator, RayStats};
use crate::sampling::sobol::Sampler;
use crate::scene::{Beam, Scene};
use crate::schedule::adaptive::{Adaptive, Band, BandCorners, corner_beam};
use crate::schedule::{Tile, tiles};
use lucent_accel::Ray;
use rayon::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};
use thiserror::Error;

mod camera_sample;
mod lanes;
mod sppm;
use camera_sample::{at_instant, camera_ray, draw};
use lanes::Tracing;

/// Samples per pixel in one pass over the tiles (see [`render`]).
pub const PASS_SAMPLES: u32 = 64;

/// Which share of the work a render does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0..count`.
    pub index: u32,
    /// How many shards the work is split into (at least 1).
    pub count: u32,
}

impl Default for Shard {
    /// The whole image.
    fn default() -> Self {
        Self { index: 0, count: 1 }
    }
}

impl Shard {
    /// True when tile `i` (in reading order) belongs to this shard.
    pub fn owns(&self, tile: usize) -> bool {
        tile % self.count.max(1) as usize == self.index as usize
    }
}

/// How to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// The light-transport method.
    pub integrator: Integrator,
    /// Samples per pixel (at least 1).
    pub spp: u32,
    /// Seed of every random decision.
    pub seed: u64,
    /// Worker threads; 0 uses every core.
    pub threads: usize,
    /// Side of the square tiles handed to threads, in pixels (also the unit of shards).
    pub tile_size: u32,
    /// The share of the work to do.
    pub shard: Shard,
    /// How each pixel is sampled.
    pub sampling: Sampling,
    /// The reconstruction filter: where in and around its pixel a sample goes, and its weight.
    pub filter: Filter,
    /// Whether a filter other than the one-pixel box splats samples into the pixels it reaches
    /// or keeps each in its own pixel ([`crate::film::splat`]).
    pub filter_sampling: FilterSampling,
    /// Stop after this long even if not every pixel has `spp` samples (uniform sampling).
    pub time_limit: Option<Duration>,
    /// Trace each tile's camera rays as one beam ([`crate::scene::Beam`]) when the camera is a
    /// pinhole — under Whitted in packets, with shadow beams for their hits' shadow rays
    /// towards point lights: the same image, faster. Adaptive sampling, the photon mapper and
    /// the debug views trace per pixel whatever this says.
    pub beam: bool,
    /// Trace the path tracer's samples eight at a time, shading the materials lanes know
    /// ([`crate::integrator::path_lanes`]) in SIMD lanes: the same image, bit for bit.
    pub lanes: bool,
}

/// How a pixel's value is sampled.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Sampling {
    /// `spp` samples per pixel, stratified and jittered.
    #[default]
    Uniform,
    /// Whitted's adaptive corners ([`crate::schedule::adaptive`]); `spp` is ignored: each
    /// pixel's value goes into the film as one sample.
    Adaptive(Adaptive),
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            integrator: Integrator::default(),
            spp: 1,
            seed: 0,
            threads: 0,
            tile_size: 16,
            shard: Shard::default(),
            sampling: Sampling::default(),
            filter: Filter::default(),
            filter_sampling: FilterSampling::default(),
            time_limit: None,
            beam: true,
            lanes: true,
        }
    }
}

/// What a render did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Rays by kind, and accelerator work.
    pub rays: RayStats,
    /// Film samples taken in this run: camera rays with uniform sampling, pixels with adaptive.
    pub samples: u64,
    /// Wall-clock time of the render.
    pub elapsed: Duration,
    /// Threads used.
    pub threads: usize,
}

impl RenderStats {
    /// Millions of rays (of every kind) per second of wall time.
    pub fn mrays_per_second(&self) -> f64 {
        self.rays.total() as f64 / self.elapsed.as_secs_f64().max(1e-9) / 1e6
    }
}

/// A finished (or interrupted) render.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The image's sums, weights and sample counts.
    pub film: Film,
    /// What it cost.
    pub stats: RenderStats,
    /// False when cancelled before every pixel of the shard got its samples (a render that
    /// reached its time limit is complete).
    pub complete: bool,
    /// True when the time limit ended the render.
    pub timed_out: bool,
    /// Fewest and most samples over the pixels of this render's shard.
    pub samples_range: (u32, u32),
    /// With adaptive sampling, the corners each pixel used (rows from the top; 0 for pixels
    /// not rendered in this run); empty otherwise.
    pub density: Vec<u32>,
}

/// Why a render could not run.
#[derive(Debug, Error)]
pub enum RenderError {
    /// The worker threads could not be started.
    #[error("could not start {threads} render threads: {source}")]
    Threads {
        /// How many were asked for.
        threads: usize,
        /// The cause.
        source: rayon::ThreadPoolBuildError,
    },
    /// The photon mapper's state is not in the film.
    #[error("a photon-mapped render cannot be {0}: its photon statistics are not in the film")]
    Sppm(&'static str),
    /// A splatting filter over shards: their films would not merge bit for bit.
    #[error(
        "a sharded render keeps every sample in its own pixel: use the box filter, or importance sampling of the filter"
    )]
    SplatShards,
    /// The reconstruction filter's parameters are out of range.
    #[error("the reconstruction filter: {0}")]
    Filter(String),
    /// The film to resume from does not fit the render.
    #[error(
        "the film to resume is {0}×{1} pixels with up to {2} samples; the render is {3}×{4} with {5}"
    )]
    ResumeMismatch(u32, u32, u32, u32, u32, u32),
}

/// The caller's hooks into a render: cancellation, progress and checkpoints.
pub struct Hooks<'a> {
    /// Set it to stop the render within one sample per thread.
    pub cancel: &'a AtomicBool,
    /// Called from worker threads as work finishes, with (samples done, samples to do), both
    /// counting only this run's work.
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
    /// Periodic copies of the film, for crash safety.
    pub checkpoint: Option<Checkpoints<'a>>,
}

impl Hooks<'static> {
    /// No stop request, no progress, no checkpoints: a render run to its end in silence
    /// (tests, and callers that want only the image).
    pub fn none() -> Self {
        static NEVER: AtomicBool = AtomicBool::new(false);
        Hooks {
            cancel: &NEVER,
            progress: &|_, _| {},
            checkpoint: None,
        }
    }
}

/// Called at most every `every` with a copy of the film (every pixel's samples so far, each
/// finished tile stored).
pub struct Checkpoints<'a> {
    /// The shortest time between two copies.
    pub every: Duration,
    /// Receives each copy.
    pub write: &'a (dyn Fn(&Film) + Sync),
}

/// Renders `scene` with `settings`, starting from `start` (a film from an earlier, stopped run
/// of the same scene and settings) or from nothing.
///
/// Setting `hooks.cancel` stops the render within one sample per thread; the film then holds
/// every sample taken so far (a pixel may be part-way), and `complete` is false.
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
    start: Option<Film>,
    hooks: &Hooks,
) -> Result<Rendered, RenderError> {
    let begin = Instant::now();
    let sppm = match settings.integrator {
        Integrator::Sppm(_) if start.is_some() => return Err(RenderError::Sppm("resumed")),
        Integrator::Sppm(_) if settings.shard.count > 1 => {
            return Err(RenderError::Sppm("split into shards"));
        }
        Integrator::Sppm(s) => Some(s),
        _ => None,
    };
    let adaptive = match settings.sampling {
        // Quadtree blocks stay inside tiles: at most the largest power of two dividing them.
        Sampling::Adaptive(a) => Some(Adaptive {
            block: a.block.min(settings.tile_size.max(1).trailing_zeros()),
            ..a
        }),
        Sampling::Uniform => None,
    };
    // An adaptive pixel is one film sample.
    let settings = &RenderSettings {
        spp: if adaptive.is_some() { 1 } else { settings.spp },
        ..*settings
    };
    let (width, height) = (scene.camera.width(), scene.camera.height());
    let film = match start {
        Some(f) => {
            let (_, most) = f.sample_range();
            if (f.width(), f.height()) != (width, height) || most > settings.spp {
                return Err(RenderError::ResumeMismatch(
                    f.width(),
                    f.height(),
                    most,
                    width,
                    height,
                    settings.spp,
                ));
            }
            f
        }
        None => Film::new(width, height),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
        .map_err(|source| RenderError::Threads {
            threads: settings.threads,
            source,
        })?;
    let threads = pool.current_num_threads();
    if let Some(sppm) = sppm {
        return Ok(pool.install(|| sppm::render_sppm(scene, settings, &sppm, hooks, begin)));
    }
    let filter = FilterSampler::new(settings.filter).map_err(RenderError::Filter)?;
    let splat = adaptive.is_none()
        && settings.filter_sampling == FilterSampling::Splat
        && settings.filter != Filter::default();
    if splat && settings.shard.count > 1 {
        return Err(RenderError::SplatShards);
    }
    let deadline = match (adaptive, settings.time_limit) {
        (None, Some(limit)) => Some(begin + limit),
        _ => None,
    };

    let work: Vec<Tile> = tiles(width, height, settings.tile_size)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| settings.shard.owns(*i))
        .map(|(_, t)| t)
        .collect();
    let missing = |t: &Tile| -> u64 {
        let mut n = 0;
        for y in t.y0..t.y1 {
            for x in t.x0..t.x1 {
                n += u64::from(settings.spp - film.samples(x, y));
            }
        }
        n
    };
    let total: u64 = work.iter().map(missing).sum();

    let film = Mutex::new(film);
    let stats = Mutex::new(RayStats::default());
    let done = AtomicU64::new(0);
    let last_checkpoint = Mutex::new(Instant::now());

    let density = Mutex::new(if adaptive.is_some() {
        vec![0u32; width as usize * height as usize]
    } else {
        Vec::new()
    });
    // Reports progress after a tile, and writes a checkpoint when one is due.
    let finished = |samples: u64| {
        (hooks.progress)(done.fetch_add(samples, Ordering::Relaxed) + samples, total);
        if let Some(c) = &hooks.checkpoint {
            // One thread at a time, only when due, and not once stopping (the caller writes
            // the final one); the copy is taken under the film's lock and written outside it.
            if let Ok(mut last) = last_checkpoint.try_lock()
                && last.elapsed() >= c.every
                && !hooks.cancel.load(Ordering::Relaxed)
            {
                let snapshot = lock(&film).clone();
                (c.write)(&snapshot);
                *last = Instant::now();
            }
        }
    };
    // Traces one tile with `trace` into its region of the film.
    let run = |tile: &Tile, trace: &dyn Fn(&Tile, &mut Film) -> (RayStats, u64)| {
        if hooks.cancel.load(Ordering::Relaxed) {
            return;
        }
        let (w, h) = (tile.x1 - tile.x0, tile.y1 - tile.y0);
        let mut part = lock(&film).region(tile.x0, tile.y0, w, h);
        let (tile_stats, samples) = trace(tile, &mut part);
        lock(&film).store_region(&part, tile.x0, tile.y0);
        *stats.lock().unwrap_or_else(|e| e.into_inner()) += tile_stats;
        finished(samples);
    };
    // Traces tile `index` of the pass, splatting, and adds it to the film in tile order.
    let commits = Mutex::new(Commits::default());
    let run_splat = |index: usize, tile: &Tile, to: (u32, Option<Instant>)| {
        if hooks.cancel.load(Ordering::Relaxed) {
            return;
        }
        let (w, h) = (tile.x1 - tile.x0, tile.y1 - tile.y0);
        let start = lock(&film).region(tile.x0, tile.y0, w, h);
        let (tile_stats, samples, splats) =
            render_tile_splats(scene, settings, tile, to, &start, hooks.cancel);
        if let Some(splats) = splats {
            let mut c = commits.lock().unwrap_or_else(|e| e.into_inner());
            c.commit(index, splats, &mut lock(&film));
        }
        *stats.lock().unwrap_or_else(|e| e.into_inner()) += tile_stats;
        finished(samples);
    };

    pool.install(|| match adaptive {
        Some(a) => {
            // Bands of tiles that share a row, top to bottom; each hands the corners of the
            // row it shares to the next.
            let mut above: Option<Band> = None;
            let mut start = 0;
            while start < work.len() {
                let (y0, y1) = (work[start].y0, work[start].y1);
                let end = start + work[start..].iter().take_while(|t| t.y1 == y1).count();
                let band = Band::new((width, height), (y0, y1), a.depth, above.take());
                let corners = BandCorners {
                    scene,
                    integrator: &settings.integrator,
                    adaptive: a,
                    band: &band,
                    beam: None,
                    instants: None,
                };
                let beams = beams_apply(settings);
                work[start..end].par_iter().for_each(|tile| {
                    run(tile, &|t, part| {
                        render_tile_adaptive(&corners, beams, t, part, &density, hooks.cancel)
                    })
                });
                above = Some(band);
                start = end;
            }
        }
        None => {
            // Passes of at most PASS_SAMPLES samples per pixel keep each work item short, so
            // that periodic checkpoints hold recent work even at very high sample counts. A
            // pixel's samples are still taken in the order of their indices.
            //
            // Against a time limit the passes start at one sample per pixel and are sized
            // from the time the earlier ones took to end near the limit, so that the image
            // stopped there is even: only the last pass may be cut short.
            let start_samples = lock(&film).sample_range().0;
            let mut upto = start_samples;
            while upto < settings.spp {
                let taken = upto - start_samples;
                let step = match deadline {
                    None => PASS_SAMPLES - upto % PASS_SAMPLES,
                    Some(d) => {
                        let now = Instant::now();
                        if now >= d && taken > 0 {
                            break;
                        }
                        if taken == 0 {
                            1
                        } else {
                            let per_sample = begin.elapsed().as_secs_f64() / f64::from(taken);
                            let fits = (d - now).as_secs_f64() / per_sample.max(1e-12);
                            (fits.floor() as u32).clamp(1, PASS_SAMPLES)
                        }
                    }
                };
                upto = settings.spp.min(upto + step);
                // The first pass is whole, however short the limit: every pixel gets a sample.
                let to = (upto, deadline.filter(|_| taken > 0));
                if splat {
                    commits.lock().unwrap_or_else(|e| e.into_inner()).new_pass();
                    work.par_iter()
                        .enumerate()
                        .for_each(|(i, tile)| run_splat(i, tile, to));
                } else {
                    work.par_iter().for_each(|tile| {
                        run(tile, &|t, part| {
                            render_tile(scene, settings, &filter, t, to, part, hooks.cancel)
                        })
                    });
                }
            }
        }
    });

    let rays = stats.into_inner().unwrap_or_else(|e| e.into_inner());
    let film = film.into_inner().unwrap_or_else(|e| e.into_inner());
    let counts = work
        .iter()
        .flat_map(|t| (t.y0..t.y1).flat_map(move |y| (t.x0..t.x1).map(move |x| (x, y))));
    let (least, most) = counts.fold((u32::MAX, 0), |(lo, hi), (x, y)| {
        let n = film.samples(x, y);
        (lo.min(n), hi.max(n))
    });
    let samples_range = if work.is_empty() {
        (settings.spp, settings.spp)
    } else {
        (least, most)
    };
    let timed_out = deadline.is_some_and(|d| Instant::now() >= d)
        && samples_range.0 < settings.spp
        && !hooks.cancel.load(Ordering::Relaxed);
    let complete = samples_range.0 == settings.spp || timed_out;
    let stats = RenderStats {
        rays,
        samples: done.load(Ordering::Relaxed),
        elapsed: begin.elapsed(),
        threads,
    };
    Ok(Rendered {
        film,
        stats,
        complete,
        timed_out,
        samples_range,
        density: density.into_inner().unwrap_or_else(|e| e.into_inner()),
    })
}

/// The film, even if a thread panicked while holding it (its data is still whole pixels).
fn lock(m: &Mutex<Film>) -> std::sync::MutexGuard<'_, Film> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// Gives every pixel of `tile` not yet in `part` its adaptive value, and records the corners
/// each used in `density`; stops between pixels when cancelled.
fn render_tile_adaptive(
    corners: &BandCorners,
    beams: bool,
    tile: &Tile,
    part: &mut Film,
    density: &Mutex<Vec<u32>>,
    cancel: &AtomicBool,
) -> (RayStats, u64) {
    // The tile's corner rays through one beam (the same values as from the roots).
    let instants = corners.scene.instants().map(Mutex::new);
    let beam = (beams && instants.is_none())
        .then(|| {
            let block = corners.adaptive.block;
            corner_beam(corners.scene, (tile.x0, tile.y0), (tile.x1, tile.y1), block)
        })
        .flatten();
    let corners = &BandCorners {
        beam: beam.as_ref(),
        instants: instants.as_ref(),
        ..*corners
    };
    let mut stats = RayStats::default();
    let mut taken = 0;
    let mut used = Vec::with_capacity(tile.pixel_count() as usize);
    let size = 1u32 << corners.adaptive.block;
    'blocks: for by in (tile.y0..tile.y1).step_by(size as usize) {
        for bx in (tile.x0..tile.x1).step_by(size as usize) {
            let (x1, y1) = ((bx + size).min(tile.x1), (by + size).min(tile.y1));
            let done =
                (by..y1).all(|y| (bx..x1).all(|x| part.samples(x - tile.x0, y - tile.y0) > 0));
            if done {
                continue;
            }
            if cancel.load(Ordering::Relaxed) {
                break 'blocks;
            }
            corners.block((bx, by), size, &mut stats, &mut |x, y, value, n| {
                let (px, py) = (x - tile.x0, y - tile.y0);
                // A block a resumed render finished in part keeps the pixels it has.
                if part.samples(px, py) == 0 {
                    part.add_sample(px, py, Some(value), 1.0);
                    used.push((x, y, n));
                    taken += 1;
                }
            });
        }
    }
    let width = corners.scene.camera.width() as usize;
    let mut density = density.lock().unwrap_or_else(|e| e.into_inner());
    for (x, y, n) in used {
        density[y as usize * width + x as usize] = n;
    }
    (stats, taken)
}

/// Adds the samples of every pixel of `tile` below index `upto` to `part` (the tile's region of
/// the film); stops between samples when cancelled, and between pixels past the deadline.
/// Returns the rays traced and the samples taken.
fn render_tile(
    scene: &Scene,
    settings: &RenderSettings,
    filter: &FilterSampler,
    tile: &Tile,
    (upto, deadline): (u32, Option<Instant>),
    part: &mut Film,
    cancel: &AtomicBool,
) -> (RayStats, u64) {
    let mut stats = RayStats::default();
    let width = u64::from(scene.camera.width());
    let beam = tile_beam(scene, settings, tile);
    // The first hits are found for many samples together, in one scene: of one instant.
    let first_hits = beam.as_ref().filter(|_| !scene.blurs());
    if let (Some(beam), Integrator::Whitted(whitted)) = (first_hits, &settings.integrator) {
        let tile_beam = TileBeam {
            beam,
            whitted,
            filter,
        };
        return render_tile_first_hits(
            scene,
            settings,
            &tile_beam,
            tile,
            (upto, deadline),
            part,
            cancel,
        );
    }
    let mut instants = scene.instants();
    let mut tracing = Tracing::new(scene, settings);
    let add = |(part, taken): &mut (&mut Film, u64),
               (px, py, weight): (u32, u32, f32),
               value: Rgb,
               stats: &mut RayStats| {
        let finite = value.is_finite() && weight.is_finite();
        stats.nonfinite += u64::from(!finite);
        part.add_sample(px, py, finite.then_some(value), weight);
        *taken += 1;
    };
    let mut out = (part, 0);
    for y in tile.y0..tile.y1 {
        for x in tile.x0..tile.x1 {
            if deadline.is_some_and(|d| Instant::now() >= d) {
                tracing.finish((scene, beam.as_ref()), (&mut stats, &mut out), &add);
                return (stats, out.1);
            }
            let pixel = u64::from(y) * width + u64::from(x);
            let (px, py) = (x - tile.x0, y - tile.y0);
            for s in out.0.samples(px, py)..upto {
                if cancel.load(Ordering::Relaxed) {
                    return (stats, out.1);
                }
                let mut sampler = Sampler::new(settings.seed, pixel, s);
                let d = draw(scene, settings, pixel, s, &mut sampler);
                let scene = at_instant(scene, &mut instants, d.time);
                let (ray, weight) = camera_ray(scene, settings, filter, (x, y), &d);
                stats.camera += 1;
                tracing.trace(
                    (scene, settings, beam.as_ref()),
                    (ray, sampler, (px, py, weight)),
                    (&mut stats, &mut out),
                    &add,
                );
            }
        }
    }
    tracing.finish((scene, beam.as_ref()), (&mut stats, &mut out), &add);
    (stats, out.1)
}

/// A tile's beam under the Whitted integrator, with what its samples need.
struct TileBeam<'a> {
    beam: &'a Beam,
    whitted: &'a crate::integrator::Whitted,
    filter: &'a FilterSampler,
}

/// Samples traced per first pass: a tile of 16×16 at 4 samples per pixel, so that the
/// pass's hits stay small however many samples a pass takes.
const FIRST_PASS: usize = 1024;

/// [`render_tile`] under the Whitted integrator with a beam: the samples in chunks, each
/// chunk's camera hits found first, in packets, with the shadow beams over them
/// ([`crate::first_hits`]), then each sample shaded per ray from its hit. The same samples,
/// values and stopping points as `render_tile`.
fn render_tile_first_hits(
    scene: &Scene,
    settings: &RenderSettings,
    tb: &TileBeam,
    tile: &Tile,
    (upto, deadline): (u32, Option<Instant>),
    part: &mut Film,
    cancel: &AtomicBool,
) -> (RayStats, u64) {
    let mut stats = RayStats::default();
    let mut taken = 0;
    let width = u64::from(scene.camera.width());
    // (pixel in the tile, first sample of its pixel, ray, film weight), in render_tile's order.
    let mut todo = Vec::new();
    for y in tile.y0..tile.y1 {
        for x in tile.x0..tile.x1 {
            let pixel = u64::from(y) * width + u64::from(x);
            let (px, py) = (x - tile.x0, y - tile.y0);
            for s in part.samples(px, py)..upto {
                let mut sampler = Sampler::new(settings.seed, pixel, s);
                let d = draw(scene, settings, pixel, s, &mut sampler);
                let (ray, weight) = camera_ray(scene, settings, tb.filter, (x, y), &d);
                let first = s == part.samples(px, py);
                todo.push(((px, py), first, ray, weight));
            }
        }
    }
    let shadows = tb.whitted.shadows;
    for chunk in todo.chunks(FIRST_PASS) {
        let rays: Vec<Ray> = chunk.iter().map(|e| e.2).collect();
        let first = crate::first_hits::first_hits(scene, tb.beam, &rays, shadows, &mut stats);
        for (&((px, py), first_of_pixel, ray, weight), hit) in chunk.iter().zip(&first.hits) {
            if first_of_pixel && deadline.is_some_and(|d| Instant::now() >= d) {
                return (stats, taken);
            }
            if cancel.load(Ordering::Relaxed) {
                return (stats, taken);
            }
            stats.camera += 1;
            let value =
                tb.whitted
                    .radiance_from_hit(scene, &first.shadows, &ray, hit.as_ref(), &mut stats);
            let finite = value.is_finite() && weight.is_finite();
            stats.nonfinite += u64::from(!finite);
            part.add_sample(px, py, finite.then_some(value), weight);
            taken += 1;
        }
    }
    (stats, taken)
}

/// Traces the samples of every pixel of `tile` from the counts in `start` (the tile's region of
/// the film) up to index `upto`, splatting them into a film of the tile and its margin; stops
/// between pixels past the deadline, and between samples when cancelled — then with no film.
fn render_tile_splats(
    scene: &Scene,
    settings: &RenderSettings,
    tile: &Tile,
    (upto, deadline): (u32, Option<Instant>),
    start: &Film,
    cancel: &AtomicBool,
) -> (RayStats, u64, Option<TileSplats>) {
    let mut stats = RayStats::default();
    let (w, h) = (tile.x1 - tile.x0, tile.y1 - tile.y0);
    let splats = TileSplats::new(tile.x0, tile.y0, w, h, &settings.filter);
    let width = u64::from(scene.camera.width());
    let beam = tile_beam(scene, settings, tile);
    let mut instants = scene.instants();
    let mut tracing = Tracing::new(scene, settings);
    let add = |(splats, taken): &mut (TileSplats, u64),
               ((x, y), at): ((u32, u32), (f32, f32)),
               value: Rgb,
               stats: &mut RayStats| {
        let finite = value.is_finite();
        stats.nonfinite += u64::from(!finite);
        splats.add(&settings.filter, (x, y), at, finite.then_some(value));
        *taken += 1;
    };
    let mut out = (splats, 0);
    for y in tile.y0..tile.y1 {
        for x in tile.x0..tile.x1 {
            if deadline.is_some_and(|d| Instant::now() >= d) {
                tracing.finish((scene, beam.as_ref()), (&mut stats, &mut out), &add);
                return (stats, out.1, Some(out.0));
            }
            let pixel = u64::from(y) * width + u64::from(x);
            for s in start.samples(x - tile.x0, y - tile.y0)..upto {
                if cancel.load(Ordering::Relaxed) {
                    // A tile cut short is not added: the image keeps whole tiles in tile order,
                    // which is what a resumed render continues from.
                    return (stats, out.1, None);
                }
                let mut sampler = Sampler::new(settings.seed, pixel, s);
                // Uniform in the pixel: the filter weighs the sample where it lands.
                let d = draw(scene, settings, pixel, s, &mut sampler);
                let scene = at_instant(scene, &mut instants, d.time);
                let (sx, sy) = (x as f32 + d.in_pixel.x, y as f32 + d.in_pixel.y);
                let ray = scene.camera.ray_through_lens(sx, sy, d.lens);
                stats.camera += 1;
                tracing.trace(
                    (scene, settings, beam.as_ref()),
                    (ray, sampler, ((x, y), (sx, sy))),
                    (&mut stats, &mut out),
                    &add,
                );
            }
        }
    }
    tracing.finish((scene, beam.as_ref()), (&mut stats, &mut out), &add);
    (stats, out.1, Some(out.0))
}

/// Whether camera rays go through beams: beams are on and the integrator is not a debug
/// view (some show the traversal's counts, which a beam changes).
fn beams_apply(settings: &RenderSettings) -> bool {
    settings.beam && !matches!(settings.integrator, Integrator::Debug(_))
}

/// The beam of `tile`'s camera rays, when beams apply ([`beams_apply`]), the camera is a
/// pinhole, and it stands still while the shutter is open.
///
/// A sample lands in `[x, x + 1)` of its pixel, or within the filter's radius of the pixel's
/// centre when the filter is importance sampled: the tile widened by the radius (at least half
/// a pixel) holds every camera ray of the tile.
fn tile_beam(scene: &Scene, settings: &RenderSettings, tile: &Tile) -> Option<Beam> {
    // A beam holds the camera rays of one place of the camera (and what stands still: the
    // moving objects are tested beside it, so they may move under it).
    if !beams_apply(settings) || (scene.blurs() && scene.camera_moves()) {
        return None;
    }
    let m = settings.filter.radius().max(0.5);
    let (x0, y0) = (tile.x0 as f32 - m, tile.y0 as f32 - m);
    let (x1, y1) = (tile.x1 as f32 + m, tile.y1 as f32 + m);
    let frustum = scene.camera.frustum((x0, y0), (x1, y1))?;
    Some(scene.beam(&frustum))
}
