//! Ray casting (Appel 1968): the visible surface along each ray, and nothing more.
//!
//! The colour is the surface's flat diffuse coefficient `kd` (its texture included), with no
//! lighting; rays that hit nothing see the background. Cut-away surfaces (opacity) are seen
//! through, as by every integrator.

use super::RayStats;
use crate::Rgb;
use crate::scene::{Beam, Scene};
use lucent_accel::Ray;

/// The diffuse colour of the nearest surface, or the background; `beam`: the one `ray` is
/// part of, if any (see [`Scene::intersect_in`]).
pub fn radiance(scene: &Scene, beam: Option<&Beam>, ray: &Ray, stats: &mut RayStats) -> Rgb {
    let hit = match beam {
        Some(beam) => scene
            .intersect_in(beam, ray, &mut stats.traversal)
            .and_then(|h| scene.opaque_beyond(h, ray, &mut stats.traversal)),
        None => scene.intersect_opaque(ray, None, &mut stats.traversal),
    };
    match hit {
        Some(hit) => scene.diffuse(&scene.materials[hit.material as usize], &hit),
        None => scene.background_along(ray.dir),
    }
}
