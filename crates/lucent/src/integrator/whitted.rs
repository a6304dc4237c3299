//! Whitted's recursive ray tracing (1980), per RGB channel:
//!
//! ```text
//! I = ka·Ia + Σ_j S_j · I_j · att_j · (kd·max(N·L, 0) + ks·max(R·V, 0)^shininess) + kr·Ir + kt·It
//! ```
//!
//! - `N` is the unit normal turned to face the incoming ray, `V` points back along it, `L` to
//!   light `j`, `R` is `L` mirrored about `N`. A light behind the surface (`N·L ≤ 0`) adds
//!   neither diffuse nor specular light.
//! - `S_j`, the shadow term, comes from a ray to the light. An opaque blocker (`kt = 0`) makes
//!   it 0. A transmissive blocker lets light through, filtered by its `kt` once per surface the
//!   shadow ray crosses (a glass sphere: `kt²`), without bending it: the shadow of glass is
//!   lighter, but it shows no caustic.
//! - `Ir` is the colour along the mirror ray `R = I − 2(N·I)N`; `It` the colour along the
//!   refracted ray of Snell's law ([`crate::optics::refract`]), with `μ = 1/ior` entering the
//!   material and `ior` leaving it (entering when the ray meets the shape's geometric normal from
//!   outside, `N·I < 0`). On total internal reflection, `kt` joins `kr` on the mirror ray.
//! - A ray's weight is the product of the `kr` and `kt` factors on its way from the camera; a
//!   secondary ray is traced only when its weight's largest channel reaches `min_weight`, and
//!   only up to `max_depth` bounces (camera rays are depth 0).

use super::RayStats;
use crate::Rgb;
use crate::optics::{reflect, refract};
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use crate::spawn::spawn_ray;
use lucent_accel::Ray;

/// Settings of the Whitted integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Whitted {
    /// The deepest bounce traced; 0 means no reflected or refracted rays.
    pub max_depth: u32,
    /// Secondary rays whose weight's largest channel falls below this are not traced.
    pub min_weight: f32,
}

impl Default for Whitted {
    fn default() -> Self {
        Self {
            max_depth: 10,
            min_weight: 1.0 / 256.0,
        }
    }
}

impl Whitted {
    /// Radiance along a camera ray.
    pub fn radiance(&self, scene: &Scene, ray: &Ray, stats: &mut RayStats) -> Rgb {
        self.trace(scene, ray, 0, Rgb::WHITE, stats)
    }

    fn trace(
        &self,
        scene: &Scene,
        ray: &Ray,
        depth: u32,
        weight: Rgb,
        stats: &mut RayStats,
    ) -> Rgb {
        match scene.intersect(ray, &mut stats.traversal) {
            Some(hit) => self.shade(scene, ray, &hit, depth, weight, stats),
            None => scene.background,
        }
    }

    fn shade(
        &self,
        scene: &Scene,
        ray: &Ray,
        hit: &SurfaceHit,
        depth: u32,
        weight: Rgb,
        stats: &mut RayStats,
    ) -> Rgb {
        let m = &scene.materials[hit.material as usize];
        let i = ray.dir;
        let entering = hit.normal.dot(i) < 0.0;
        let n = if entering { hit.normal } else { -hit.normal };
        let v = -i;
        let kd = m.kd.eval(hit.texture_coords);

        let mut color = m.ka * scene.ambient;
        for light in &scene.lights {
            let Some(l) = light.illuminate(hit.point) else {
                continue;
            };
            let n_dot_l = n.dot(l.to_light);
            if n_dot_l <= 0.0 {
                continue;
            }
            let s = self.shadow(scene, hit, l.to_light, l.distance, stats);
            if s.is_black() {
                continue;
            }
            let r = reflect(-l.to_light, n);
            let specular = m.ks * r.dot(v).max(0.0).powf(m.shininess);
            color += s * l.intensity * (kd * n_dot_l + specular);
        }

        if depth >= self.max_depth {
            return color;
        }
        let mut kr = m.kr;
        if !m.kt.is_black() {
            let mu = if entering { 1.0 / m.ior } else { m.ior };
            match refract(i, n, mu) {
                Some(t) => {
                    let w = weight * m.kt;
                    if w.max_channel() >= self.min_weight {
                        stats.refracted += 1;
                        let ray = spawn_ray(hit.point, hit.normal, t.normalize());
                        color += m.kt * self.trace(scene, &ray, depth + 1, w, stats);
                    }
                }
                // Total internal reflection: the transmitted share is reflected.
                None => kr += m.kt,
            }
        }
        let w = weight * kr;
        if !kr.is_black() && w.max_channel() >= self.min_weight {
            stats.reflected += 1;
            let ray = spawn_ray(hit.point, hit.normal, reflect(i, n).normalize());
            color += kr * self.trace(scene, &ray, depth + 1, w, stats);
        }
        color
    }

    /// `S_j`: the share of a light that reaches the hit point, filtered by transmissive blockers.
    fn shadow(
        &self,
        scene: &Scene,
        hit: &SurfaceHit,
        to_light: glam::Vec3,
        distance: f32,
        stats: &mut RayStats,
    ) -> Rgb {
        stats.shadow += 1;
        let ray = spawn_ray(hit.point, hit.normal, to_light);
        let mut s = Rgb::WHITE;
        scene.occlusion(
            &ray,
            distance,
            &mut stats.traversal,
            |material, crossings| {
                s *= scene.materials[material as usize].kt.powi(crossings as i32);
                s.is_black()
            },
        );
        s
    }
}
