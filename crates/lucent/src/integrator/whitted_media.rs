//! Participating media under Whitted's ray tracer: fog that dims with distance, as POV-Ray's
//! `fog` does, from the media's own coefficients.
//!
//! Along each stretch of length `d` a ray (camera, reflected, refracted or shadow) spends in a
//! medium, what lies beyond is seen through the medium's transmittance `Tr = exp(−σt·d)` (by
//! quadrature through a grid: no noise), and the medium itself glows with the light it
//! scatters of the scene's ambient light `Ia`: `σs/σt·(1 − Tr)·Ia`, the integral of
//! `Tr(t)·σs·Ia` over the stretch — the local model's ambient term, applied to the medium.
//! So a ray that escapes through endless fog sees `albedo·Ia`, POV-Ray's fog colour. What the
//! medium scatters of the lights themselves (god rays) and of other surfaces is not gathered:
//! that is the path tracer's work. Rays cross null surfaces (index-matched boundaries) and
//! change medium where they cross an object with media, as under the path tracer.

use super::RayStats;
use super::crossings::MAX_CROSSINGS;
use crate::Rgb;
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use crate::spawn::{Leaving, spawn_ray};
use lucent_accel::Ray;

/// What the media along a ray do to what it finds: `seen = tr·found + glow`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Fog {
    /// The transmittance so far.
    pub tr: Rgb,
    /// The light the media scatter towards the ray's origin.
    pub glow: Rgb,
}

impl Fog {
    const CLEAR: Fog = Fog {
        tr: Rgb::WHITE,
        glow: Rgb::BLACK,
    };

    /// Adds a stretch of length `len` along `ray` in `medium`.
    fn cross(&mut self, scene: &Scene, medium: Option<u32>, ray: &Ray, len: f32) {
        let Some(m) = medium else {
            return;
        };
        let (tr, scattered) = scene.medium(m).fog_along((ray.origin, ray.dir), len);
        self.glow += self.tr * scattered * scene.ambient;
        self.tr *= tr;
    }

    /// What is seen through the fog of `found`.
    pub fn over(&self, found: Rgb) -> Rgb {
        self.tr * found + self.glow
    }
}

/// The first surface along `ray` (leaving `from`, starting in `medium`) that stops it, the ray
/// that reaches it, the medium it is met in, and the fog on the way; `None` for a ray that
/// escapes (its fog over the whole way) or crosses too many surfaces.
pub(super) fn first_stop(
    scene: &Scene,
    mut ray: Ray,
    mut from: Option<Leaving>,
    mut medium: Option<u32>,
    stats: &mut RayStats,
) -> (Option<(SurfaceHit, Ray)>, Option<u32>, Fog) {
    let mut fog = Fog::CLEAR;
    for _ in 0..MAX_CROSSINGS {
        let hit = scene.intersect_from(&ray, from, &mut stats.traversal);
        fog.cross(
            scene,
            medium,
            &ray,
            hit.as_ref().map_or(f32::INFINITY, |h| h.t),
        );
        let Some(hit) = hit else {
            return (None, medium, fog);
        };
        if scene.stops(&hit, &ray) {
            return (Some((hit, ray)), medium, fog);
        }
        medium = scene
            .medium_interface(hit.object)
            .towards(hit.normal, ray.dir, medium);
        let (next, leaving) = spawn_ray(&hit, ray.dir);
        ray = next;
        from = Some(leaving);
    }
    (
        None,
        medium,
        Fog {
            tr: Rgb::BLACK,
            glow: fog.glow,
        },
    )
}
