//! Unidirectional path tracing with next-event estimation and multiple importance sampling:
//! the answer to the classic critique of Whitted ray tracing (no diffuse interreflection, no
//! area lights, no soft shadows).
//!
//! The rendering equation `L(x, ωo) = Le(x, ωo) + ∫ f(x, ωi, ωo) L(x', −ωi) |cos θi| dωi` is
//! estimated along one path per sample. At every vertex two techniques gather direct light:
//!
//! - **light sampling**: a light picked by power ([`crate::light::Emitters`]), a point on it,
//!   and a shadow ray; it adds `β·f·Le / p_light · w_light`;
//! - **BSDF sampling**: the next direction of the path; when it hits an emitter (or escapes to
//!   the environment) it adds `β·Le · w_bsdf`.
//!
//! The weights are Veach's power heuristic, `w_a = p_a² / (p_a² + p_b²)`, each density the
//! solid-angle density at the shaded point of the technique that did not find the light
//! computed by the other. Delta lights (points, spots, directions) can only be found by light
//! sampling and delta lobes (mirrors, smooth glass) only by BSDF sampling: their weight is 1.
//!
//! Depth counts as the Whitted integrator does (camera rays are depth 0, `max_depth` bounces),
//! so that a path holds at most `max_depth + 2` segments: Mitsuba's `max_depth`, less 2. The
//! vertex reached by the last bounce is lit by both techniques, as every other is: its BSDF
//! sample is traced too, only for the emission it finds. After
//! `rr_depth` bounces Russian roulette ends a path with probability `1 − q`,
//! `q = min(max channel of β, 0.95)`, and divides the survivors by `q`.
//!
//! Materials are sampled through their [`crate::bsdf::Bsdf`] in the shading frame; a sampled
//! or lit direction that the shading normal puts on the other side of the surface than the
//! geometric normal does is dropped, so smooth normals never leak light through a surface.
//! Rays that escape see the scene's environment (its background colour or image), which also
//! lights the scene; the ambient term of the classic model is not used.

use super::vertex::{Bounce, Vertex, footprint_of_sample};
use super::{RayStats, unless_untraceable};
use crate::Rgb;
use crate::bsdf::Transport;
use crate::sampling::mis::power_heuristic;
use crate::sampling::sobol::Sampler;
use crate::scene::{Beam, Scene};
use crate::shape::SurfaceHit;
use crate::spawn::Leaving;
use glam::Vec3;
use lucent_accel::Ray;

/// Settings of the path tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTracer {
    /// The deepest bounce: a path has at most `max_depth + 2` segments.
    pub max_depth: u32,
    /// Bounces before Russian roulette may end a path.
    pub rr_depth: u32,
}

impl Default for PathTracer {
    fn default() -> Self {
        Self {
            max_depth: 10,
            rr_depth: 5,
        }
    }
}

impl PathTracer {
    /// Radiance along a camera ray, one path; randomness from `sampler`.
    pub fn radiance(
        &self,
        scene: &Scene,
        camera_ray: &Ray,
        sampler: &mut Sampler,
        stats: &mut RayStats,
    ) -> Rgb {
        self.radiance_in(scene, None, camera_ray, sampler, stats)
    }

    /// [`PathTracer::radiance`] for a camera ray of `beam`, if any: its first hit is found
    /// through the beam ([`Scene::intersect_in`]), the same hit.
    pub fn radiance_in(
        &self,
        scene: &Scene,
        beam: Option<&Beam>,
        camera_ray: &Ray,
        sampler: &mut Sampler,
        stats: &mut RayStats,
    ) -> Rgb {
        if scene.has_media() {
            return self.radiance_through_media(scene, camera_ray, sampler, stats);
        }
        let untraceable = stats.untraceable;
        let mut path = Path::new(camera_ray);
        loop {
            let go_on = self.arrive(
                scene,
                beam,
                &mut path,
                sampler,
                stats,
                |path, hit, at, stats| self.scatter(scene, path, hit, at, stats),
            );
            if !go_on {
                break;
            }
        }
        // A ray of the path that could not be traced leaves its estimate incomplete: dropped.
        unless_untraceable(path.l, stats, untraceable)
    }

    /// The first half of a bounce, the same for one path and for lanes: the bounce's random
    /// numbers set aside, the next hit found, the light of what the ray meets (an emitter, or
    /// the environment when it escapes) added. Then `scatter` is called with the hit (passed
    /// on, not stored: a hit is 200 bytes) and what it returns is returned; false when the
    /// path ends here.
    #[inline(always)]
    pub(super) fn arrive(
        &self,
        scene: &Scene,
        beam: Option<&Beam>,
        path: &mut Path,
        sampler: &mut Sampler,
        stats: &mut RayStats,
        scatter: impl FnOnce(&mut Path, SurfaceHit, Arrival, &mut RayStats) -> bool,
    ) -> bool {
        // Every bounce spends the same dimensions, whichever branches it takes, so that each
        // dimension means the same decision in every sample of a pixel; the numbers are drawn
        // only where a branch uses them.
        let u_light = sampler.defer(3);
        let u_bsdf = sampler.defer(3);
        let u_rr = sampler.defer(1);

        let ray = &path.ray;
        let hit = match beam {
            Some(beam) if path.depth == 0 && !scene.has_cutouts() => {
                scene.intersect_in(beam, ray, &mut stats.traversal)
            }
            Some(beam) if path.depth == 0 => scene
                .intersect_in(beam, ray, &mut stats.traversal)
                .and_then(|h| scene.opaque_beyond(h, ray, &mut stats.traversal)),
            _ => scene.intersect_opaque(ray, path.from, &mut stats.traversal),
        };
        let Some(hit) = hit else {
            path.escape(scene);
            return false;
        };
        let footprint = footprint_of_sample(sampler.index());
        path.meet(scene, &hit, footprint);

        // The last bounce's ray was traced only for the light it finds (so that both
        // techniques of the last vertex count, as MIS assumes).
        if path.depth > self.max_depth {
            return false;
        }
        let at = Arrival {
            footprint,
            u_light,
            u_bsdf,
            u_rr,
        };
        scatter(path, hit, at, stats)
    }

    /// The second half of a bounce for one path: the material resolved at `hit`, direct light
    /// by light sampling, the next direction by BSDF sampling. Whether the path goes on.
    #[inline(always)]
    pub(super) fn scatter(
        &self,
        scene: &Scene,
        path: &mut Path,
        hit: SurfaceHit,
        at: Arrival,
        stats: &mut RayStats,
    ) -> bool {
        let mut v = Vertex::unresolved(path.ray.dir, hit);
        v.resolve(scene, at.footprint);
        if !v.bsdf.is_delta() {
            let mut u_light = at.u_light;
            let u = (u_light.next_1d(), u_light.next_2d());
            path.l += path.beta * v.direct_light(scene, u, true, stats);
        }
        let mut u_bsdf = at.u_bsdf;
        let u = (u_bsdf.next_1d(), u_bsdf.next_2d());
        let b = v.bounce(u, Transport::Radiance, stats);
        self.go_on(path, b, &v.hit, at.u_rr)
    }

    /// The last step of a bounce, the same for one path and for lanes: the path follows the
    /// bounce `b` from `hit` (none: it ends), and past `rr_depth` bounces Russian roulette, with
    /// `u_rr`, may end it. Whether it goes on.
    #[inline(always)]
    pub(super) fn go_on(
        &self,
        path: &mut Path,
        b: Option<Bounce>,
        hit: &SurfaceHit,
        u_rr: Sampler,
    ) -> bool {
        let Some(b) = b else {
            return false;
        };
        path.beta *= b.sample.weight;
        path.last = (!b.sample.delta).then_some((hit.point, b.sample.pdf));
        path.ray = b.ray;
        path.from = Some(b.from);
        self.roulette(path, u_rr)
    }

    /// Counts the bounce just taken and, past `rr_depth` bounces, plays Russian roulette with
    /// `u_rr`: whether the path goes on.
    #[inline(always)]
    pub(super) fn roulette(&self, path: &mut Path, mut u_rr: Sampler) -> bool {
        let depth = path.depth;
        path.depth += 1;
        if depth + 1 >= self.rr_depth {
            let q = path.beta.max_channel().min(0.95);
            if u_rr.next_1d() >= q || q.is_nan() {
                return false;
            }
            path.beta = path.beta / q;
        }
        true
    }
}

/// A path being traced: what its loop carries from one bounce to the next.
#[derive(Clone, Copy, Debug)]
pub(super) struct Path {
    /// The radiance gathered so far.
    pub l: Rgb,
    /// The throughput: the product of the bounces' weights.
    pub beta: Rgb,
    /// The ray to trace next.
    pub ray: Ray,
    /// The surface it leaves.
    pub from: Option<Leaving>,
    /// Where the last bounce was and the density of its BSDF sample, for weighing an emitter
    /// it hits; `None` after the camera or a delta lobe (weight 1).
    pub last: Option<(Vec3, f32)>,
    /// Bounces so far (camera rays are depth 0).
    pub depth: u32,
}

impl Path {
    /// A path starting along a camera ray.
    pub fn new(camera_ray: &Ray) -> Self {
        Self {
            l: Rgb::BLACK,
            beta: Rgb::WHITE,
            ray: *camera_ray,
            from: None,
            last: None,
            depth: 0,
        }
    }

    /// Adds the environment's light, seen by the ray that escaped the scene, weighed against
    /// the light sample of the vertex before.
    #[inline(always)]
    pub fn escape(&mut self, scene: &Scene) {
        let dir = self.ray.dir;
        let le = scene.background_along(dir);
        if !le.is_black() {
            let w = self.last.map_or(1.0, |(_, pdf)| {
                power_heuristic(pdf, scene.emitters.pdf_environment(dir))
            });
            self.l += self.beta * le * w;
        }
    }

    /// Adds the light of the surface the ray hit at `hit`, if it emits towards the ray,
    /// weighed against the light sample of the vertex before; its textures filtered over
    /// `footprint`.
    #[inline(always)]
    pub fn meet(&mut self, scene: &Scene, hit: &SurfaceHit, footprint: f32) {
        let m = &scene.materials[hit.material as usize];
        if !m.emits_towards(hit.normal, self.ray.dir) {
            return;
        }
        let w = match (self.last, scene.emitters.area_light_of(hit.object)) {
            (Some((p, pdf)), Some(light)) => power_heuristic(
                pdf,
                scene.emitters.pdf_area(light, p, hit.point, hit.normal),
            ),
            _ => 1.0,
        };
        let le = match m.emission_map {
            None => m.ke,
            Some(_) => m.emission(&scene.tex_coords(m, hit, footprint), &scene.images),
        };
        self.l += self.beta * le * w;
    }
}

/// What a path's arrival at a hit passes on besides the hit: the bounce's random numbers
/// ([`PathTracer::arrive`]).
pub(super) struct Arrival {
    /// The hit's texture footprint.
    pub footprint: f32,
    /// Light sampling's numbers (3 dimensions).
    pub u_light: Sampler,
    /// BSDF sampling's (3).
    pub u_bsdf: Sampler,
    /// Russian roulette's (1).
    pub u_rr: Sampler,
}
