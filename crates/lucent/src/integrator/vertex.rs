//! A scattering vertex of a path, as the physically based integrators (the path tracer and the
//! photon mapper) see it: the material resolved at a hit ([`Scattering`]), direct light by
//! light sampling, and the next direction by BSDF sampling — free functions they share.

use super::{RayStats, traceable};
use crate::Rgb;
use crate::bsdf::Transport;
use crate::light::EmitterSample;
use crate::material::{Geometry, Scattering, ScatteringSample};
use crate::sampling::mis::power_heuristic;
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use crate::spawn::{Leaving, spawn_ray};
use glam::{Vec2, Vec3};
use lucent_accel::Ray;

/// The material at a hit, resolved for the ray that arrived.
pub struct Vertex<'a> {
    /// The surface.
    pub hit: SurfaceHit,
    /// Its scattering there (textures evaluated, frames set).
    pub bsdf: Scattering<'a>,
    /// The unit direction back along the arriving ray (world space).
    pub wo: Vec3,
}

/// Where a sampled direction leads.
pub struct Bounce {
    /// The sample (world direction, weight, pdf, delta).
    pub sample: ScatteringSample,
    /// The ray leaving the surface along it.
    pub ray: Ray,
    /// The surface left, for the self-intersection policy.
    pub from: Leaving,
    /// False when it passed through the surface.
    pub reflected: bool,
}

/// The texture footprint of sample `index` of a pixel: the camera's one-pixel footprint
/// narrowed as samples accumulate, `max(1/8, 1/√(index + 1))` (pbrt-v4 narrows it by the
/// samples per pixel; by the index, every sample count and time limit gets the same samples).
pub fn footprint_of_sample(index: u32) -> f32 {
    (1.0 / ((index as f32) + 1.0).sqrt()).max(0.125)
}

impl<'a> Vertex<'a> {
    /// The vertex where `ray` (travelling along `dir`) hit `hit`, its textures filtered over
    /// `footprint` times the camera's pixel footprint.
    pub fn new(scene: &'a Scene, dir: Vec3, hit: SurfaceHit, footprint: f32) -> Self {
        let mut v = Self::unresolved(dir, hit);
        v.resolve(scene, footprint);
        v
    }

    /// The vertex with nothing scattering yet: [`Vertex::resolve`] it where it is to stay. (A
    /// vertex is most of a kilobyte; the path tracer builds it in place rather than moving a
    /// resolved one.)
    #[inline(always)]
    pub fn unresolved(dir: Vec3, hit: SurfaceHit) -> Self {
        Self {
            hit,
            bsdf: Scattering::empty(),
            wo: -dir,
        }
    }

    /// Resolves the material of the hit, as [`Vertex::new`] does.
    #[inline(always)]
    pub fn resolve(&mut self, scene: &'a Scene, footprint: f32) {
        let m = &scene.materials[self.hit.material as usize];
        let at = scene.tex_coords(m, &self.hit, footprint);
        let geometry = Geometry::of_hit(&self.hit);
        self.bsdf
            .resolve(m, geometry, self.hit.normal, &at, &scene.images, -self.wo);
    }

    /// Direct light by one light sample: `f·Le / p`, weighted by the power heuristic against
    /// BSDF sampling when `mis` (the path tracer, whose BSDF samples find lights too), or not
    /// (the photon mapper, whose camera paths end here).
    pub fn direct_light(
        &self,
        scene: &Scene,
        (u_pick, u): (f32, Vec2),
        mis: bool,
        stats: &mut RayStats,
    ) -> Rgb {
        let Some(s) = scene
            .emitters
            .sample(&scene.lights, self.hit.point, u_pick, u)
        else {
            return Rgb::BLACK;
        };
        let (f, bsdf_pdf) = self.bsdf.eval_pdf(self.wo, s.wi, Transport::Radiance);
        light_through(scene, &self.hit, &s, (f, bsdf_pdf), mis, stats)
    }

    /// The next direction, drawn from the BSDF with `(u_lobe, u)`, and the ray along it (counted
    /// as reflected or refracted in `stats`); `None` when nothing scatters, or a direction would
    /// leak through the surface.
    #[inline(always)]
    pub fn bounce(
        &self,
        (u_lobe, u): (f32, Vec2),
        mode: Transport,
        stats: &mut RayStats,
    ) -> Option<Bounce> {
        let s = self.bsdf.sample(self.wo, u_lobe, u, mode)?;
        leave(&self.hit, s, stats)
    }

    /// `f(wo, wi)` — without the cosine — for a world direction `wi` arriving from elsewhere
    /// (a photon's reverse direction), zero where it would leak through the surface. A photon's
    /// flux per area is already irradiance, projected on the surface: its cosine is counted.
    pub fn bsdf_value(&self, wi: Vec3, mode: Transport) -> Rgb {
        let f = self.bsdf.eval(self.wo, wi, mode);
        if f.is_black() {
            return f;
        }
        // Each part's cosine is its own frame's; divide by the shading cosine of the first,
        // which the others share unless a blend mixes normal maps.
        let cos = self
            .bsdf
            .parts()
            .first()
            .map_or(0.0, |p| p.frame.n.dot(wi).abs());
        if cos <= 0.0 { Rgb::BLACK } else { f / cos }
    }
}

/// The light sample `s` at `hit`, where the BSDF's value for it is `f` (cosine included) and
/// its density `bsdf_pdf`: `f·Le / p` if nothing blocks the shadow ray, weighted by the power
/// heuristic against BSDF sampling when `mis`. The part of [`Vertex::direct_light`] after the
/// BSDF, which the lane path tracer shares.
#[inline]
pub fn light_through(
    scene: &Scene,
    hit: &SurfaceHit,
    s: &EmitterSample,
    (f, bsdf_pdf): (Rgb, f32),
    mis: bool,
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
    let (ray, from) = spawn_ray(hit, s.wi);
    if !traceable(&ray, stats) {
        return Rgb::BLACK;
    }
    if scene.blocked(&ray, shadow_reach(s), Some(from), &mut stats.traversal) {
        return Rgb::BLACK;
    }
    f * le * (light_weight(s, bsdf_pdf, mis) / s.pdf)
}

/// The radiance the light sample `s` sends: its own, or for a sample of the environment, the
/// environment's along it.
#[inline]
pub fn light_sampled(scene: &Scene, s: &EmitterSample) -> Rgb {
    if s.distance.is_infinite() && !s.delta {
        scene.background_along(s.wi)
    } else {
        s.radiance
    }
}

/// How far a shadow ray towards the light sample `s` goes: short of the light's own surface.
#[inline]
pub fn shadow_reach(s: &EmitterSample) -> f32 {
    if s.distance.is_finite() {
        s.distance * (1.0 - 1e-4)
    } else {
        f32::INFINITY
    }
}

/// The light sample `s`'s weight against the scattering's own sample of density `pdf`: the
/// power heuristic when `mis`, 1 for delta lights or without.
#[inline]
pub fn light_weight(s: &EmitterSample, pdf: f32, mis: bool) -> f32 {
    if s.delta || !mis {
        1.0
    } else {
        power_heuristic(s.pdf, pdf)
    }
}

/// The ray leaving `hit` along the scattered sample `s` (counted as reflected or refracted in
/// `stats`); `None` when it carries nothing or cannot be traced. The part of
/// [`Vertex::bounce`] after the BSDF, which the lane path tracer shares.
#[inline(always)]
pub fn leave(hit: &SurfaceHit, s: ScatteringSample, stats: &mut RayStats) -> Option<Bounce> {
    if s.weight.is_black() {
        return None;
    }
    let (ray, from) = spawn_ray(hit, s.wi);
    if !traceable(&ray, stats) {
        return None;
    }
    if s.reflected {
        stats.reflected += 1;
    } else {
        stats.refracted += 1;
    }
    Some(Bounce {
        sample: s,
        ray,
        from,
        reflected: s.reflected,
    })
}
