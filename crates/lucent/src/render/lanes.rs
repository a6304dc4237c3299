//! Camera samples traced one at a time, or queued and traced eight at a time in lanes
//! ([`crate::integrator::path_lanes`]) — the same values either way, handed back in the order
//! the samples were given, so a film receives the same sums in the same order.

use arrayvec::ArrayVec;
use lucent_accel::Ray;

use super::RenderSettings;
use crate::Rgb;
use crate::integrator::path_lanes::LaneMaterials;
use crate::integrator::{Integrator, PathTracer, RayStats};
use crate::lanes::LANES;
use crate::sampling::sobol::Sampler;
use crate::scene::{Beam, Scene};

/// How a tile's camera samples are traced. `T` is what the caller needs to add a sample's value
/// to its film (its pixel, its weight).
pub(super) struct Tracing<'a, T> {
    /// The path tracer and the materials its lanes shade, when samples go through lanes.
    lanes: Option<(PathTracer, LaneMaterials<'a>)>,
    pending: ArrayVec<(Ray, Sampler, T), LANES>,
}

impl<'a, T> Tracing<'a, T> {
    /// Lanes when the settings allow them ([`RenderSettings::lanes`]), the integrator is the
    /// path tracer, every sample sees the scene at one instant (no motion blur), the scene has
    /// no media, and lanes shade some of its materials; else one sample at a time.
    pub fn new(scene: &'a Scene, settings: &RenderSettings) -> Self {
        let lanes = match settings.integrator {
            Integrator::Path(tracer) if settings.lanes && !scene.blurs() && !scene.has_media() => {
                let materials = LaneMaterials::of(scene);
                materials.any().then_some((tracer, materials))
            }
            _ => None,
        };
        Self {
            lanes,
            pending: ArrayVec::new(),
        }
    }

    /// Traces the sample along `ray` with `sampler` in `scene` (the tile's, at the sample's
    /// instant) — now, or when the queue is full — and calls `add` with `out` and each traced
    /// sample's tag and value, in the order they were given.
    #[inline]
    pub fn trace<C>(
        &mut self,
        (scene, settings, beam): (&Scene, &RenderSettings, Option<&Beam>),
        (ray, mut sampler, tag): (Ray, Sampler, T),
        (stats, out): (&mut RayStats, &mut C),
        add: &impl Fn(&mut C, T, Rgb, &mut RayStats),
    ) {
        if self.lanes.is_none() {
            let value = settings
                .integrator
                .radiance_in(scene, beam, &ray, &mut sampler, stats);
            add(out, tag, value, stats);
            return;
        }
        self.pending.push((ray, sampler, tag));
        if self.pending.is_full() {
            self.finish((scene, beam), (stats, out), add);
        }
    }

    /// Traces the queued samples and hands them to `add`.
    pub fn finish<C>(
        &mut self,
        (scene, beam): (&Scene, Option<&Beam>),
        (stats, out): (&mut RayStats, &mut C),
        add: &impl Fn(&mut C, T, Rgb, &mut RayStats),
    ) {
        let Some((tracer, materials)) = &self.lanes else {
            return;
        };
        if self.pending.is_empty() {
            return;
        }
        let rays: ArrayVec<Ray, LANES> = self.pending.iter().map(|p| p.0).collect();
        let mut samplers: ArrayVec<Sampler, LANES> = self.pending.iter().map(|p| p.1).collect();
        let values = tracer.radiance_lanes(scene, materials, beam, &rays, &mut samplers, stats);
        for ((_, _, tag), value) in self.pending.drain(..).zip(values) {
            add(out, tag, value, stats);
        }
    }
}
