//! The first pass of a tile's camera rays, for the Whitted integrator under a beam: the rays'
//! hits found eight at a time through the tile's beam ([`Scene::intersect_packet_in`]), then
//! for each point or spot light the shadow beam over the shadow rays from those hits
//! ([`Scene::shadow_beam`]); the shading that follows is per ray as ever
//! ([`crate::integrator::Whitted::radiance_from_hit`]), and gives the same values.
//!
//! Why a pass of its own: a shadow beam needs the box of its rays' origins before the first
//! of them is traced, and those are the camera hits of the whole tile.

use crate::integrator::RayStats;
use crate::scene::{Beam, Scene};
use crate::shape::SurfaceHit;
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
    let mut hits = vec![None; rays.len()];
    for (packet, out) in rays.chunks(PACKET).zip(hits.chunks_mut(PACKET)) {
        scene.intersect_packet_in(beam, packet, &mut stats.traversal, out);
    }
    let shadows = if shadows {
        let origins = hits.iter().flatten().fold(Aabb::EMPTY, |b, hit| {
            let m = spawn_margin(hit);
            b.union(Aabb::new(hit.point - m, hit.point + m))
        });
        scene
            .lights
            .iter()
            .map(|light| {
                light
                    .position()
                    .and_then(|p| scene.shadow_beam(p, &origins))
            })
            .collect()
    } else {
        Vec::new()
    };
    FirstHits { hits, shadows }
}

/// How far [`crate::spawn::spawn_ray`] may move a ray's origin from `hit`'s point, per axis,
/// in any direction: the error bound projected on a unit normal (at most its 1-norm), then at
/// most 256 ulps of the coordinate (under `2⁻²³ · 2 · 256 · |p|`) or `2⁻¹⁶` near zero —
/// doubled. A box of the hits widened by it holds every shadow ray's origin, whichever light
/// it heads for, without spawning them (which cost an eighth of a render).
fn spawn_margin(hit: &SurfaceHit) -> glam::Vec3 {
    let moved = hit.error.x.abs() + hit.error.y.abs() + hit.error.z.abs();
    let size = hit.point.abs().max_element() + moved;
    glam::Vec3::splat(2.0 * (moved + size * 6.2e-5 + 1.0 / 65536.0))
}
