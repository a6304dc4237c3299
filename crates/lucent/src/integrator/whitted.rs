//! Whitted's recursive ray tracing (1980), per RGB channel:
//!
//! ```text
//! I = ka·Ia + Σ_j S_j · I_j · att_j · (kd·max(N·L, 0) + ks·max(R·V, 0)^shininess) + kr·Ir + kt·It
//! ```
//!
//! (A material may ask for POV-Ray's variants: `N·L` to the power `brilliance`, and Blinn's
//! highlight `ks·max(N·H, 0)^shininess` with `H` halfway between `L` and `V`.)
//!
//! - `N` is the unit normal turned to face the incoming ray, `V` points back along it, `L` to
//!   light `j`, `R` is `L` mirrored about `N`. A light behind the surface (`N·L ≤ 0`) adds
//!   neither diffuse nor specular light.
//! - `S_j`, the shadow term, comes from a ray to the light. An opaque blocker (`kt = 0`) makes
//!   it 0. A transmissive blocker lets light through, filtered by its `kt` once per surface the
//!   shadow ray crosses (a glass sphere: `kt²`), without bending it: the shadow of glass is
//!   lighter, but it shows no caustic. Emitting surfaces (area lights) cast no shadows.
//! - `Ir` is the colour along the mirror ray `R = I − 2(N·I)N`; `It` the colour along the
//!   refracted ray of Snell's law ([`crate::optics::refract`]), with `μ = 1/ior` entering the
//!   material and `ior` leaving it (entering when the ray meets the shape's geometric normal from
//!   outside, `N·I < 0`). On total internal reflection, `kt` joins `kr` on the mirror ray.
//! - Smooth meshes shade with their interpolated vertex normal; the triangle's own normal still
//!   decides which side a ray or a light is on, and takes over when the bent normal would send
//!   a reflected or refracted ray through the surface. A material's bump pattern
//!   ([`crate::texture::bump`], POV-Ray's `normal`) bends the normal the same way.
//! - A surface's own emission `ke` (area lights; MTL's `Ke`) is added where its front side is
//!   seen.
//! - A ray's weight is the product of the `kr` and `kt` factors on its way from the camera; a
//!   secondary ray is traced only when its weight's largest channel reaches `min_weight`, and
//!   only up to `max_depth` bounces (camera rays are depth 0), and at most
//!   [`MAX_SECONDARY_RAYS`] per camera ray.
//! - Participating media dim every ray by their transmittance and glow with the ambient light
//!   they scatter (POV-Ray's `fog`, from the media's coefficients: see `whitted_media`).

use super::record::{Cut, NoRecord, RayKind, Recorder};
use super::{RayStats, traceable, unless_untraceable};
use super::{crossings, whitted_media};
use crate::Rgb;
use crate::material::Material;
use crate::optics::{reflect, refract};
use crate::scene::{Beam, Scene};
use crate::shape::SurfaceHit;
use crate::spawn::{Leaving, spawn_ray};
use glam::Vec3;
use lucent_accel::Ray;

/// The most secondary rays (reflected and refracted) one camera ray may spawn. Glass facing
/// glass doubles the ray tree at every bounce, and with `kr + kt ≥ 1` the weight never falls
/// under `min_weight`; this bound keeps such a pixel from running for hours. Ordinary scenes
/// use a few dozen.
pub const MAX_SECONDARY_RAYS: u32 = 1 << 16;

/// Settings of the Whitted integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Whitted {
    /// The deepest bounce traced; 0 means no reflected or refracted rays.
    pub max_depth: u32,
    /// Secondary rays whose weight's largest channel falls below this are not traced.
    pub min_weight: f32,
    /// Shadow rays are traced; without them every light reaches every point facing it
    /// (`S_j = 1`), as in the lecture's picture of shading without shadows.
    pub shadows: bool,
}

impl Default for Whitted {
    fn default() -> Self {
        Self {
            max_depth: 10,
            min_weight: 1.0 / 256.0,
            shadows: true,
        }
    }
}

/// A ray being traced: where it came from, and what it has left to spend.
struct Path {
    depth: u32,
    /// Product of the `kr`/`kt` factors from the camera.
    weight: Rgb,
    /// The participating medium the ray is in (see `whitted_media`).
    medium: Option<u32>,
}

/// What one trace carries besides the ray: the scene, the budget, the counters and the
/// recorder of the ray tree.
struct Trace<'a, R> {
    scene: &'a Scene,
    /// The beam the camera ray belongs to, if any.
    beam: Option<&'a Beam>,
    /// The camera ray's hit, when the driver found it already (taken by the camera ray).
    primary: Option<Option<&'a SurfaceHit>>,
    /// Per light, the shadow beam of the camera hits' shadow rays towards it, if any.
    shadows: &'a [Option<Beam>],
    budget: u32,
    stats: &'a mut RayStats,
    record: &'a mut R,
}

impl Whitted {
    /// Radiance along a camera ray.
    pub fn radiance(&self, scene: &Scene, ray: &Ray, stats: &mut RayStats) -> Rgb {
        self.radiance_in(scene, None, ray, stats)
    }

    /// [`Whitted::radiance`] for a camera ray of `beam`, if any: the camera ray's hit is found
    /// through the beam ([`Scene::intersect_in`]), the same hit.
    pub fn radiance_in(
        &self,
        scene: &Scene,
        beam: Option<&Beam>,
        ray: &Ray,
        stats: &mut RayStats,
    ) -> Rgb {
        self.radiance_with(scene, beam, ray, stats, &mut NoRecord)
    }

    /// [`Whitted::radiance`], telling `record` every ray traced and every term added (for
    /// `lucent explain`; [`NoRecord`] costs nothing).
    pub fn radiance_recorded<R: Recorder>(
        &self,
        scene: &Scene,
        ray: &Ray,
        stats: &mut RayStats,
        record: &mut R,
    ) -> Rgb {
        self.radiance_with(scene, None, ray, stats, record)
    }

    /// [`Whitted::radiance`] for a camera ray whose hit the driver found already (`hit`, as
    /// [`Scene::intersect`] finds it; its traversal counted by the driver), with `shadows[j]`
    /// the shadow beam of light `j` over the shadow rays from this hit and its neighbours:
    /// the same value. Each shadow ray of the camera hit goes through its light's beam; one
    /// that meets more than two transmissive blockers is traced again from the roots, since
    /// the product of their `kt` factors depends on the order they are met in.
    pub fn radiance_from_hit(
        &self,
        scene: &Scene,
        shadows: &[Option<Beam>],
        ray: &Ray,
        hit: Option<&SurfaceHit>,
        stats: &mut RayStats,
    ) -> Rgb {
        let mut t = Trace {
            scene,
            beam: None,
            primary: Some(hit),
            shadows,
            budget: MAX_SECONDARY_RAYS,
            stats,
            record: &mut NoRecord,
        };
        self.trace_camera(&mut t, ray)
    }

    fn radiance_with<R: Recorder>(
        &self,
        scene: &Scene,
        beam: Option<&Beam>,
        ray: &Ray,
        stats: &mut RayStats,
        record: &mut R,
    ) -> Rgb {
        let mut t = Trace {
            scene,
            beam,
            primary: None,
            shadows: &[],
            budget: MAX_SECONDARY_RAYS,
            stats,
            record,
        };
        self.trace_camera(&mut t, ray)
    }

    /// The radiance along camera ray `ray`: NaN (dropped and counted by the drivers) when a ray
    /// it led to could not be traced.
    fn trace_camera<R: Recorder>(&self, t: &mut Trace<R>, ray: &Ray) -> Rgb {
        let untraceable = t.stats.untraceable;
        let path = Path {
            depth: 0,
            weight: Rgb::WHITE,
            medium: t.scene.camera_medium(),
        };
        let color = self.trace(t, RayKind::Camera, ray, None, &path);
        unless_untraceable(color, t.stats, untraceable)
    }

    fn trace<R: Recorder>(
        &self,
        t: &mut Trace<R>,
        kind: RayKind,
        ray: &Ray,
        from: Option<Leaving>,
        path: &Path,
    ) -> Rgb {
        t.record.begin(kind, ray, path.weight);
        if t.scene.has_media() {
            // The driver's camera hit may lie past null boundaries: walk them afresh.
            t.primary = None;
            return self.trace_through_media(t, ray, from, path);
        }
        // The driver's camera hit is borrowed, not copied, when it stops the ray (a hit is
        // ~200 bytes: its copies were a tenth of a Whitted render).
        let found;
        let hit = match (t.primary.take(), t.beam) {
            (Some(Some(h)), _) if kind == RayKind::Camera && t.scene.stops(h, ray) => Some(h),
            (Some(hit), _) if kind == RayKind::Camera => {
                found = hit.and_then(|h| t.scene.opaque_beyond(*h, ray, &mut t.stats.traversal));
                found.as_ref()
            }
            (_, Some(beam)) if kind == RayKind::Camera => {
                found = t
                    .scene
                    .intersect_in(beam, ray, &mut t.stats.traversal)
                    .and_then(|h| t.scene.opaque_beyond(h, ray, &mut t.stats.traversal));
                found.as_ref()
            }
            _ => {
                found = t.scene.intersect_opaque(ray, from, &mut t.stats.traversal);
                found.as_ref()
            }
        };
        t.record.hit(hit);
        let color = match hit {
            Some(hit) => self.shade(t, ray, hit, path),
            None => {
                let background = t.scene.background_along(ray.dir);
                t.record.local(background);
                background
            }
        };
        t.record.end(color);
        color
    }

    /// [`Self::trace`] in a scene with media: through the surfaces that do not stop the ray,
    /// the fog of every medium on the way over what it finds.
    fn trace_through_media<R: Recorder>(
        &self,
        t: &mut Trace<R>,
        ray: &Ray,
        from: Option<Leaving>,
        path: &Path,
    ) -> Rgb {
        let (stop, medium, fog) =
            whitted_media::first_stop(t.scene, *ray, from, path.medium, t.stats);
        t.record.hit(stop.as_ref().map(|(hit, _)| hit));
        let found = match &stop {
            Some((hit, ray)) => {
                let path = Path { medium, ..*path };
                self.shade(t, ray, hit, &path)
            }
            None => {
                let background = t.scene.background_along(ray.dir);
                t.record.local(background);
                background
            }
        };
        let color = fog.over(found);
        t.record.end(color);
        color
    }

    fn shade<R: Recorder>(
        &self,
        t: &mut Trace<R>,
        ray: &Ray,
        hit: &SurfaceHit,
        path: &Path,
    ) -> Rgb {
        let scene = t.scene;
        let m = &scene.materials[hit.material as usize];
        let i = ray.dir;
        let entering = hit.normal.dot(i) < 0.0;
        // The geometric normal decides sides (entering, a light behind the surface); the
        // shading normal (interpolated on smooth meshes) shapes the lighting and the bounces.
        let ng = if entering { hit.normal } else { -hit.normal };
        let n = if entering {
            hit.shading_normal
        } else {
            -hit.shading_normal
        };
        // A bump pattern bends it (lighting, reflection and refraction alike).
        let n = m.bump.as_ref().map_or(n, |b| b.bend(hit.point, n));
        let v = -i;
        let kd = scene.diffuse(m, hit);
        // The media on either side, for the rays that leave the surface.
        let interface = scene.medium_interface(hit.object);

        let mut color = scene.ambient_coefficient(m, hit) * scene.ambient;
        if (entering || m.emits_back) && m.emits() {
            color += m.emission(&scene.tex_coords(m, hit, 1.0), &scene.images);
        }
        for (j, light) in scene.lights.iter().enumerate() {
            let Some(l) = light.illuminate(hit.point) else {
                continue;
            };
            let n_dot_l = n.dot(l.to_light);
            if n_dot_l <= 0.0 || ng.dot(l.to_light) <= 0.0 {
                continue;
            }
            // Only the camera hit's shadow rays lie in the light's shadow beam.
            let beam = t.shadows.get(j).and_then(Option::as_ref);
            let beam = beam.filter(|_| path.depth == 0);
            let s = if !self.shadows {
                Rgb::WHITE
            } else if scene.has_media() {
                // Through the media and the surfaces between, the media's transmittance.
                let (ray, from) = spawn_ray(hit, l.to_light);
                let start = interface.towards(hit.normal, l.to_light, path.medium);
                t.stats.shadow += 1;
                let stretch =
                    |m, ray: &Ray, len| (scene.medium(m)).fog_along((ray.origin, ray.dir), len).0;
                let blocker = |m: u32| shadow_factor(&scene.materials[m as usize], 1);
                let ray = (ray, Some(from));
                crossings::through(scene, ray, l.distance, start, stretch, blocker, t.stats)
            } else {
                self.shadow(scene, hit, (l.to_light, l.distance), beam, t.stats)
            };
            if s.is_black() {
                t.record.light(j, s, Rgb::BLACK);
                continue;
            }
            let highlight = if m.blinn {
                let h = (l.to_light + v).normalize_or_zero();
                n.dot(h)
            } else {
                reflect(-l.to_light, n).dot(v)
            };
            let specular = m.ks * highlight.max(0.0).powf(m.shininess);
            let diffuse = if m.brilliance == 1.0 {
                n_dot_l
            } else {
                n_dot_l.powf(m.brilliance)
            };
            let term = s * l.intensity * (kd * diffuse + specular);
            t.record.light(j, s, term);
            color += term;
        }
        t.record.local(color);

        let wanted = !m.kr.is_black() || !m.kt.is_black();
        if path.depth >= self.max_depth {
            if wanted {
                t.record.cut(Cut::Depth);
            }
            return color;
        }
        let mut kr = m.kr;
        if !m.kt.is_black() {
            let mu = if entering { 1.0 / m.ior } else { m.ior };
            // A bent normal may send the ray to the wrong side: then bend by the face's.
            let bent = refract(i, n, mu).filter(|t| t.dot(ng) < 0.0);
            match bent.or_else(|| refract(i, ng, mu)) {
                Some(dir) => {
                    if let Some(mut child) = self.child(t, RayKind::Refracted, path, m.kt) {
                        t.stats.refracted += 1;
                        let dir = dir.normalize();
                        child.medium = interface.towards(hit.normal, dir, path.medium);
                        let (ray, from) = spawn_ray(hit, dir);
                        if traceable(&ray, t.stats) {
                            let it = self.trace(t, RayKind::Refracted, &ray, Some(from), &child);
                            color += m.kt * it;
                        }
                    }
                }
                // Total internal reflection: the transmitted share is reflected.
                None => {
                    t.record.cut(Cut::TotalInternalReflection);
                    kr += m.kt;
                }
            }
        }
        if !kr.is_black()
            && let Some(mut child) = self.child(t, RayKind::Reflected, path, kr)
        {
            t.stats.reflected += 1;
            let r = Some(reflect(i, n)).filter(|r| r.dot(ng) > 0.0);
            let dir = r.unwrap_or_else(|| reflect(i, ng)).normalize();
            child.medium = interface.towards(hit.normal, dir, path.medium);
            let (ray, from) = spawn_ray(hit, dir);
            if traceable(&ray, t.stats) {
                color += kr * self.trace(t, RayKind::Reflected, &ray, Some(from), &child);
            }
        }
        color
    }

    /// The path of a secondary ray weighted by `k`, if it is worth tracing and the budget
    /// allows (a ray cut is told to the recorder).
    fn child<R: Recorder>(
        &self,
        t: &mut Trace<R>,
        kind: RayKind,
        path: &Path,
        k: Rgb,
    ) -> Option<Path> {
        let weight = path.weight * k;
        if weight.max_channel() < self.min_weight {
            t.record.cut(Cut::Weight(kind, weight));
            return None;
        }
        if t.budget == 0 {
            t.record.cut(Cut::Budget(kind));
            return None;
        }
        t.budget -= 1;
        Some(Path {
            depth: path.depth + 1,
            weight,
            medium: path.medium,
        })
    }

    /// `S_j`: the share of a light that reaches the hit point, filtered by transmissive blockers
    /// (through `beam` when the shadow ray is one of its rays, see `radiance_from_hit`).
    fn shadow(
        &self,
        scene: &Scene,
        hit: &SurfaceHit,
        (to_light, distance): (Vec3, f32),
        beam: Option<&Beam>,
        stats: &mut RayStats,
    ) -> Rgb {
        stats.shadow += 1;
        let (ray, from) = spawn_ray(hit, to_light);
        if !traceable(&ray, stats) {
            return Rgb::BLACK;
        }
        if scene.has_cutouts() {
            // Cut-away crossings let the light through: the blockers one by one, in order.
            let mut s = Rgb::WHITE;
            scene.stopping_surfaces(&ray, distance, Some(from), &mut stats.traversal, |b| {
                s *= shadow_factor(&scene.materials[b.material as usize], 1);
                s.is_black()
            });
            return s;
        }
        if let Some(beam) = beam {
            // The beam meets the same blockers in another order, so only order-free answers
            // are taken from it: an opaque blocker (black, whichever comes first), or at most
            // two transmissive ones (`1·a·b = 1·b·a` exactly, float products commuting). A
            // third needs the roots' order: the shadow ray is traced again from them.
            let (mut factors, mut met) = ([Rgb::WHITE; 2], 0);
            let mut opaque = false;
            let stopped = scene.occlusion_in(
                beam,
                &ray,
                distance,
                Some(from),
                &mut stats.traversal,
                |material, crossings| {
                    let m = &scene.materials[material as usize];
                    if !m.ke.is_black() {
                        return false;
                    }
                    if m.kt.is_black() {
                        opaque = true;
                        return true;
                    }
                    let Some(f) = factors.get_mut(met) else {
                        return true;
                    };
                    *f = m.kt.powi(crossings as i32);
                    met += 1;
                    false
                },
            );
            if opaque {
                return Rgb::BLACK;
            }
            if !stopped {
                return factors[..met].iter().fold(Rgb::WHITE, |s, &f| s * f);
            }
        }
        let mut s = Rgb::WHITE;
        scene.occlusion(
            &ray,
            distance,
            Some(from),
            &mut stats.traversal,
            |material, crossings| {
                s *= shadow_factor(&scene.materials[material as usize], crossings);
                s.is_black()
            },
        );
        s
    }
}

/// What a blocker of `material`, crossed `crossings` times, lets through of a shadow ray: `kt`
/// per crossing. Emitting surfaces (area lights) cast no shadows: under this integrator their
/// light comes from a point inside them.
fn shadow_factor(material: &Material, crossings: u32) -> Rgb {
    if material.emits() {
        Rgb::WHITE
    } else {
        material.kt.powi(crossings as i32)
    }
}
