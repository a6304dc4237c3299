//! Hostile rays through the scene's own queries: origins and directions with NaN, ±Inf, zero,
//! subnormal and `f32::MAX` components against a scene of spheres, planes, a merged mesh and a
//! placed one — the sphere and plane loops, the accelerators under them, the cut-out walk, the
//! occlusion queries, and a beam's single rays and packets. None may panic, and none may
//! report a hit or a blocker; a good ray's answer is unchanged beside hostile ones.

mod common;

use glam::{Affine3A, Vec3};
use lucent::Rgb;
use lucent::camera::Camera;
use lucent::material::Material;
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::{Plane, Sphere, SurfaceHit};
use lucent_accel::wide_bvh::PACKET;
use lucent_accel::{Ray, TraversalStats};
use proptest::prelude::*;

/// A component: mostly ordinary, often one of the hostile values.
fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => -4.0f32..4.0,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        1 => Just(f32::MIN_POSITIVE / 8.0),
        1 => Just(f32::MAX),
    ]
}

fn vec3() -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(component()).prop_map(Vec3::from_array)
}

/// Whether no query should trace `ray`.
fn hostile(ray: &Ray) -> bool {
    !ray.origin.is_finite() || !ray.dir.is_finite() || ray.dir == Vec3::ZERO
}

/// Spheres, two planes, a small mesh (merged into world space) and a placed larger one, with
/// one cut-out material so that the cut-out walk runs too.
fn scene() -> Scene {
    let camera = Camera::new(Vec3::new(0.0, 0.0, 8.0), Vec3::ZERO, Vec3::Y, 60.0, 16, 16).unwrap();
    let mut b = SceneBuilder::new(camera);
    let grey = b.material(Material::diffuse(Rgb::gray(0.5)));
    let holey = b.material(Material {
        opacity: Some(lucent::texture::Texture::from(0.5)),
        ..Material::diffuse(Rgb::gray(0.5))
    });
    for (i, c) in [Vec3::new(-1.5, 0.0, 0.0), Vec3::new(1.5, 0.5, -1.0)]
        .into_iter()
        .enumerate()
    {
        let m = if i == 0 { grey } else { holey };
        b.sphere(
            Sphere {
                center: c,
                radius: 0.8,
            },
            m,
        );
    }
    b.plane(Plane::new(Vec3::new(0.0, -2.0, 0.0), Vec3::Y), grey);
    b.plane(Plane::new(Vec3::new(0.0, 0.0, -6.0), Vec3::Z), holey);
    b.mesh(common::icosphere(0), grey);
    let big = b.add_mesh(common::icosphere(3));
    b.instance(
        big,
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(1.2),
            glam::Quat::from_rotation_y(0.3),
            Vec3::new(0.0, 2.0, -2.0),
        ),
        grey,
    );
    b.build().unwrap()
}

/// A hit's identity, bit for bit.
fn key(h: &Option<SurfaceHit>) -> Option<(u32, lucent::shape::SurfaceId)> {
    h.as_ref().map(|h| (h.t.to_bits(), h.surface))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn hostile_rays_meet_nothing_in_the_scene(origin in vec3(), dir in vec3(), t_max in component()) {
        let scene = scene();
        let ray = Ray::new(origin, dir);
        let mut stats = TraversalStats::default();
        let hit = scene.intersect(&ray, &mut stats);
        let opaque = scene.intersect_opaque(&ray, None, &mut stats);
        let t_max = if t_max.is_nan() { f32::INFINITY } else { t_max.abs() };
        let occluded = scene.occluded(&ray, t_max, &mut stats);
        let blocked = scene.blocked(&ray, t_max, None, &mut stats);
        if hostile(&ray) {
            prop_assert!(hit.is_none() && opaque.is_none(), "{ray:?}: {hit:?} {opaque:?}");
            prop_assert!(!occluded && !blocked, "{ray:?}");
        }
        // Through a beam of the whole view, alone and in a packet beside a good ray.
        let Some(frustum) = scene.camera.frustum((0.0, 0.0), (16.0, 16.0)) else {
            return Ok(());
        };
        let beam = scene.beam(&frustum);
        let alone = scene.intersect_in(&beam, &ray, &mut stats);
        let good = scene.camera.ray(8.5, 8.5);
        let mut rays = vec![good; PACKET];
        rays[3] = ray;
        let mut hits = [None; PACKET];
        scene.intersect_packet_in(&beam, &rays, &mut stats, &mut hits);
        let good_alone = scene.intersect_in(&beam, &good, &mut stats);
        prop_assert_eq!(key(&hits[0]), key(&good_alone));
        if hostile(&ray) {
            prop_assert!(alone.is_none() && hits[3].is_none(), "{ray:?}: {alone:?} {:?}", hits[3]);
        }
    }
}
