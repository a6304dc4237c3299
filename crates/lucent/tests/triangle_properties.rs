//! Property tests of the two ray–triangle methods.

mod common;

use common::{icosphere, mesh_scene, placed, unit_vector};
use glam::{Quat, Vec3};
use lucent::accel::{Ray, TraversalStats};
use lucent::shape::triangle::{projection, watertight};
use proptest::prelude::*;

fn point() -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(-10.0f32..10.0).prop_map(Vec3::from_array)
}

/// A triangle whose smallest angle is not tiny (well-conditioned for comparing the methods).
fn triangle() -> impl Strategy<Value = [Vec3; 3]> {
    [point(), point(), point()].prop_filter("well-shaped triangle", |&[a, b, c]| {
        let (ab, bc, ca) = ((b - a).length(), (c - b).length(), (a - c).length());
        let area2 = (b - a).cross(c - a).length();
        // area / longest edge² bounds the smallest angle away from zero.
        area2 > 0.05 * ab.max(bc).max(ca).powi(2) && ab.min(bc).min(ca) > 0.5
    })
}

/// A unit direction from two numbers.
fn direction() -> impl Strategy<Value = Vec3> {
    (0.0f32..1.0, 0.0f32..1.0).prop_map(|(u, v)| unit_vector(u, v))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 4000,
        max_global_rejects: 100_000,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Rays aimed at a point well inside a triangle: both methods hit, at the same t and weights.
    #[test]
    fn both_methods_agree_inside(tri in triangle(), w in (0.05f32..0.9, 0.0f32..1.0), dir in direction(), dist in 1.0f32..30.0) {
        // Weights of at least 0.05 each: w2 spans [0.05, 0.95 − w1].
        let w1 = w.0;
        let w2 = 0.05 + w.1 * (0.9 - w1);
        let target = w1 * tri[0] + w2 * tri[1] + (1.0 - w1 - w2) * tri[2];
        let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
        prop_assume!(dir.dot(n).abs() > 0.2); // not grazing
        let ray = Ray::new(target - dist * dir, dir);
        let a = watertight(&ray, tri, f32::INFINITY).expect("watertight hits");
        let b = projection(&ray, tri, f32::INFINITY).expect("projection hits");
        prop_assert!((a.t - dist).abs() < 1e-3 * dist.max(1.0), "t {} vs {}", a.t, dist);
        prop_assert!((a.t - b.t).abs() < 1e-3 * dist.max(1.0));
        for k in 0..3 {
            prop_assert!((a.bary[k] - b.bary[k]).abs() < 1e-3, "{:?} vs {:?}", a.bary, b.bary);
        }
        prop_assert!((a.bary[0] - w1).abs() < 1e-3 && (a.bary[1] - w2).abs() < 1e-3);
    }

    /// Rays aimed at a point clearly outside a triangle: both methods miss.
    #[test]
    fn both_methods_agree_outside(tri in triangle(), w in (-2.0f32..2.0, -2.0f32..2.0), dir in direction(), dist in 1.0f32..30.0) {
        let (w1, w2) = w;
        let w3 = 1.0 - w1 - w2;
        prop_assume!(w1.min(w2).min(w3) < -0.05);
        let target = w1 * tri[0] + w2 * tri[1] + w3 * tri[2];
        let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
        prop_assume!(dir.dot(n).abs() > 0.2);
        let ray = Ray::new(target - dist * dir, dir);
        prop_assert_eq!(watertight(&ray, tri, f32::INFINITY), None);
        prop_assert_eq!(projection(&ray, tri, f32::INFINITY), None);
    }

    /// Two coplanar triangles sharing an edge, anywhere in space: a ray aimed at any point of
    /// the shared edge hits at least one of them, from either side.
    #[test]
    fn watertight_never_lets_a_ray_through_a_shared_edge(
        quad in (prop::array::uniform2(-5.0f32..5.0), prop::array::uniform2(-5.0f32..5.0), 0.2f32..5.0, 0.2f32..5.0),
        rotation in (direction(), 0.0f32..6.3),
        offset in point(),
        s in 0.001f32..0.999,
        dir in direction(),
        dist in 0.5f32..50.0,
    ) {
        let (a2, b2, hc, hd) = quad;
        let (a2, b2) = (glam::Vec2::from_array(a2), glam::Vec2::from_array(b2));
        prop_assume!((b2 - a2).length() > 0.1);
        // C and D on opposite sides of AB, in the plane z = 0.
        let side = (b2 - a2).perp().normalize();
        let mid = (a2 + b2) / 2.0;
        let (c2, d2) = (mid + hc * side, mid - hd * side);
        let q = Quat::from_axis_angle(rotation.0, rotation.1);
        let lift = |p: glam::Vec2| q * p.extend(0.0) + offset;
        let (a, b, c, d) = (lift(a2), lift(b2), lift(c2), lift(d2));
        let n = q * Vec3::Z;
        // Not grazing: at a shallow angle, the target's rounding error (~1e-7) moves the
        // crossing point along the plane by error / sin(angle), possibly past a vertex.
        prop_assume!(dir.dot(n).abs() > 0.05);
        let target = a.lerp(b, s);
        let ray = Ray::new(target - dist * dir, dir);
        let hit = watertight(&ray, [a, b, c], f32::INFINITY).is_some()
            || watertight(&ray, [b, a, d], f32::INFINITY).is_some();
        prop_assert!(hit, "ray slipped through the shared edge at s = {}", s);
    }
}

/// Every ray from inside a closed mesh hits it (watertight test, through the scene), and
/// every ray that enters it from outside leaves it again.
#[test]
fn rays_inside_a_closed_mesh_always_hit_it() {
    for offset in [Vec3::ZERO, Vec3::new(1000.0, -500.0, 250.0)] {
        let scene = mesh_scene(placed(icosphere(2), 2.0, offset));
        let mut stats = TraversalStats::default();
        let mut rng = 12345u64;
        let mut next = || {
            rng = lucent::sampling::mix64(rng);
            lucent::sampling::to_unit_float(rng)
        };
        for _ in 0..20_000 {
            let origin = offset + 1.5 * next().cbrt() * unit_vector(next(), next());
            let ray = Ray::new(origin, unit_vector(next(), next()));
            let hit = scene.intersect(&ray, &mut stats);
            assert!(hit.is_some(), "ray from {origin} along {} escaped", ray.dir);
        }
        // Rays entering from outside, aimed at the centre: the entry point's inward ray leaves.
        for _ in 0..20_000 {
            let dir = unit_vector(next(), next());
            let ray = Ray::new(offset - 10.0 * dir + 0.5 * unit_vector(next(), next()), dir);
            let entry = scene.intersect(&ray, &mut stats).expect("enters");
            let (inside, from) = lucent::spawn::spawn_ray(&entry, dir);
            let exit = scene
                .intersect_from(&inside, Some(from), &mut stats)
                .expect("leaves again");
            assert!(exit.t > 0.5, "left after only t = {}: a self-hit", exit.t);
        }
    }
}
