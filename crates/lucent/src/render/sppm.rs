//! The photon mapper's progressive loop (see [`crate::integrator::sppm`]): iterations of its
//! [`Estimate`] until the sample count, the time limit or a stop request, each seeing the scene
//! at an instant of its own under a shutter; then the estimate as the film.

use super::{Hooks, RenderSettings, RenderStats, Rendered};
use crate::integrator::RayStats;
use crate::integrator::sppm::{Estimate, Sppm, iteration_time};
use crate::scene::Scene;
use std::sync::atomic::Ordering;
use std::time::Instant;

/// Renders with the photon mapper: `settings.spp` iterations (or fewer when stopped or out of
/// time); the film holds each pixel's estimate as that many samples.
pub(super) fn render_sppm(
    scene: &Scene,
    settings: &RenderSettings,
    sppm: &Sppm,
    hooks: &Hooks,
    begin: Instant,
) -> Rendered {
    let pixels = scene.camera.width() as usize * scene.camera.height() as usize;
    let mut estimate = Estimate::new(scene, sppm);
    let deadline = settings.time_limit.map(|t| begin + t);
    let mut stats = RayStats::default();
    let mut iterations = 0u32;
    let total = u64::from(settings.spp) * pixels as u64;
    while iterations < settings.spp {
        // The first iteration is whole however short the time limit.
        let out_of_time = iterations > 0 && deadline.is_some_and(|d| Instant::now() >= d);
        if hooks.cancel.load(Ordering::Relaxed) || out_of_time {
            break;
        }
        let k = iterations;
        // With a shutter, each iteration sees the scene at an instant of its own: its camera
        // and photon passes together, the instants spread evenly over the shutter in order.
        let instant = scene
            .shutter()
            .filter(|_| scene.blurs())
            .map(|shutter| scene.at_time(shutter.at(iteration_time(settings.seed, k))));
        let scene = instant.as_ref().unwrap_or(scene);
        // A stop request or the time limit ends the photon pass between chunks; a camera pass
        // takes well under a second and is not stopped.
        let stop = || {
            hooks.cancel.load(Ordering::Relaxed)
                || (k > 0 && deadline.is_some_and(|d| Instant::now() >= d))
        };
        let (whole, rays) = estimate.iterate(scene, settings.seed, sppm, k, &stop);
        stats += rays;
        // An interrupted photon pass drops the iteration (its camera rays stay counted).
        if !whole {
            break;
        }
        iterations += 1;
        let done = u64::from(iterations) * pixels as u64;
        (hooks.progress)(done, total);
    }
    let (film, nonfinite) = estimate.film(iterations);
    stats.nonfinite += nonfinite;
    let complete = iterations == settings.spp
        || (deadline.is_some_and(|d| Instant::now() >= d) && !hooks.cancel.load(Ordering::Relaxed));
    Rendered {
        film,
        stats: RenderStats {
            rays: stats,
            samples: u64::from(iterations) * pixels as u64,
            elapsed: begin.elapsed(),
            threads: rayon::current_num_threads(),
        },
        complete,
        timed_out: complete && iterations < settings.spp,
        samples_range: (iterations, iterations),
        density: Vec::new(),
    }
}
