//! A camera whose rays cannot be traced (a lens and focus distance so small that the
//! directions lose all precision) renders without a panic under every integrator, and its
//! samples are dropped and counted as non-finite instead of drawn as a silent image.

mod common;

use glam::Vec3;
use lucent::Rgb;
use lucent::camera::Camera;
use lucent::integrator::{Integrator, PathTracer, Sppm, Whitted};
use lucent::material::Material;
use lucent::render::RenderSettings;
use lucent::scene::SceneBuilder;
use lucent::shape::Sphere;

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
    for integrator in [
        Integrator::Raycast,
        Integrator::Whitted(Whitted::default()),
        Integrator::Path(PathTracer::default()),
        Integrator::Sppm(Sppm::default()),
    ] {
        let settings = RenderSettings {
            integrator,
            spp: 2,
            ..RenderSettings::default()
        };
        let rendered = common::render_all(&scene, &settings);
        let rays = rendered.stats.rays;
        assert!(rays.nonfinite > 0, "{:?}: {rays:?}", settings.integrator);
        for y in 0..8 {
            for x in 0..8 {
                assert!(rendered.film.pixel(x, y).is_finite(), "pixel ({x}, {y})");
            }
        }
    }
}
