//! Ray casting (Appel 1968): the visible surface along each ray, and nothing more.
//!
//! The colour is the surface's flat diffuse coefficient `kd` (its texture included), with no
//! lighting; rays that hit nothing see the background.

use super::RayStats;
use crate::Rgb;
use crate::scene::{Beam, Scene};
use lucent_accel::Ray;

/// The diffuse colour of the nearest surface, or the background; `beam`: the one `ray` is
/// part of, if any (see [`Scene::intersect_in`]).
pub fn radiance(scene: &Scene, beam: Option<&Beam>, ray: &Ray, stats: &mut RayStats) -> Rgb {
    let hit = match beam {
        Some(beam) => scene.intersect_in(beam, ray, &mut stats.traversal),
        None => scene.intersect(ray, &mut stats.traversal),
    };
    match hit {
        Some(hit) => scene.diffuse(&scene.materials[hit.material as usize], &hit),
        None => scene.background_along(ray.dir),
    }
}
