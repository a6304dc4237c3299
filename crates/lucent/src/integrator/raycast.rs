//! Ray casting (Appel 1968): the visible surface along each ray, and nothing more.
//!
//! The colour is the surface's flat diffuse coefficient `kd` (its texture included), with no
//! lighting; rays that hit nothing see the background.

use super::RayStats;
use crate::Rgb;
use crate::scene::Scene;
use lucent_accel::Ray;

/// The diffuse colour of the nearest surface, or the background.
pub fn radiance(scene: &Scene, ray: &Ray, stats: &mut RayStats) -> Rgb {
    match scene.intersect(ray, &mut stats.traversal) {
        Some(hit) => scene.diffuse(&scene.materials[hit.material as usize], &hit),
        None => scene.background_along(ray.dir),
    }
}
