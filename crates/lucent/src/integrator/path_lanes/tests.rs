//! Lanes against one path at a time, bit for bit.

use super::*;
use crate::bsdf::Distribution;
use crate::camera::Camera;
use crate::light::Light;
use crate::light::point::{Falloff, PointLight};
use crate::material::{Material, Roughness, Surface};
use crate::scene::SceneBuilder;
use crate::shape::{Mesh, Sphere};
use crate::texture::Texture;
use glam::Vec3;

/// An open box of Lambertian walls (one two-sided, one seen from behind through the open
/// side), a Lambertian ball, a metal one, a glass one, a rough metal one (GGX, anisotropic,
/// its roughness a texture), a rough glass one (GGX), a plastic one (its base a texture) and a
/// rough metal one that lanes do not know (Beckmann), a rectangular light, a point light and a
/// grey sky: paths that go through lanes, per path, and between the two.
fn mixed_scene() -> Scene {
    let camera = Camera::new(Vec3::new(0.2, 0.1, 3.5), Vec3::ZERO, Vec3::Y, 50.0, 16, 16);
    let mut b = SceneBuilder::new(camera.unwrap());
    b.background(Rgb::gray(0.3));
    let white = b.material(Material::lambertian(Rgb::new(0.8, 0.7, 0.6)));
    let checker = b.material(Material {
        surface: Surface::Diffuse {
            reflectance: Texture::Checker(crate::texture::checker::Checker {
                even: Rgb::new(0.9, 0.8, 0.1),
                odd: Rgb::BLACK,
                size: 0.3,
                world: None,
            }),
        },
        ..Material::default()
    });
    let red = b.material(Material {
        two_sided: true,
        ..Material::lambertian(Rgb::new(0.6, 0.05, 0.05))
    });
    let metal = b.material(
        Material::physically_based(
            Surface::Conductor {
                eta: Texture::from(0.2),
                k: Texture::from(3.0),
                specular: Texture::from(1.0),
                roughness: None,
            },
            &[],
        )
        .0,
    );
    let rough = |distribution, alpha_u| {
        Material::physically_based(
            Surface::Conductor {
                eta: Texture::from(Rgb::new(0.2, 0.9, 1.1)),
                k: Texture::from(Rgb::new(3.9, 2.4, 2.2)),
                specular: Texture::from(1.0),
                roughness: Some(Roughness {
                    distribution,
                    alpha_u,
                    alpha_v: Texture::from(0.08),
                }),
            },
            &[],
        )
        .0
    };
    let ggx_alpha = Texture::Checker(crate::texture::checker::Checker {
        even: Rgb::gray(0.4),
        odd: Rgb::gray(0.02),
        size: 0.2,
        world: None,
    });
    let ggx = b.material(rough(Distribution::Ggx, ggx_alpha));
    let beckmann = b.material(rough(Distribution::Beckmann, Texture::from(0.3)));
    let rough_glass = b.material(
        Material::physically_based(
            Surface::Dielectric {
                eta: 1.33,
                specular: Texture::from(1.0),
                transmittance: Texture::from(Rgb::new(0.8, 0.95, 1.0)),
                roughness: Some(Roughness {
                    distribution: Distribution::Ggx,
                    alpha_u: Texture::from(0.25),
                    alpha_v: Texture::from(0.1),
                }),
            },
            &[],
        )
        .0,
    );
    let plastic = b.material(
        Material::physically_based(
            Surface::Plastic {
                diffuse: Texture::Checker(crate::texture::checker::Checker {
                    even: Rgb::new(0.1, 0.5, 0.8),
                    odd: Rgb::new(0.9, 0.9, 0.2),
                    size: 0.15,
                    world: None,
                }),
                eta: 1.6,
                specular: Texture::from(1.0),
                nonlinear: true,
                coat: None,
            },
            &[],
        )
        .0,
    );
    let glass = b.material(
        Material::physically_based(
            Surface::Dielectric {
                eta: 1.5,
                specular: Texture::from(1.0),
                transmittance: Texture::from(Rgb::new(0.9, 1.0, 0.95)),
                roughness: None,
            },
            &[],
        )
        .0,
    );
    let lamp = b.material(Material {
        ke: Rgb::new(9.0, 8.0, 6.0),
        ..Material::lambertian(Rgb::gray(0.5))
    });
    let quad = |c: [Vec3; 4]| Mesh::new(c.to_vec(), vec![[0, 1, 2], [0, 2, 3]]);
    let v = Vec3::new;
    let (l, h, a, c) = (-1.0, 1.0, -0.3, 0.3);
    let walls = [
        ([v(l, l, l), v(h, l, l), v(h, l, h), v(l, l, h)], checker),
        ([v(l, l, l), v(l, h, l), v(h, h, l), v(h, l, l)], white),
        ([v(l, l, l), v(l, l, h), v(l, h, h), v(l, h, l)], red),
        ([v(h, l, l), v(h, h, l), v(h, h, h), v(h, l, h)], red),
        (
            [v(a, 0.99, a), v(c, 0.99, a), v(c, 0.99, c), v(a, 0.99, c)],
            lamp,
        ),
    ];
    for (corners, material) in walls {
        b.mesh(quad(corners), material);
    }
    b.sphere(
        Sphere {
            center: Vec3::new(-0.4, -0.6, 0.1),
            radius: 0.4,
        },
        white,
    );
    b.sphere(
        Sphere {
            center: Vec3::new(0.45, -0.65, -0.2),
            radius: 0.35,
        },
        metal,
    );
    b.sphere(
        Sphere {
            center: Vec3::new(0.1, -0.1, 0.5),
            radius: 0.25,
        },
        glass,
    );
    for (center, radius, material) in [
        (Vec3::new(-0.55, 0.35, -0.5), 0.3, ggx),
        (Vec3::new(0.6, 0.4, -0.5), 0.25, beckmann),
        (Vec3::new(-0.25, 0.35, 0.6), 0.22, rough_glass),
        (Vec3::new(0.3, 0.3, 0.2), 0.2, plastic),
    ] {
        b.sphere(Sphere { center, radius }, material);
    }
    b.light(Light::Point(PointLight {
        position: Vec3::new(0.5, 0.5, 0.8),
        intensity: Rgb::gray(0.5),
        falloff: Falloff::Quadratic,
    }));
    b.build().unwrap()
}

#[test]
fn lanes_give_the_scalar_paths_bits() {
    let scene = mixed_scene();
    let lanes = LaneMaterials::of(&scene);
    assert!(lanes.any());
    // The GGX metal and glass go through lanes, the Beckmann metal per path.
    let rough_glass = scene.materials.iter().enumerate().filter(|(i, m)| {
        matches!(
            m.surface,
            Surface::Dielectric {
                roughness: Some(_),
                ..
            }
        ) && lanes.get(*i as u32).is_some()
    });
    assert_eq!(rough_glass.count(), 1);
    let plastic = scene.materials.iter().enumerate().filter(|(i, m)| {
        matches!(m.surface, Surface::Plastic { .. }) && lanes.get(*i as u32).is_some()
    });
    assert_eq!(plastic.count(), 1);
    let mut rough = 0;
    for (i, m) in scene.materials.iter().enumerate() {
        if let Surface::Conductor {
            roughness: Some(r), ..
        } = &m.surface
        {
            assert_eq!(
                lanes.get(i as u32).is_some(),
                r.distribution == Distribution::Ggx
            );
            rough += 1;
        }
    }
    assert_eq!(rough, 2);
    let tracer = PathTracer {
        max_depth: 6,
        rr_depth: 2,
    };
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let mut scalar_stats = RayStats::default();
    let mut lane_stats = RayStats::default();
    // Groups of every size from 1 to 8 (so that partial groups are covered).
    let mut pixel = 0u64;
    let mut shown = 0;
    for size in (1..=LANES).cycle().take(400) {
        let mut rays = ArrayVec::<Ray, LANES>::new();
        let mut samplers = ArrayVec::<Sampler, LANES>::new();
        for _ in 0..size {
            let (x, y) = (
                (pixel % u64::from(w)) as u32,
                ((pixel / u64::from(w)) % u64::from(h)) as u32,
            );
            let s = (pixel / u64::from(w * h)) as u32;
            let mut sampler = Sampler::new(3, pixel, s);
            let u = sampler.next_2d();
            sampler.defer(2);
            rays.push(scene.camera.ray(x as f32 + u.x, y as f32 + u.y));
            samplers.push(sampler);
            pixel += 1;
        }
        let expected: Vec<Rgb> = rays
            .iter()
            .zip(samplers.clone())
            .map(|(r, mut s)| tracer.radiance(&scene, r, &mut s, &mut scalar_stats))
            .collect();
        // As the processor runs it (with AVX2 where it has it), and in the baseline
        // instruction set.
        let mut baseline = samplers.clone();
        let got =
            tracer.radiance_lanes(&scene, &lanes, None, &rays, &mut samplers, &mut lane_stats);
        let got_baseline = tracer.radiance_lanes_with(
            &scene,
            &lanes,
            None,
            &rays,
            &mut baseline,
            &mut RayStats::default(),
        );
        for ((e, g), b) in expected.iter().zip(&got).zip(&got_baseline) {
            let bits = |c: &Rgb| c.to_array().map(f32::to_bits);
            assert_eq!(bits(e), bits(g), "expected {e:?}, got {g:?}");
            assert_eq!(bits(e), bits(b), "expected {e:?}, got {b:?} (baseline)");
            shown += usize::from(!e.is_black());
        }
    }
    assert_eq!(scalar_stats, lane_stats, "the same rays");
    assert!(shown > 400, "only {shown} paths found light");
    assert!(
        scalar_stats.shadow > 1000 && scalar_stats.reflected > 1000,
        "{scalar_stats:?}"
    );
}
