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

use super::vertex::{Vertex, footprint_of_sample};
use super::{RayStats, unless_untraceable};
use crate::Rgb;
use crate::bsdf::Transport;
use crate::lanes::Real;
use crate::sampling::sobol::Sampler;
use crate::scene::{Beam, Scene};
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

/// The power heuristic with exponent 2 for a sample of density `a` against one of density `b`.
#[inline]
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    power_heuristic_of(a, b)
}

/// [`power_heuristic`] for any [`Real`], written once for one path and for lanes: 0 where `a`
/// is not positive or either density is NaN, 1 where `a` is infinite.
#[inline(always)]
pub fn power_heuristic_of<R: Real>(a: R, b: R) -> R {
    // As a ratio, so that squares of huge densities cannot overflow: a²/(a²+b²) = 1/(1+(b/a)²).
    let one = R::splat(1.0);
    let r = b / a;
    let w = one / (one + r * r);
    let w = R::select(a.eq(R::splat(f32::INFINITY)), one, w);
    let none = !a.gt(R::splat(0.0)) | !b.eq(b);
    R::select(none, R::splat(0.0), w)
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
        let untraceable = stats.untraceable;
        let mut l = Rgb::BLACK;
        let mut beta = Rgb::WHITE;
        let mut ray = *camera_ray;
        let mut from = None;
        // Where the last bounce was and the density of its BSDF sample, for weighing an
        // emitter it hits; `None` after the camera or a delta lobe (weight 1).
        let mut last: Option<(Vec3, f32)> = None;
        for depth in 0.. {
            // Every bounce spends the same dimensions, whichever branches it takes, so that
            // each dimension means the same decision in every sample of a pixel; the numbers
            // are drawn only where a branch uses them.
            let mut u_light = sampler.defer(3);
            let mut u_bsdf = sampler.defer(3);
            let mut u_rr = sampler.defer(1);

            let hit = match beam {
                Some(beam) if depth == 0 && !scene.has_cutouts() => {
                    scene.intersect_in(beam, &ray, &mut stats.traversal)
                }
                Some(beam) if depth == 0 => scene
                    .intersect_in(beam, &ray, &mut stats.traversal)
                    .and_then(|h| scene.opaque_beyond(h, &ray, &mut stats.traversal)),
                _ => scene.intersect_opaque(&ray, from, &mut stats.traversal),
            };
            let Some(hit) = hit else {
                let le = scene.background_along(ray.dir);
                if !le.is_black() {
                    let w = last.map_or(1.0, |(_, pdf)| {
                        power_heuristic(pdf, scene.emitters.pdf_environment(ray.dir))
                    });
                    l += beta * le * w;
                }
                break;
            };
            let footprint = footprint_of_sample(sampler.index());
            let m = &scene.materials[hit.material as usize];
            if m.emits_towards(hit.normal, ray.dir) {
                let w = match (last, scene.emitters.area_light_of(hit.object)) {
                    (Some((p, pdf)), Some(light)) => power_heuristic(
                        pdf,
                        scene.emitters.pdf_area(light, p, hit.point, hit.normal),
                    ),
                    _ => 1.0,
                };
                let le = match m.emission_map {
                    None => m.ke,
                    Some(_) => m.emission(&scene.tex_coords(m, &hit, footprint), &scene.images),
                };
                l += beta * le * w;
            }

            // The last bounce's ray was traced only for the light it finds (so that both
            // techniques of the last vertex count, as MIS assumes).
            if depth > self.max_depth {
                break;
            }
            let mut v = Vertex::unresolved(ray.dir, hit);
            v.resolve(scene, footprint);
            if !v.bsdf.is_delta() {
                let u = (u_light.next_1d(), u_light.next_2d());
                l += beta * v.direct_light(scene, u, true, stats);
            }
            let u = (u_bsdf.next_1d(), u_bsdf.next_2d());
            let Some(b) = v.bounce(u, Transport::Radiance, stats) else {
                break;
            };
            beta *= b.sample.weight;
            last = (!b.sample.delta).then_some((v.hit.point, b.sample.pdf));
            ray = b.ray;
            from = Some(b.from);

            if depth + 1 >= self.rr_depth {
                let q = beta.max_channel().min(0.95);
                if u_rr.next_1d() >= q || q.is_nan() {
                    break;
                }
                beta = beta / q;
            }
        }
        // A ray of the path that could not be traced leaves its estimate incomplete: dropped.
        unless_untraceable(l, stats, untraceable)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_power_heuristic_weights_sum_to_one() {
        for (a, b) in [(1.0, 1.0), (3.0, 0.5), (0.0, 2.0), (1e-20, 1e-20)] {
            let sum = power_heuristic(a, b) + power_heuristic(b, a);
            assert!((sum - 1.0).abs() < 1e-6, "{a}, {b}: {sum}");
        }
        assert_eq!(power_heuristic(f32::INFINITY, 1.0), 1.0);
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
    }
}
