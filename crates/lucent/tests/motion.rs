//! Scenes that move: objects and the camera at an instant, against analytic hits and static
//! scenes built with the moved placement.

mod common;

use common::{any_camera, icosphere, render_all};
use glam::{Affine3A, Quat, Vec3};
use lucent::Rgb;
use lucent::accel::{AccelKind, Ray, TraversalStats};
use lucent::camera::Camera;
use lucent::integrator::{Integrator, Whitted};
use lucent::light::{Light, PointLight};
use lucent::material::Material;
use lucent::motion::{Key, Motion, Orbit, Oscillate, Repeat};
use lucent::render::RenderSettings;
use lucent::scene::{SceneBuilder, SceneError};
use lucent::shape::{Plane, Sphere};

/// From x = 0 at t = 0 to x = 4 at t = 2.
fn slide() -> Motion {
    Motion::keyframes(
        vec![
            Key::new(0.0),
            Key::new(2.0).with_translate(Vec3::new(4.0, 0.0, 0.0)),
        ],
        Repeat::Hold,
    )
    .unwrap()
}

fn hit_t(scene: &lucent::scene::Scene, ray: &Ray) -> Option<f32> {
    scene
        .intersect(ray, &mut TraversalStats::default())
        .map(|h| h.t)
}

#[test]
fn a_moving_sphere_is_hit_where_it_is_at_each_instant() {
    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(Material::lambertian(Rgb::gray(0.5)));
    // A still sphere, so that the moving one shares the scene with a static top level.
    b.sphere(
        Sphere {
            center: Vec3::new(0.0, 10.0, 0.0),
            radius: 1.0,
        },
        m,
    );
    let moving = b.sphere(
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        m,
    );
    b.motion(moving, slide());
    let scene = b.build().unwrap();
    assert!(scene.is_animated());
    assert_eq!(scene.moving_objects(), 1);
    // A ray down the z axis through x = 2 misses the sphere at t = 0 (centre at x = 0)…
    let ray = Ray::new(Vec3::new(2.0, 0.0, -10.0), Vec3::Z);
    assert_eq!(hit_t(&scene, &ray), None);
    assert_eq!(hit_t(&scene.at_time(0.0), &ray), None);
    // …hits it at its centre line at t = 1 (centre x = 2: the near side at z = −1)…
    assert_eq!(hit_t(&scene.at_time(1.0), &ray), Some(9.0));
    // …and off-centre at t = 0.75 (centre x = 1.5, offset 0.5: chord half-length √0.75).
    let t = hit_t(&scene.at_time(0.75), &ray).unwrap();
    assert!((t - (10.0 - 0.75f32.sqrt())).abs() < 1e-5, "t = {t}");
    // The bounds follow the sphere.
    let bounds = scene.at_time(2.0).bounds();
    assert!((bounds.max.x - 5.0).abs() < 1e-6, "{bounds:?}");
    // Shadow rays see it too.
    let shadow = Ray::new(Vec3::new(4.0, 0.0, -10.0), Vec3::Z);
    let mut stats = TraversalStats::default();
    assert!(!scene.occluded(&shadow, 20.0, &mut stats));
    assert!(scene.at_time(3.0).occluded(&shadow, 20.0, &mut stats));
}

#[test]
fn a_sphere_scales_with_its_motion() {
    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(Material::lambertian(Rgb::gray(0.5)));
    let s = b.sphere(
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        m,
    );
    let grow = Motion::keyframes(
        vec![Key::new(0.0), Key::new(1.0).with_scale(Vec3::splat(3.0))],
        Repeat::Hold,
    );
    b.motion(s, grow.unwrap());
    let scene = b.build().unwrap();
    let ray = Ray::new(Vec3::new(0.0, 0.0, -10.0), Vec3::Z);
    assert_eq!(hit_t(&scene.at_time(0.5), &ray), Some(8.0));
}

/// Places `icosphere(2)` (320 triangles) twice, so that neither placement is merged into
/// world space: the moving one never is, and a static one must not be for the comparison to
/// be bit for bit.
fn instance_scene(
    first: Affine3A,
    motion: Option<Motion>,
    kind: AccelKind,
) -> lucent::scene::Scene {
    let mut b = SceneBuilder::new(any_camera());
    b.accelerator(kind);
    let m = b.material(Material::lambertian(Rgb::gray(0.5)));
    let mesh = b.add_mesh(icosphere(2));
    let id = b.instance(mesh, first, m);
    b.instance(
        mesh,
        Affine3A::from_translation(Vec3::new(0.0, -20.0, 0.0)),
        m,
    );
    if let Some(motion) = motion {
        b.motion(id, motion);
    }
    b.build().unwrap()
}

#[test]
fn a_moving_instance_is_hit_as_a_static_one_placed_there() {
    let placement = Affine3A::from_scale_rotation_translation(
        Vec3::new(1.0, 0.5, 1.5),
        Quat::from_rotation_x(0.3),
        Vec3::new(0.0, 0.0, 1.0),
    );
    let orbit = Orbit {
        center: Vec3::new(1.0, 0.0, 0.0),
        axis: Vec3::new(0.2, 1.0, 0.1),
        period: 5.0,
        phase: 0.4,
    };
    let swing = Oscillate {
        offset: Vec3::new(0.0, 0.7, 0.0),
        period: 1.3,
        phase: 0.0,
    };
    let keys = vec![
        Key::new(0.0),
        Key::new(1.0)
            .with_translate(Vec3::new(0.5, 0.0, 0.0))
            .with_rotate_degrees(Vec3::new(10.0, 60.0, -20.0))
            .with_scale(Vec3::new(1.2, 0.9, 1.0)),
    ];
    let motion = Motion::new(keys, Repeat::Bounce, Some(swing), Some(orbit)).unwrap();
    for kind in [AccelKind::Wide, AccelKind::Bvh, AccelKind::BruteForce] {
        let scene = instance_scene(placement, Some(motion.clone()), kind);
        for t in [0.0, 0.37, 1.5, 4.2] {
            let moved = scene.at_time(t);
            let fixed = instance_scene(motion.at(t) * placement, None, kind);
            assert!(!fixed.is_animated());
            let mut hits = 0;
            for i in 0..400 {
                let (x, y) = ((i % 20) as f32 * 0.25 - 2.0, (i / 20) as f32 * 0.25 - 2.5);
                let ray = Ray::new(
                    Vec3::new(x, y, -10.0),
                    Vec3::new(0.01 * x, 0.02, 1.0).normalize(),
                );
                let mut stats = TraversalStats::default();
                let a = moved.intersect(&ray, &mut stats);
                let b = fixed.intersect(&ray, &mut stats);
                assert_eq!(
                    a.map(|h| h.t.to_bits()),
                    b.map(|h| h.t.to_bits()),
                    "t = {t}"
                );
                assert_eq!(a, b);
                hits += usize::from(a.is_some());
            }
            assert!(hits > 20, "{kind}, t = {t}: only {hits} hits");
            assert_eq!(moved.bounds(), fixed.bounds());
        }
    }
}

fn camera() -> Camera {
    Camera::new(
        Vec3::new(0.0, 1.0, 6.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::Y,
        40.0,
        32,
        24,
    )
    .unwrap()
}

#[test]
fn the_camera_motion_carries_the_pinhole_rays() {
    let mut b = SceneBuilder::new(camera());
    let orbit = Orbit {
        center: Vec3::new(0.0, 1.0, 0.0),
        axis: Vec3::Y,
        period: 20.0,
        phase: 0.0,
    };
    b.camera_motion(Motion::new(vec![], Repeat::Hold, None, Some(orbit)).unwrap());
    let scene = b.build().unwrap();
    assert!(scene.is_animated() && scene.camera_moves());
    assert_eq!(scene.moving_objects(), 0);
    // A quarter period is a quarter turn: the eye from +z to +x, looking along −x.
    let c = scene.at_time(5.0).camera;
    let ray = c.ray(16.0, 12.0);
    assert!(
        (ray.origin - Vec3::new(6.0, 1.0, 0.0)).length() < 1e-5,
        "{}",
        ray.origin
    );
    assert!((ray.dir - -Vec3::X).length() < 1e-5, "{}", ray.dir);
    assert!((c.fov_degrees() - 40.0).abs() < 1e-3);
    // The instant is absolute: at_time of an instant is that of the scene built.
    assert_eq!(
        scene.at_time(5.0).at_time(1.0).camera,
        scene.at_time(1.0).camera
    );
    assert_eq!(scene.at_time(20.0).camera.eye(), scene.camera.eye());
}

fn lit_scene(motion: bool) -> lucent::scene::Scene {
    let mut b = SceneBuilder::new(camera());
    b.background(Rgb::new(0.1, 0.2, 0.4))
        .ambient(Rgb::gray(0.1));
    let floor = b.material(Material::lambertian(Rgb::gray(0.6)));
    let red = b.material(Material::lambertian(Rgb::new(0.8, 0.1, 0.1)));
    b.plane(Plane::new(Vec3::ZERO, Vec3::Y), floor);
    for x in [-1.5, 0.0, 1.5] {
        b.sphere(
            Sphere {
                center: Vec3::new(x, 0.6, 0.0),
                radius: 0.6,
            },
            red,
        );
    }
    b.light(Light::Point(PointLight {
        position: Vec3::new(2.0, 5.0, 4.0),
        intensity: Rgb::WHITE,
        falloff: Default::default(),
    }));
    if motion {
        // Keys that stand still: a static motion, applied once.
        let still = Motion::keyframes(vec![Key::new(0.0), Key::new(1.0)], Repeat::Loop);
        b.motion(1, still.unwrap());
    }
    b.build().unwrap()
}

#[test]
fn a_static_scene_at_any_time_renders_as_the_scene() {
    let scene = lit_scene(false);
    assert!(!scene.is_animated());
    let settings = RenderSettings {
        integrator: Integrator::Whitted(Whitted::default()),
        ..RenderSettings::default()
    };
    let image = render_all(&scene, &settings).film.to_linear_rgb();
    for t in [0.0, 3.5, -2.0] {
        let later = render_all(&scene.at_time(t), &settings)
            .film
            .to_linear_rgb();
        assert_eq!(image, later, "t = {t}");
    }
    let still = lit_scene(true);
    assert!(!still.is_animated());
    assert_eq!(render_all(&still, &settings).film.to_linear_rgb(), image);
}

#[test]
fn what_cannot_move_is_refused() {
    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(Material::lambertian(Rgb::gray(0.5)));
    let plane = b.plane(Plane::new(Vec3::ZERO, Vec3::Y), m);
    b.motion(plane, slide());
    assert_eq!(b.build().unwrap_err(), SceneError::PlaneCannotMove(plane));

    let mut b = SceneBuilder::new(any_camera());
    let lamp = b.material(Material {
        ke: Rgb::WHITE,
        ..Material::default()
    });
    let s = b.sphere(
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        lamp,
    );
    b.motion(s, slide());
    let e = b.build().unwrap_err();
    assert_eq!(e, SceneError::EmitterCannotMove(s));
    assert!(e.to_string().contains("emits light"), "{e}");

    let mut b = SceneBuilder::new(any_camera());
    b.material(Material::default());
    b.motion(3, slide());
    assert!(matches!(
        b.build(),
        Err(SceneError::NoSuchObject { object: 3, .. })
    ));

    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(Material::default());
    let s = b.sphere(
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        m,
    );
    let squash = Motion::keyframes(
        vec![Key::new(0.0).with_scale(Vec3::new(1.0, 2.0, 1.0))],
        Repeat::Hold,
    );
    b.motion(s, squash.unwrap());
    assert_eq!(b.build().unwrap_err(), SceneError::SphereScaleNotUniform(s));
}

#[test]
fn clones_and_instants_share_the_heavy_parts() {
    let scene = instance_scene(Affine3A::IDENTITY, Some(slide()), AccelKind::Wide);
    let later = scene.at_time(1.0);
    assert!(std::sync::Arc::ptr_eq(&scene.images, &later.images));
    assert!(std::sync::Arc::ptr_eq(&scene.emitters, &later.emitters));
    assert_eq!(scene.counts(), later.counts());
}
