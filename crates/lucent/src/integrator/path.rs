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

use super::RayStats;
use crate::Rgb;
use crate::bsdf::{Frame, Transport};
use crate::sampling::sobol::Sampler;
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use crate::spawn::spawn_ray;
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
    let (a2, b2) = (a * a, b * b);
    if a2.is_infinite() {
        return 1.0;
    }
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
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
        let mut l = Rgb::BLACK;
        let mut beta = Rgb::WHITE;
        let mut ray = *camera_ray;
        let mut from = None;
        // Where the last bounce was and the density of its BSDF sample, for weighing an
        // emitter it hits; `None` after the camera or a delta lobe (weight 1).
        let mut last: Option<(Vec3, f32)> = None;
        for depth in 0.. {
            // Every bounce draws the same dimensions, whichever branches it takes, so that
            // each dimension means the same decision in every sample of a pixel.
            let u_light = (sampler.next_1d(), sampler.next_2d());
            let u_bsdf = (sampler.next_1d(), sampler.next_2d());
            let u_rr = sampler.next_1d();

            let Some(hit) = scene.intersect_from(&ray, from, &mut stats.traversal) else {
                let le = scene.background_along(ray.dir);
                if !le.is_black() {
                    let w = last.map_or(1.0, |(_, pdf)| {
                        power_heuristic(pdf, scene.emitters.pdf_environment(ray.dir))
                    });
                    l += beta * le * w;
                }
                break;
            };
            let m = &scene.materials[hit.material as usize];
            if !m.ke.is_black() && hit.normal.dot(ray.dir) < 0.0 {
                let w = match (last, scene.emitters.area_light_of(hit.object)) {
                    (Some((p, pdf)), Some(light)) => power_heuristic(
                        pdf,
                        scene.emitters.pdf_area(light, p, hit.point, hit.normal),
                    ),
                    _ => 1.0,
                };
                l += beta * m.ke * w;
            }

            // The last bounce's ray was traced only for the light it finds (so that both
            // techniques of the last vertex count, as MIS assumes).
            if depth > self.max_depth {
                break;
            }
            let bsdf = m.bsdf(scene.diffuse(m, &hit));
            // A two-sided reflector scatters on whichever side the ray arrives.
            let back = hit.normal.dot(ray.dir) > 0.0;
            let flip = back && m.two_sided && !bsdf.transmits();
            let (n, ng) = if flip {
                (-hit.shading_normal, -hit.normal)
            } else {
                (hit.shading_normal, hit.normal)
            };
            let frame = Frame::from_normal(n);
            let wo_world = -ray.dir;
            let wo = frame.to_local(wo_world);
            let wo_side = wo_world.dot(ng) > 0.0;

            if !bsdf.is_delta() {
                l += beta * self.light(scene, &hit, &bsdf, &frame, ng, wo, u_light, stats);
            }
            let Some(s) = bsdf.sample(wo, u_bsdf.0, u_bsdf.1, Transport::Radiance) else {
                break;
            };
            let wi = frame.to_world(s.wi);
            let reflected = (s.wi.z > 0.0) == (wo.z > 0.0);
            let same_side = (wi.dot(ng) > 0.0) == wo_side;
            if same_side != reflected || s.weight.is_black() {
                break;
            }
            if reflected {
                stats.reflected += 1;
            } else {
                stats.refracted += 1;
            }
            beta *= s.weight;
            last = (!s.delta).then_some((hit.point, s.pdf));
            let (next, leaving) = spawn_ray(&hit, wi.normalize());
            ray = next;
            from = Some(leaving);

            if depth + 1 >= self.rr_depth {
                let q = beta.max_channel().min(0.95);
                if u_rr >= q || q.is_nan() {
                    break;
                }
                beta = beta / q;
            }
        }
        l
    }

    /// Direct light at `hit` by light sampling, MIS-weighted against the BSDF: `f·Le·w / p`.
    #[allow(clippy::too_many_arguments)]
    fn light(
        &self,
        scene: &Scene,
        hit: &SurfaceHit,
        bsdf: &crate::bsdf::Bsdf,
        frame: &Frame,
        ng: Vec3,
        wo: Vec3,
        (u_pick, u): (f32, glam::Vec2),
        stats: &mut RayStats,
    ) -> Rgb {
        let Some(s) = scene.emitters.sample(&scene.lights, hit.point, u_pick, u) else {
            return Rgb::BLACK;
        };
        let wi = frame.to_local(s.wi);
        // The light must be on the side of the surface the shading frame says it is.
        if (s.wi.dot(ng) > 0.0) != (wi.z > 0.0) {
            return Rgb::BLACK;
        }
        let f = bsdf.eval(wo, wi, Transport::Radiance);
        if f.is_black() {
            return Rgb::BLACK;
        }
        let le = if s.distance.is_infinite() && !s.delta {
            scene.background_along(s.wi)
        } else {
            s.radiance
        };
        if le.is_black() {
            return Rgb::BLACK;
        }
        stats.shadow += 1;
        let (ray, from) = spawn_ray(hit, s.wi);
        // Stop short of the light's own surface.
        let t_max = if s.distance.is_finite() {
            s.distance * (1.0 - 1e-4)
        } else {
            f32::INFINITY
        };
        if scene.occlusion(&ray, t_max, Some(from), &mut stats.traversal, |_, _| true) {
            return Rgb::BLACK;
        }
        let w = if s.delta {
            1.0
        } else {
            power_heuristic(s.pdf, bsdf.pdf(wo, wi))
        };
        f * le * (w / s.pdf)
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
