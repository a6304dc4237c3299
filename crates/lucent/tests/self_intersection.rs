//! The self-intersection policy: secondary rays never hit the surface they leave, on spheres
//! and meshes, near and far from the origin.

mod common;

use common::{icosphere, mesh_scene, placed, sphere_scene, unit_vector};
use glam::Vec3;
use lucent::accel::{Ray, TraversalStats};
use lucent::sampling::{mix64, to_unit_float};
use lucent::scene::Scene;
use lucent::shape::Sphere;
use lucent::spawn::spawn_ray;

/// For many rays aimed at the (convex) object: rays leaving the hit point outwards hit nothing,
/// and rays leaving it inwards reach the far side, not the point they left.
fn check_convex(scene: &Scene, center: Vec3, radius: f32, rays: usize) {
    let mut stats = TraversalStats::default();
    let mut state = 99u64;
    let mut next = || {
        state = mix64(state);
        to_unit_float(state)
    };
    for _ in 0..rays {
        let dir = unit_vector(next(), next());
        let aim = center + 0.9 * radius * unit_vector(next(), next());
        let ray = Ray::new(aim - 4.0 * radius * dir, dir);
        let Some(hit) = scene.intersect(&ray, &mut stats) else {
            continue;
        };
        let n = hit.normal;
        // A mirror-like ray out, and a shadow ray towards a light outside.
        // Not grazing: at least 17° off the tangent plane, so that on a faceted mesh the inward
        // ray cannot legitimately meet a neighbouring facet right away.
        let out = unit_vector(next(), next());
        let out = if out.dot(n) < 0.0 { -out } else { out };
        let out = if out.dot(n) < 0.3 {
            (out + n).normalize()
        } else {
            out
        };
        let leaving = spawn_ray(hit.point, n, out);
        assert_eq!(
            scene.intersect(&leaving, &mut stats),
            None,
            "outgoing ray re-hit at {}",
            hit.point
        );
        assert!(
            !scene.occluded(&leaving, 10.0 * radius, &mut stats),
            "shadow acne at {}",
            hit.point
        );
        // A refracted-like ray in.
        let inward = spawn_ray(hit.point, n, -out);
        let far = scene
            .intersect(&inward, &mut stats)
            .expect("the inward ray hits the far side");
        assert!(
            far.t > 0.2 * radius,
            "inward ray re-hit its own point (t = {})",
            far.t
        );
    }
}

#[test]
fn spheres_near_and_far_from_the_origin() {
    for (center, radius) in [
        (Vec3::ZERO, 1.0),
        (Vec3::new(0.3, -0.2, 0.1), 0.01),
        (Vec3::new(1e4, 2e3, -5e3), 50.0),
        (Vec3::new(-300.0, 0.0, 100.0), 1.0),
    ] {
        check_convex(
            &sphere_scene(Sphere { center, radius }),
            center,
            radius,
            20_000,
        );
    }
}

#[test]
fn meshes_near_and_far_from_the_origin() {
    for (center, radius) in [
        (Vec3::ZERO, 1.0),
        (Vec3::new(1e4, 2e3, -5e3), 50.0),
        (Vec3::new(0.5, 0.5, 0.5), 0.02),
    ] {
        let mesh = placed(icosphere(3), radius, center);
        check_convex(&mesh_scene(mesh), center, radius, 4_000);
    }
}
