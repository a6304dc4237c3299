//! Volumetric path tracing: the path tracer of [`super::path`] through participating media
//! ([`crate::medium`]), which it runs whenever a scene has media (Mitsuba's `volpath`).
//!
//! Along each segment in a medium a distance is sampled ([`crate::medium::Medium::sample_along`]: exactly in a
//! homogeneous medium, by delta tracking through a grid's density): before
//! the next surface the path scatters in the medium, by its phase function; past it the
//! surface is reached as without media. At a scattering point in a medium, direct light is
//! gathered as at a surface — a light sample weighed by the power heuristic against the phase
//! function's sample, which finds lights too — with the phase function in the BSDF's place.
//! Shadow rays carry the transmittance of every medium they cross (exact, or by ratio tracking
//! through a grid) and pass through null
//! surfaces (index-matched boundaries: cut away, `opacity = 0`), so a light inside a glass of
//! murky water is dimmed by the water, not blocked by its surface. Crossing a surface of an
//! object with media puts the path in the medium on the side it goes to.
//!
//! Depth counts scattering in media as bounces; crossing a null surface is not a bounce. A
//! scene without media never comes here: its paths are [`PathTracer::radiance`]'s, bit for bit.

use super::crossings::{self, MAX_CROSSINGS};
use super::path::Path;
use super::vertex::{Vertex, footprint_of_sample, light_sampled, light_weight, shadow_reach};
use super::{RayStats, traceable, unless_untraceable};
use crate::Rgb;
use crate::bsdf::Transport;
use crate::integrator::PathTracer;
use crate::light::EmitterSample;
use crate::medium::Interaction;
use crate::sampling::Rng;
use crate::sampling::sobol::Sampler;
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use crate::spawn::{Leaving, spawn_ray};
use glam::Vec3;
use lucent_accel::Ray;

/// Where a light sample is taken from.
enum From<'a> {
    /// A surface: shadow rays are offset off it.
    Surface(&'a SurfaceHit),
    /// A point in a medium.
    Medium(Vec3),
}

impl PathTracer {
    /// Radiance along a camera ray through a scene with media, one path; randomness from
    /// `sampler`. The camera sits in [`Scene::camera_medium`].
    pub fn radiance_through_media(
        &self,
        scene: &Scene,
        camera_ray: &Ray,
        sampler: &mut Sampler,
        stats: &mut RayStats,
    ) -> Rgb {
        let untraceable = stats.untraceable;
        let mut path = Path::new(camera_ray);
        let mut medium = scene.camera_medium();
        let mut crossings = 0;
        // The hero channel, and each channel's density of the path's distances relative to
        // the hero's, normalised to mean 1: `path.beta` holds the throughput already divided
        // by their mean (see `crate::medium`).
        let hero = ((sampler.next_1d() * 3.0) as usize).min(2);
        let mut ratio = Rgb::WHITE;
        // Tracking through grids draws as many numbers as it meets collisions.
        let mut rng = sampler.stream();
        loop {
            // The same dimensions for every segment, whichever way it goes (see `arrive`).
            let mut u_distance = sampler.defer(1);
            let u_light = sampler.defer(3);
            let u_scatter = sampler.defer(3);
            let u_rr = sampler.defer(1);

            let ray = path.ray;
            let hit = scene.intersect_from(&ray, path.from, &mut stats.traversal);
            if let Some(m) = medium {
                let end = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
                let u = u_distance.next_1d();
                match scene
                    .medium(m)
                    .sample_along((ray.origin, ray.dir), end, hero, u, &mut rng)
                {
                    Interaction::Scatter {
                        t,
                        weight,
                        ratio: r,
                    } => {
                        path.beta *= spectral_mis(&mut ratio, weight, r);
                        let at = ray.at(t);
                        if !self.scatter_in_medium(
                            scene,
                            &mut path,
                            (m, at),
                            [u_light, u_scatter, u_rr],
                            &mut rng,
                            stats,
                        ) {
                            break;
                        }
                        continue;
                    }
                    Interaction::Pass { weight, ratio: r } => {
                        path.beta *= spectral_mis(&mut ratio, weight, r)
                    }
                }
            }
            let Some(hit) = hit else {
                path.escape(scene);
                break;
            };
            if !scene.stops(&hit, &ray) {
                // A null boundary or a cut-away surface: the path goes on as it was.
                crossings += 1;
                if crossings > MAX_CROSSINGS {
                    break;
                }
                medium = scene
                    .medium_interface(hit.object)
                    .towards(hit.normal, ray.dir, medium);
                let (next, leaving) = spawn_ray(&hit, ray.dir);
                path.ray = next;
                path.from = Some(leaving);
                continue;
            }
            let footprint = footprint_of_sample(sampler.index());
            path.meet(scene, &hit, footprint);
            if path.depth > self.max_depth {
                break;
            }
            let interface = scene.medium_interface(hit.object);
            let mut v = Vertex::unresolved(ray.dir, hit);
            v.resolve(scene, footprint);
            if !v.bsdf.is_delta() {
                let mut u_light = u_light;
                let (u_pick, u) = (u_light.next_1d(), u_light.next_2d());
                if let Some(s) = scene.emitters.sample(&scene.lights, v.hit.point, u_pick, u) {
                    let (f, pdf) = v.bsdf.eval_pdf(v.wo, s.wi, Transport::Radiance);
                    let start = interface.towards(v.hit.normal, s.wi, medium);
                    let from = (From::Surface(&v.hit), start);
                    path.l += path.beta * lit(scene, from, &s, (f, pdf), &mut rng, stats);
                }
            }
            let mut u_scatter = u_scatter;
            let u = (u_scatter.next_1d(), u_scatter.next_2d());
            let b = v.bounce(u, Transport::Radiance, stats);
            if let Some(b) = &b {
                medium = interface.towards(v.hit.normal, b.ray.dir, medium);
            }
            if !self.go_on(&mut path, b, &v.hit, u_rr) {
                break;
            }
        }
        unless_untraceable(path.l, stats, untraceable)
    }

    /// A scattering event in medium `m` at `at`: direct light by a light sample, and the next
    /// direction from the phase function. Whether the path goes on.
    fn scatter_in_medium(
        &self,
        scene: &Scene,
        path: &mut Path,
        (m, at): (u32, Vec3),
        [mut u_light, mut u_phase, u_rr]: [Sampler; 3],
        rng: &mut Rng,
        stats: &mut RayStats,
    ) -> bool {
        if path.depth > self.max_depth {
            return false;
        }
        let phase = scene.medium(m).phase;
        let wo = -path.ray.dir;
        let (u_pick, u) = (u_light.next_1d(), u_light.next_2d());
        if let Some(s) = scene.emitters.sample(&scene.lights, at, u_pick, u) {
            let p = phase.eval(wo, s.wi);
            let from = (From::Medium(at), Some(m));
            path.l += path.beta * lit(scene, from, &s, (Rgb::gray(p), p), rng, stats);
        }
        let (wi, pdf) = phase.sample(wo, u_phase.next_2d());
        let ray = Ray::new(at, wi);
        if !traceable(&ray, stats) {
            return false;
        }
        stats.scattered += 1;
        // The phase function's sample weighs 1: its value is its density.
        path.ray = ray;
        path.from = None;
        path.last = Some((at, pdf));
        self.roulette(path, u_rr)
    }
}

/// The factor by which a distance sample of throughput factor `weight` and density ratios `r`
/// changes `beta / mean(ratio)`, `ratio` updated (and renormalised to mean 1).
fn spectral_mis(ratio: &mut Rgb, weight: Rgb, r: Rgb) -> Rgb {
    let next = *ratio * r;
    let mean = next.mean();
    if !(mean > 0.0 && mean.is_finite()) {
        return Rgb::BLACK;
    }
    *ratio = next / mean;
    weight / mean
}

/// The light sample `s` seen from `from`, the shadow ray starting in medium `start`, where the
/// scattering's value for it is `f` (cosine included at a surface) and its density `pdf`:
/// `f·Tr·Le / p`, weighed by the power heuristic against the scattering's own sample.
fn lit(
    scene: &Scene,
    (from, start): (From<'_>, Option<u32>),
    s: &EmitterSample,
    (f, pdf): (Rgb, f32),
    rng: &mut Rng,
    stats: &mut RayStats,
) -> Rgb {
    if f.is_black() {
        return Rgb::BLACK;
    }
    let le = light_sampled(scene, s);
    if le.is_black() {
        return Rgb::BLACK;
    }
    stats.shadow += 1;
    let (ray, leaving) = match from {
        From::Surface(hit) => {
            let (ray, leaving) = spawn_ray(hit, s.wi);
            (ray, Some(leaving))
        }
        From::Medium(p) => (Ray::new(p, s.wi), None),
    };
    if !traceable(&ray, stats) {
        return Rgb::BLACK;
    }
    let tr = transmittance(scene, (ray, leaving), shadow_reach(s), start, rng, stats);
    if tr.is_black() {
        return Rgb::BLACK;
    }
    f * le * tr * (light_weight(s, pdf, true) / s.pdf)
}

/// The share of light that travels along `ray` (leaving `from`, starting in `medium`) for a
/// distance `t_max`: the media's transmittance over each stretch (estimated with `rng`
/// through grids), through the surfaces that do not stop it; 0 when one does.
fn transmittance(
    scene: &Scene,
    (ray, from): (Ray, Option<Leaving>),
    t_max: f32,
    medium: Option<u32>,
    rng: &mut Rng,
    stats: &mut RayStats,
) -> Rgb {
    // First the cheap any-hit query, which stops at the first surface that surely blocks; only
    // a ray that meets surfaces it may cross (null boundaries, cut-outs) walks them in order.
    let mut crosses = false;
    let blocked = scene.occlusion(&ray, t_max, from, &mut stats.traversal, |m, _| {
        let m = &scene.materials[m as usize];
        let may_cross = m.opacity.is_some() || m.cull_back;
        crosses |= may_cross;
        !may_cross
    });
    if blocked {
        return Rgb::BLACK;
    }
    match (crosses, medium) {
        (false, None) => Rgb::WHITE,
        (false, Some(m)) => scene
            .medium(m)
            .transmittance_along((ray.origin, ray.dir), t_max, rng),
        (true, _) => {
            let stretch = |m, ray: &Ray, len| {
                (scene.medium(m)).transmittance_along((ray.origin, ray.dir), len, rng)
            };
            crossings::through(
                scene,
                (ray, from),
                t_max,
                medium,
                stretch,
                |_| Rgb::BLACK,
                stats,
            )
        }
    }
}
