//! Cut-out surfaces: where a material's opacity (glTF's alpha, Mitsuba's `mask`) is below 1,
//! a ray passes through the surface as if it were not there — camera and scattered rays, and
//! shadow rays alike, so a cut-away leaf casts no shadow where it is cut away. The back of a
//! material that culls it (glTF's single-sided materials) is cut away whole.
//!
//! Fractional opacity is a coin toss per crossing: the ray passes where a hash of the hit
//! point and the ray's direction falls at or above the opacity (pbrt-v4's `HashFloat`), so the
//! same crossing is decided the same way whichever query asks, and an image does not depend on
//! thread count or tile order. In expectation a surface of opacity `a` blocks the share `a`.

use super::Scene;
use crate::shape::SurfaceHit;
use crate::spawn::{Leaving, spawn_ray};
use crate::texture::TexCoords;
use lucent_accel::{Ray, TraversalStats};

/// The most cut-away surfaces one query passes through before it takes the next one as
/// opaque (a stack of many transparent leaves, or a loop of coplanar ones).
const MAX_CROSSINGS: u32 = 64;

/// A uniform number in `[0, 1)` from the bits of a crossing.
fn crossing_hash(hit: &SurfaceHit, ray: &Ray) -> f32 {
    let mut h: u64 = 0x9E37_79B9_7F4A_7C15;
    for v in [
        hit.point.x,
        hit.point.y,
        hit.point.z,
        ray.dir.x,
        ray.dir.y,
        ray.dir.z,
    ] {
        h ^= u64::from(v.to_bits());
        h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        h ^= h >> 31;
    }
    h = h.wrapping_mul(0x94D0_49BB_1331_11EB);
    h ^= h >> 29;
    (h >> 40) as f32 / (1u64 << 24) as f32
}

impl Scene {
    /// Whether the surface hit by `ray` at `hit` stops it: always for an opaque material;
    /// with the probability of its opacity there for a cut-out one; never from behind for a
    /// material that culls its back.
    pub fn stops(&self, hit: &SurfaceHit, ray: &Ray) -> bool {
        let m = &self.materials[hit.material as usize];
        if m.cull_back && hit.normal.dot(ray.dir) > 0.0 {
            return false;
        }
        if m.opacity.is_none() {
            return true;
        }
        let at = TexCoords {
            uv: hit.uv(),
            ..TexCoords::at(hit.texture_coords, glam::Vec2::ZERO)
        };
        let opacity = m.opacity(&at, &self.images);
        opacity >= 1.0 || (opacity > 0.0 && crossing_hash(hit, ray) < opacity)
    }

    /// The nearest surface along `ray` (leaving `from`) that stops it: [`Scene::intersect_from`]
    /// past the cut-away surfaces it crosses (`t` then counts from `ray`'s origin, up to the
    /// small offsets of the rays that go on).
    #[inline]
    pub fn intersect_opaque(
        &self,
        ray: &Ray,
        from: Option<Leaving>,
        stats: &mut TraversalStats,
    ) -> Option<SurfaceHit> {
        if !self.has_cutouts {
            // Returned as found: a 200-byte hit is not copied on its way out.
            return self.intersect_from(ray, from, stats);
        }
        let mut hit = self.intersect_from(ray, from, stats)?;
        let mut t0 = 0.0;
        for _ in 0..MAX_CROSSINGS {
            if self.stops(&hit, ray) {
                hit.t += t0;
                return Some(hit);
            }
            // Go on from the far side, with the parameter counted from the first origin.
            let (next, leaving) = spawn_ray(&hit, ray.dir);
            t0 += hit.t;
            hit = self.intersect_from(&next, Some(leaving), stats)?;
        }
        hit.t += t0;
        Some(hit)
    }

    /// Whether the scene has cut-out materials at all (without them every surface stops rays).
    pub fn has_cutouts(&self) -> bool {
        self.has_cutouts
    }

    /// `hit`, found along `ray` by a query that ignores opacity (a beam's), if it stops the
    /// ray; else the next surface beyond it that does ([`Scene::intersect_opaque`] from there,
    /// `t` counted from `ray`'s origin).
    pub fn opaque_beyond(
        &self,
        hit: SurfaceHit,
        ray: &Ray,
        stats: &mut TraversalStats,
    ) -> Option<SurfaceHit> {
        if self.stops(&hit, ray) {
            return Some(hit);
        }
        let (next, leaving) = spawn_ray(&hit, ray.dir);
        let mut beyond = self.intersect_opaque(&next, Some(leaving), stats)?;
        beyond.t += hit.t;
        Some(beyond)
    }

    /// Calls `blocker(hit)` for each surface, nearest first, that stops `ray` (leaving `from`)
    /// before `t_max`, until it returns `true`; returns whether it did. Cut-away crossings are
    /// skipped; after `MAX_CROSSINGS` surfaces the walk gives up and answers `true`. (The
    /// ordered walk of the shadow rays of integrators that weigh each blocker, where
    /// [`Scene::occlusion`] cannot see opacity.)
    pub fn stopping_surfaces<F>(
        &self,
        ray: &Ray,
        t_max: f32,
        from: Option<Leaving>,
        stats: &mut TraversalStats,
        mut blocker: F,
    ) -> bool
    where
        F: FnMut(&SurfaceHit) -> bool,
    {
        let mut ray = *ray;
        let mut from = from;
        let mut left = t_max;
        for _ in 0..MAX_CROSSINGS {
            let Some(hit) = self.intersect_from(&ray, from, stats) else {
                return false;
            };
            if hit.t >= left {
                return false;
            }
            if self.stops(&hit, &ray) && blocker(&hit) {
                return true;
            }
            left -= hit.t;
            let (next, leaving) = spawn_ray(&hit, ray.dir);
            ray = next;
            from = Some(leaving);
        }
        true
    }

    /// Whether anything stops `ray` (leaving `from`) before `t_max`: [`Scene::occlusion`],
    /// except that cut-away surfaces let it through.
    #[inline]
    pub fn blocked(
        &self,
        ray: &Ray,
        t_max: f32,
        from: Option<Leaving>,
        stats: &mut TraversalStats,
    ) -> bool {
        if !self.has_cutouts {
            return self.occlusion(ray, t_max, from, stats, |_, _| true);
        }
        self.stopping_surfaces(ray, t_max, from, stats, |_| true)
    }
}
