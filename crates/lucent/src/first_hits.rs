//! The first pass of a tile's camera rays, for the Whitted integrator under a beam: the rays'
//! hits found eight at a time through the tile's beam ([`Scene::intersect_packet_in`]), then
//! for each point or spot light the shadow beam over the shadow rays from those hits
//! ([`Scene::shadow_beam`]); the shading that follows is per ray as ever
//! ([`crate::integrator::Whitted::radiance_from_hit`]), and gives the same values.
//!
//! Why a pass of its own: a shadow beam needs the box of its rays' origins before the first
//! of them is traced, and those are the camera hits of the whole tile.

use crate::integrator::RayStats;
use crate::light::Light;
use crate::scene::{Beam, Scene};
use crate::shape::SurfaceHit;
use crate::spawn::spawn_ray;
use lucent_accel::wide_bvh::PACKET;
use lucent_accel::{Aabb, Ray};

/// The camera hits of a tile's rays (in the order given), and each light's shadow beam.
pub(crate) struct FirstHits {
    /// Hit `i` is ray `i`'s.
    pub(crate) hits: Vec<Option<SurfaceHit>>,
    /// Per light (the scene's order): the beam of the camera hits' shadow rays towards it;
    /// `None` for a directional light, or when the light is not clear of the hits' box.
    pub(crate) shadows: Vec<Option<Beam>>,
}

/// The first pass over `rays`, all inside `beam`, counting the traversal into `stats` (the
/// camera rays themselves are counted by the caller).
pub(crate) fn first_hits(
    scene: &Scene,
    beam: &Beam,
    rays: &[Ray],
    shadows: bool,
    stats: &mut RayStats,
) -> FirstHits {
    let mut hits = Vec::with_capacity(rays.len());
    for packet in rays.chunks(PACKET) {
        let found = scene.intersect_packet_in(beam, packet, &mut stats.traversal);
        hits.extend_from_slice(&found[..packet.len()]);
    }
    let shadows = if shadows {
        scene
            .lights
            .iter()
            .map(|light| {
                let position = match light {
                    Light::Point(p) => p.position,
                    Light::Spot(s) => s.point.position,
                    Light::Directional(_) => return None,
                };
                // The origins the integrator's shadow rays will have: from each hit, towards
                // the light as the light itself says (`illuminate`), off the surface by
                // `spawn_ray`. Hits the light does not reach just widen the box.
                let origins = hits.iter().flatten().fold(Aabb::EMPTY, |b, hit| {
                    match light.illuminate(hit.point) {
                        Some(l) => {
                            let o = spawn_ray(hit, l.to_light).0.origin;
                            b.union(Aabb::new(o, o))
                        }
                        None => b,
                    }
                });
                scene.shadow_beam(position, &origins)
            })
            .collect()
    } else {
        Vec::new()
    };
    FirstHits { hits, shadows }
}
