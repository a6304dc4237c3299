//! A scattering vertex of a path, as the physically based integrators (the path tracer and the
//! photon mapper) see it: the BSDF at a hit in its shading frame, direct light by light
//! sampling, and the next direction by BSDF sampling — free functions they share.

use super::RayStats;
use super::path::power_heuristic;
use crate::Rgb;
use crate::bsdf::{Bsdf, BsdfSample, Frame, Transport};
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use crate::spawn::{Leaving, spawn_ray};
use glam::{Vec2, Vec3};
use lucent_accel::Ray;

/// The BSDF at a hit, turned to the side the ray arrived on.
pub struct Vertex {
    /// The surface.
    pub hit: SurfaceHit,
    /// Its BSDF there (textures evaluated).
    pub bsdf: Bsdf,
    /// The shading frame: z is the shading normal (flipped to the ray's side for two-sided
    /// reflectors).
    pub frame: Frame,
    /// The geometric normal, flipped as the frame is.
    pub ng: Vec3,
    /// The direction back along the arriving ray, in the shading frame.
    pub wo: Vec3,
    /// Whether `wo` is on the side `ng` points to.
    wo_side: bool,
}

/// Where a sampled direction leads.
pub struct Bounce {
    /// The BSDF sample (direction in the shading frame, weight, pdf, delta).
    pub sample: BsdfSample,
    /// The ray leaving the surface along it.
    pub ray: Ray,
    /// The surface left, for the self-intersection policy.
    pub from: Leaving,
    /// False when it passed through the surface.
    pub reflected: bool,
}

impl Vertex {
    /// The vertex where `ray` (travelling along `dir`) hit `hit`.
    pub fn new(scene: &Scene, dir: Vec3, hit: SurfaceHit) -> Self {
        let m = &scene.materials[hit.material as usize];
        let bsdf = m.bsdf(scene.diffuse(m, &hit));
        // A two-sided reflector scatters on whichever side the ray arrives.
        let back = hit.normal.dot(dir) > 0.0;
        let flip = back && m.two_sided && !bsdf.transmits();
        let (n, ng) = if flip {
            (-hit.shading_normal, -hit.normal)
        } else {
            (hit.shading_normal, hit.normal)
        };
        let frame = Frame::from_normal(n);
        let wo = frame.to_local(-dir);
        Self {
            wo_side: (-dir).dot(ng) > 0.0,
            hit,
            bsdf,
            frame,
            ng,
            wo,
        }
    }

    /// Whether the unit world direction `w` (away from the surface) is on the side the shading
    /// frame puts it: directions that smooth normals would leak through are refused.
    fn consistent(&self, w: Vec3, local: Vec3) -> bool {
        (w.dot(self.ng) > 0.0) == (local.z > 0.0)
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
        let wi = self.frame.to_local(s.wi);
        if !self.consistent(s.wi, wi) {
            return Rgb::BLACK;
        }
        let f = self.bsdf.eval(self.wo, wi, Transport::Radiance);
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
        let (ray, from) = spawn_ray(&self.hit, s.wi);
        // Stop short of the light's own surface.
        let t_max = if s.distance.is_finite() {
            s.distance * (1.0 - 1e-4)
        } else {
            f32::INFINITY
        };
        if scene.occlusion(&ray, t_max, Some(from), &mut stats.traversal, |_, _| true) {
            return Rgb::BLACK;
        }
        let w = if s.delta || !mis {
            1.0
        } else {
            power_heuristic(s.pdf, self.bsdf.pdf(self.wo, wi))
        };
        f * le * (w / s.pdf)
    }

    /// The next direction, drawn from the BSDF with `(u_lobe, u)`, and the ray along it (counted
    /// as reflected or refracted in `stats`); `None` when nothing scatters, or a direction would
    /// leak through the surface.
    pub fn bounce(
        &self,
        (u_lobe, u): (f32, Vec2),
        mode: Transport,
        stats: &mut RayStats,
    ) -> Option<Bounce> {
        let s = self.bsdf.sample(self.wo, u_lobe, u, mode)?;
        let wi = self.frame.to_world(s.wi);
        let reflected = (s.wi.z > 0.0) == (self.wo.z > 0.0);
        let same_side = (wi.dot(self.ng) > 0.0) == self.wo_side;
        if same_side != reflected || s.weight.is_black() {
            return None;
        }
        let (ray, from) = spawn_ray(&self.hit, wi.normalize());
        if reflected {
            stats.reflected += 1;
        } else {
            stats.refracted += 1;
        }
        Some(Bounce {
            sample: s,
            ray,
            from,
            reflected,
        })
    }

    /// `f(wo, wi)` — without the cosine — for a world direction `wi` arriving from elsewhere
    /// (a photon's reverse direction), zero where it would leak through the surface. A photon's
    /// flux per area is already irradiance, projected on the surface: its cosine is counted.
    pub fn bsdf_value(&self, wi: Vec3, mode: Transport) -> Rgb {
        let local = self.frame.to_local(wi);
        let cos = local.z.abs();
        if !self.consistent(wi, local) || cos <= 0.0 {
            return Rgb::BLACK;
        }
        self.bsdf.eval(self.wo, local, mode) / cos
    }
}
