//! A camera whose rays cannot be traced (a lens and focus distance so small that the
//! directions lose all precision) renders without a panic under every integrator, and its
//! samples are dropped and counted as non-finite instead of drawn as a silent image; so do
//! the samples whose later rays (shadow, reflected) cannot be traced.

mod common;

use glam::Vec3;
use lucent::Rgb;
use lucent::camera::Camera;
use lucent::integrator::{Integrator, PathTracer, RayStats, Sppm, Whitted};
use lucent::light::{Falloff, Light, PointLight};
use lucent::material::Material;
use lucent::render::RenderSettings;
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::{Plane, Sphere};

#[test]
fn a_degenerate_lens_drops_and_counts_every_sample() {
    let camera = Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 40.0, 8, 8)
        .unwrap()
        .with_lens(1e-30, 1e-30)
        .unwrap();
    let mut b = SceneBuilder::new(camera);
    let m = b.material(Material::diffuse(Rgb::gray(0.5)));
    b.sphere(
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        m,
    );
    let scene = b.build().unwrap();
    let integrators = [
        Integrator::Raycast,
        Integrator::Whitted(Whitted::default()),
        Integrator::Path(PathTracer::default()),
        Integrator::Sppm(Sppm::default()),
    ];
    for rays in renders_with_finite_pixels(&scene, &integrators) {
        assert!(rays.nonfinite > 0, "{rays:?}");
    }
}

/// A wall so far away (3·10³⁸, near `f32::MAX`) that the offset off its surface overflows: the
/// camera rays reach it, but the shadow and reflected rays from it cannot be traced. Every
/// integrator ends those paths, counts the rays as untraceable, and drops their samples, so
/// that no pixel is NaN and nothing is drawn as if the light were blocked.
#[test]
fn rays_that_overflow_at_a_far_wall_end_their_paths_and_are_counted() {
    let scene = far_wall(Material {
        kr: Rgb::gray(0.5),
        ..Material::diffuse(Rgb::gray(0.5))
    });
    let integrators = [
        Integrator::Whitted(Whitted::default()),
        Integrator::Path(PathTracer::default()),
        Integrator::Sppm(Sppm::default()),
    ];
    for rays in renders_with_finite_pixels(&scene, &integrators) {
        assert!(rays.untraceable > 0 && rays.nonfinite > 0, "{rays:?}");
    }
}

/// The far wall of the test above, Lambertian, under the path tracer: paths traced in lanes meet
/// the untraceable rays, end and are dropped as paths traced one at a time are.
#[test]
fn paths_in_lanes_drop_the_samples_of_untraceable_rays_as_single_paths_do() {
    let scene = far_wall(Material::lambertian(Rgb::gray(0.5)));
    let render = |lanes| {
        let settings = RenderSettings {
            integrator: Integrator::Path(PathTracer::default()),
            spp: 9,
            lanes,
            ..RenderSettings::default()
        };
        common::render_all(&scene, &settings)
    };
    let (alone, in_lanes) = (render(false), render(true));
    assert!(alone.stats.rays.untraceable > 0 && alone.stats.rays.nonfinite > 0);
    assert_eq!(in_lanes.stats.rays, alone.stats.rays);
    assert_eq!(in_lanes.film, alone.film);
}

/// A wall of `material` 3·10³⁸ in front of a 4 × 4 camera, lit by a point light.
fn far_wall(material: Material) -> Scene {
    let camera = Camera::new(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 40.0, 4, 4).unwrap();
    let mut b = SceneBuilder::new(camera);
    let m = b.material(material);
    b.plane(
        Plane::new(Vec3::new(0.0, 0.0, -3e38), Vec3::new(0.0, 0.0, 1.0)),
        m,
    );
    b.light(Light::Point(PointLight {
        position: Vec3::new(0.0, 1.0, 0.0),
        intensity: Rgb::WHITE,
        falloff: Falloff::None,
    }));
    b.build().unwrap()
}

/// Renders `scene` at 2 spp under each integrator, asserts that every pixel is finite, and
/// returns each render's ray counts.
fn renders_with_finite_pixels(scene: &Scene, integrators: &[Integrator]) -> Vec<RayStats> {
    let (w, h) = (scene.camera.width(), scene.camera.height());
    integrators
        .iter()
        .map(|&integrator| {
            let settings = RenderSettings {
                integrator,
                spp: 2,
                ..RenderSettings::default()
            };
            let rendered = common::render_all(scene, &settings);
            for y in 0..h {
                for x in 0..w {
                    let p = rendered.film.pixel(x, y);
                    assert!(p.is_finite(), "{integrator:?}: pixel ({x}, {y}) is {p:?}");
                }
            }
            rendered.stats.rays
        })
        .collect()
}
