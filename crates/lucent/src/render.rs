//! The render driver: threads, progress, cancellation and statistics.
//!
//! Tiles from the schedule are traced in parallel on a rayon pool of the requested size. Each
//! sample's position comes from [`crate::sampling`], a pure function of (seed, pixel, sample),
//! so the image is the same for any number of threads and any tile order.

use crate::film::Film;
use crate::integrator::{Integrator, RayStats};
use crate::sampling::pixel_offset;
use crate::scene::Scene;
use crate::schedule::{Tile, tiles};
use rayon::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};
use thiserror::Error;

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
    /// Side of the square tiles handed to threads, in pixels.
    pub tile_size: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            integrator: Integrator::default(),
            spp: 1,
            seed: 0,
            threads: 0,
            tile_size: 16,
        }
    }
}

/// What a render did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Rays by kind, and accelerator work.
    pub rays: RayStats,
    /// Samples taken (camera rays).
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
    /// The image's sums and weights.
    pub film: Film,
    /// What it cost.
    pub stats: RenderStats,
    /// False when cancelled before every pixel got its samples.
    pub complete: bool,
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
}

/// Renders `scene` with `settings`.
///
/// `progress(done, total)` is called from worker threads as pixels finish. Setting `cancel`
/// stops the render within one pixel per thread; the film then holds every pixel
/// finished so far, and `complete` is false.
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Rendered, RenderError> {
    let start = Instant::now();
    let (width, height) = (scene.camera.width(), scene.camera.height());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
        .map_err(|source| RenderError::Threads {
            threads: settings.threads,
            source,
        })?;
    let threads = pool.current_num_threads();
    let film = Mutex::new(Film::new(width, height));
    let stats = Mutex::new(RayStats::default());
    let total = u64::from(width) * u64::from(height);
    let done = AtomicU64::new(0);

    pool.install(|| {
        tiles(width, height, settings.tile_size)
            .par_iter()
            .for_each(|tile| {
                if cancel.load(Ordering::Relaxed) {
                    return;
                }
                let (tile_film, tile_stats, pixels) = render_tile(scene, settings, tile, cancel);
                let mut f = film.lock().unwrap_or_else(|e| e.into_inner());
                f.merge_region(&tile_film, tile.x0, tile.y0);
                drop(f);
                *stats.lock().unwrap_or_else(|e| e.into_inner()) += tile_stats;
                progress(done.fetch_add(pixels, Ordering::Relaxed) + pixels, total);
            });
    });

    let rays = stats.into_inner().unwrap_or_else(|e| e.into_inner());
    let film = film.into_inner().unwrap_or_else(|e| e.into_inner());
    let complete = done.load(Ordering::Relaxed) == total;
    let stats = RenderStats {
        rays,
        samples: rays.camera,
        elapsed: start.elapsed(),
        threads,
    };
    Ok(Rendered {
        film,
        stats,
        complete,
    })
}

/// Traces every sample of `tile` into a film of the tile's size; stops between pixels when
/// cancelled. Returns the film, the rays traced and the pixels finished.
fn render_tile(
    scene: &Scene,
    settings: &RenderSettings,
    tile: &Tile,
    cancel: &AtomicBool,
) -> (Film, RayStats, u64) {
    let mut film = Film::new(tile.x1 - tile.x0, tile.y1 - tile.y0);
    let mut stats = RayStats::default();
    let mut pixels = 0;
    let width = u64::from(scene.camera.width());
    'rows: for y in tile.y0..tile.y1 {
        for x in tile.x0..tile.x1 {
            if cancel.load(Ordering::Relaxed) {
                break 'rows;
            }
            let pixel = u64::from(y) * width + u64::from(x);
            for s in 0..settings.spp {
                let (dx, dy) = pixel_offset(settings.seed, pixel, s, settings.spp);
                let ray = scene.camera.ray(x as f32 + dx, y as f32 + dy);
                stats.camera += 1;
                let value = settings.integrator.radiance(scene, &ray, &mut stats);
                if value.is_finite() {
                    film.add(x - tile.x0, y - tile.y0, value, 1.0);
                } else {
                    stats.nonfinite += 1;
                }
            }
            pixels += 1;
        }
    }
    (film, stats, pixels)
}
