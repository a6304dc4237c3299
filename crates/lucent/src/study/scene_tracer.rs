//! The study's tracer for a real scene: each instant's snapshot, its camera, the integrator.

use super::frameless::Tracer;
use crate::Rgb;
use crate::integrator::{Integrator, RayStats};
use crate::scene::Scene;
use crate::schedule::frameless::{Snapshots, trace_sample};
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// Traces pixels of an animated scene with a deterministic integrator.
#[derive(Debug)]
pub struct SceneTracer {
    snapshots: Snapshots,
    size: (u32, u32),
    integrator: Integrator,
    seed: u64,
    rays: AtomicU64,
}

impl SceneTracer {
    /// Traces `scene` (at its camera's resolution) with `integrator`, which must be
    /// deterministic: the ideal image is one sample per pixel, and a mode's sample of a pixel
    /// at an instant must agree with it. Instants are resolved to `step` seconds.
    pub fn new(scene: Arc<Scene>, integrator: Integrator, seed: u64, step: f64) -> Self {
        let size = (scene.camera.width(), scene.camera.height());
        Self {
            snapshots: Snapshots::new(scene, step),
            size,
            integrator,
            seed,
            rays: AtomicU64::new(0),
        }
    }

    /// Rays traced so far.
    pub fn rays(&self) -> u64 {
        self.rays.load(Ordering::Relaxed)
    }
}

impl Tracer for SceneTracer {
    fn size(&self) -> (u32, u32) {
        self.size
    }

    fn trace(&self, time: f64, pixels: &[u32], out: &mut [Rgb]) {
        let scene = self.snapshots.at(time);
        let rays: u64 = pixels
            .par_iter()
            .zip(out.par_iter_mut())
            .with_min_len(64)
            .map(|(&p, o)| {
                let mut stats = RayStats::default();
                *o = trace_sample(
                    &scene,
                    &scene.camera,
                    &self.integrator,
                    p,
                    0,
                    self.seed,
                    &mut stats,
                );
                stats.total()
            })
            .sum();
        self.rays.fetch_add(rays, Ordering::Relaxed);
    }
}
