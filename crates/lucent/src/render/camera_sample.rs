//! A camera sample: where in its pixel it lands, which point of the lens it passes, and — with
//! a shutter — at which instant; and the scene and camera ray at that instant.

use super::RenderSettings;
use crate::film::filter::{Filter, FilterSampler};
use crate::integrator::Integrator;
use crate::sampling::sobol::Sampler;
use crate::sampling::{hash, permute, pixel_offset, uniform};
use crate::scene::Scene;
use glam::Vec2;
use lucent_accel::Ray;

/// What a camera sample draws.
#[derive(Clone, Copy, Debug)]
pub(super) struct Draw {
    /// Uniform in `[0, 1)²` over the pixel.
    pub in_pixel: Vec2,
    /// In `[0, 1)²`, mapped onto the lens by the camera.
    pub lens: Vec2,
    /// The fraction of the way through the shutter, when the scene blurs.
    pub time: Option<f32>,
}

/// The dimension of the hash that gives the deterministic integrators' instants (2 and 3 are
/// the lens's).
const TIME_DIMENSION: u32 = 4;

/// What sample `s` of pixel `pixel` draws: from the low-discrepancy sampler for the path
/// tracer (the pixel, the lens, then the instant, each a dimension of its own), and for the
/// deterministic integrators the stratified jitter of [`pixel_offset`] (exactly as before
/// filters, lenses and shutters existed), the lens position from the hash, and the instant
/// stratified over the pixel's samples in an order of its own (so that it does not follow
/// the jitter's rows).
pub(super) fn draw(
    scene: &Scene,
    settings: &RenderSettings,
    pixel: u64,
    s: u32,
    sampler: &mut Sampler,
) -> Draw {
    if let Integrator::Path(_) = settings.integrator {
        let in_pixel = sampler.next_2d();
        // A camera without a lens has no use for a lens position: its dimensions are spent,
        // not drawn.
        let mut lens = sampler.defer(2);
        let lens = if scene.camera.has_lens() {
            lens.next_2d()
        } else {
            Vec2::ZERO
        };
        let time = scene.blurs().then(|| sampler.next_1d());
        return Draw {
            in_pixel,
            lens,
            time,
        };
    }
    let (dx, dy) = pixel_offset(settings.seed, pixel, s, settings.spp);
    // Hashed only for a lens: a pinhole's rays do not read it.
    let lens = if scene.camera.has_lens() {
        Vec2::new(
            uniform(settings.seed, pixel, s, 2),
            uniform(settings.seed, pixel, s, 3),
        )
    } else {
        Vec2::ZERO
    };
    let time = scene.blurs().then(|| {
        let n = settings.spp.max(s + 1);
        let stratum = permute(s, n, hash(settings.seed, pixel, 0, TIME_DIMENSION));
        (stratum as f32 + uniform(settings.seed, pixel, s, TIME_DIMENSION)) / n as f32
    });
    Draw {
        in_pixel: Vec2::new(dx, dy),
        lens,
        time,
    }
}

/// The scene a sample is traced in: `scene` itself, or the thread's copy from
/// [`Scene::instants`] put at the sample's instant.
pub(super) fn at_instant<'a>(
    scene: &'a Scene,
    instants: &'a mut Option<Scene>,
    time: Option<f32>,
) -> &'a Scene {
    match (instants, time, scene.shutter()) {
        (Some(copy), Some(u), Some(shutter)) => {
            copy.put_at(shutter.at(u));
            copy
        }
        _ => scene,
    }
}

/// The camera ray of a sample of pixel `(x, y)` that drew `d`, in `scene` (at the sample's
/// instant), and its film weight: mapped through the filter by importance sampling unless the
/// filter is the one-pixel box.
pub(super) fn camera_ray(
    scene: &Scene,
    settings: &RenderSettings,
    filter: &FilterSampler,
    (x, y): (u32, u32),
    d: &Draw,
) -> (Ray, f32) {
    let (x, y) = (x as f32, y as f32);
    let u = d.in_pixel;
    if settings.filter == Filter::default() {
        return (scene.camera.ray_through_lens(x + u.x, y + u.y, d.lens), 1.0);
    }
    let (offset, weight) = filter.sample(u);
    let ray = scene
        .camera
        .ray_through_lens(x + 0.5 + offset.x, y + 0.5 + offset.y, d.lens);
    (ray, weight)
}
