//! Rays through participating media and the surfaces between them: the walk both the
//! volumetric path tracer's and Whitted's shadow rays take.

use super::RayStats;
use crate::Rgb;
use crate::scene::Scene;
use crate::spawn::{Leaving, spawn_ray};
use lucent_accel::Ray;

/// The most surfaces a path or a shadow ray crosses without scattering (null boundaries,
/// cut-outs, glass under Whitted) before it is ended: a loop of coplanar boundaries cannot
/// hold it forever.
pub(super) const MAX_CROSSINGS: u32 = 256;

/// What reaches the end of `ray` (leaving `from`, starting in `medium`) at `distance`: the
/// product of `stretch(m, ray, length)` over each stretch spent in a medium `m` and of
/// `stopper(material)` at each surface that stops rays, nearest first; rays cross the others
/// (changing medium where their objects bound media). Black after [`MAX_CROSSINGS`] surfaces.
pub(super) fn through(
    scene: &Scene,
    (mut ray, mut from): (Ray, Option<Leaving>),
    mut distance: f32,
    mut medium: Option<u32>,
    mut stretch: impl FnMut(u32, &Ray, f32) -> Rgb,
    stopper: impl Fn(u32) -> Rgb,
    stats: &mut RayStats,
) -> Rgb {
    let mut s = Rgb::WHITE;
    for _ in 0..MAX_CROSSINGS {
        let hit = scene
            .intersect_from(&ray, from, &mut stats.traversal)
            .filter(|h| h.t < distance);
        if let Some(m) = medium {
            s *= stretch(m, &ray, hit.as_ref().map_or(distance, |h| h.t));
        }
        let Some(hit) = hit else {
            return s;
        };
        if scene.stops(&hit, &ray) {
            s *= stopper(hit.material);
        }
        if s.is_black() {
            return s;
        }
        medium = scene
            .medium_interface(hit.object)
            .towards(hit.normal, ray.dir, medium);
        distance -= hit.t;
        let (next, leaving) = spawn_ray(&hit, ray.dir);
        ray = next;
        from = Some(leaving);
    }
    Rgb::BLACK
}
