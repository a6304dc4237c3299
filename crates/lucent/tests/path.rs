//! The path tracer against answers known in closed form: white furnaces, the irradiance of a
//! rectangular area light, depth of field, and images that do not depend on threads.

mod common;

use glam::Vec2;
use glam::Vec3;
use lucent::Rgb;
use lucent::bsdf::{Bsdf, Distribution, Microfacet, Transport};
use lucent::camera::Camera;
use lucent::film::Film;
use lucent::film::filter::Filter;
use lucent::film::splat::FilterSampling;
use lucent::integrator::{Integrator, PathTracer};
use lucent::material::{Material, Roughness, Surface};
use lucent::render::{Hooks, RenderSettings, render};
use lucent::sampling::uniform;
use lucent::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::{Mesh, Sphere};
use lucent::texture::Texture;
use std::sync::atomic::AtomicBool;

fn film_of(scene: &Scene, spp: u32, threads: usize, max_depth: u32) -> Film {
    film_filtered(
        scene,
        spp,
        threads,
        max_depth,
        Filter::default(),
        FilterSampling::Splat,
    )
}

fn film_filtered(
    scene: &Scene,
    spp: u32,
    threads: usize,
    max_depth: u32,
    filter: Filter,
    filter_sampling: FilterSampling,
) -> Film {
    let settings = RenderSettings {
        integrator: Integrator::Path(PathTracer {
            max_depth,
            rr_depth: 5,
        }),
        spp,
        threads,
        seed: 7,
        filter,
        filter_sampling,
        ..RenderSettings::default()
    };
    common::render_all(scene, &settings).film
}

/// A unit sphere of `material` seen whole by a `size`² camera, inside a constant environment
/// of radiance 1.
fn furnace(material: Material, size: u32) -> Scene {
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 4.0),
        Vec3::ZERO,
        Vec3::Y,
        30.0,
        size,
        size,
    )
    .unwrap();
    let mut b = SceneBuilder::new(camera);
    b.background(Rgb::WHITE);
    let m = b.material(material);
    b.sphere(
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        m,
    );
    b.build().unwrap()
}

/// The worst relative difference from `expected` over every pixel and channel.
fn worst(film: &Film, expected: f32) -> f32 {
    let mut worst = 0.0f32;
    for y in 0..film.height() {
        for x in 0..film.width() {
            let p = film.pixel(x, y);
            for c in p.to_array() {
                worst = worst.max((c - expected).abs() / expected);
            }
        }
    }
    worst
}

#[test]
fn a_white_diffuse_sphere_vanishes_in_the_white_furnace() {
    // A convex object sees only the environment: every bounce returns ρ·1.
    let white = Material::lambertian(Rgb::WHITE);
    let film = film_of(&furnace(white, 10), 16384, 0, 10);
    let w = worst(&film, 1.0);
    assert!(w < 0.005, "worst pixel {w} from 1");

    let grey = Material::lambertian(Rgb::gray(0.5));
    let film = film_of(&furnace(grey, 16), 1024, 0, 10);
    // The sphere's pixels are 0.5, the background's 1.
    let centre = film.pixel(8, 8);
    assert!((centre.r - 0.5).abs() < 0.005, "{centre:?}");
    assert!((film.pixel(0, 0).g - 1.0).abs() < 1e-6);
}

#[test]
fn glass_and_a_white_metal_keep_the_furnace_white() {
    // Smooth glass absorbs nothing: reflection and refraction together return all the light,
    // whatever the path does inside (up to the depth limit).
    let glass = Material {
        surface: Surface::Dielectric {
            eta: 1.5,
            specular: Texture::from(1.0),
            transmittance: Texture::from(1.0),
            roughness: None,
        },
        ..Material::default()
    };
    let film = film_of(&furnace(glass, 10), 4096, 0, 64);
    let w = worst(&film, 1.0);
    assert!(w < 0.01, "glass: worst pixel {w} from 1");

    // A rough white metal loses what single-scattering microfacets lose (about 12% facing
    // the light at α 0.3): the furnace pixel facing the camera must equal the BSDF's own
    // albedo there, computed apart from the integrator by cosine sampling of `eval` — light
    // sampling, BSDF sampling and their MIS weights agree with the BSDF.
    let alpha = 0.3;
    let metal = Material {
        surface: Surface::Conductor {
            eta: Texture::from(0.0),
            k: Texture::from(1e4),
            specular: Texture::from(1.0),
            roughness: Some(Roughness::isotropic(Distribution::Ggx, alpha)),
        },
        ..Material::default()
    };
    let bsdf = Bsdf::RoughConductor {
        eta: Rgb::BLACK,
        k: Rgb::gray(1e4),
        specular: Rgb::WHITE,
        microfacet: Microfacet::ggx(alpha),
    };
    let n = 1_000_000u64;
    let albedo = (0..n)
        .map(|i| {
            let u = Vec2::new(uniform(5, i, 0, 0), uniform(5, i, 0, 1));
            let wi = square_to_cosine_hemisphere(u);
            let f = bsdf.eval(Vec3::Z, wi, Transport::Radiance).r;
            f64::from(f / cosine_hemisphere_pdf(wi.z))
        })
        .sum::<f64>()
        / n as f64;
    let film = film_of(&furnace(metal, 9), 4096, 0, 10);
    for y in 0..9 {
        for x in 0..9 {
            let p = film.pixel(x, y).r;
            assert!(p < 1.005, "rough metal at ({x}, {y}) gains light: {p}");
        }
    }
    let centre = f64::from(film.pixel(4, 4).r);
    assert!(
        (centre - albedo).abs() < 0.01 * albedo,
        "rough metal facing the camera: {centre}, its albedo {albedo}"
    );
    assert!(albedo > 0.85 && albedo < 0.9, "GGX at α 0.3 keeps {albedo}");
}

/// The irradiance at the origin (normal +y) from a polygon of constant radiance 1, by
/// Lambert's formula: `E = ½ Σ γ_k (n · (v_k × v_k+1) / |v_k × v_k+1|)`, with `γ_k` the
/// angle the edge subtends and the polygon wound clockwise seen from the point.
fn polygon_irradiance(corners: &[Vec3]) -> f32 {
    let n = corners.len();
    let mut e = 0.0;
    for k in 0..n {
        let (a, b) = (corners[k].normalize(), corners[(k + 1) % n].normalize());
        let c = a.cross(b);
        e += a.dot(b).clamp(-1.0, 1.0).acos() * c.y / c.length();
    }
    0.5 * e.abs()
}

#[test]
fn a_rectangular_light_gives_lamberts_irradiance() {
    // A floor (y = 0) of albedo ρ under a 1 × 0.5 light at height 1, off to one side; the
    // floor's radiance at the origin is ρ/π · L · E. Direct light only (max_depth 0): both
    // light sampling and BSDF sampling of the one bounce, weighted by MIS.
    let (rho, radiance) = (0.8, 3.0);
    // A camera looking straight down at the origin through a narrow field.
    let camera = Camera::new(Vec3::new(0.0, 0.5, 0.0), Vec3::ZERO, Vec3::Z, 0.5, 5, 5).unwrap();
    let mut b = SceneBuilder::new(camera);
    let floor = b.material(Material::lambertian(Rgb::gray(rho)));
    let light = b.material(Material {
        ke: Rgb::gray(radiance),
        surface: Surface::Diffuse {
            reflectance: Texture::from(0.0),
        },
        ..Material::default()
    });
    let s = 20.0;
    b.mesh(
        Mesh::new(
            vec![
                Vec3::new(-s, 0.0, -s),
                Vec3::new(s, 0.0, -s),
                Vec3::new(s, 0.0, s),
                Vec3::new(-s, 0.0, s),
            ],
            vec![[0, 2, 1], [0, 3, 2]],
        ),
        floor,
    );
    // Facing down: wound counter-clockwise seen from below.
    let corners = [
        Vec3::new(0.3, 1.0, -0.2),
        Vec3::new(1.3, 1.0, -0.2),
        Vec3::new(1.3, 1.0, 0.3),
        Vec3::new(0.3, 1.0, 0.3),
    ];
    b.mesh(
        Mesh::new(corners.to_vec(), vec![[0, 1, 2], [0, 2, 3]]),
        light,
    );
    let scene = b.build().unwrap();
    let expected = rho / std::f32::consts::PI * radiance * polygon_irradiance(&corners);
    let film = film_of(&scene, 4096, 0, 0);
    let got = film.pixel(2, 2).r;
    assert!(
        (got - expected).abs() < 0.01 * expected,
        "floor radiance {got}, Lambert's formula gives {expected}"
    );
}

#[test]
fn the_same_seed_gives_the_same_image_on_any_number_of_threads() {
    let grey = Material::lambertian(Rgb::gray(0.5));
    let scene = furnace(grey, 20);
    let one = film_of(&scene, 8, 1, 10);
    let two = film_of(&scene, 8, 2, 10);
    assert_eq!(one, two);
}

#[test]
fn a_splatted_gaussian_is_as_bright_less_noisy_and_the_same_on_any_threads() {
    // A uniformly lit white floor seen straight down: every pixel has the same expected value,
    // so the spread over pixels is the noise.
    let camera = Camera::new(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, Vec3::Z, 40.0, 24, 24).unwrap();
    let mut b = SceneBuilder::new(camera);
    b.background(Rgb::WHITE);
    let floor = b.material(Material::lambertian(Rgb::gray(0.5)));
    b.plane(lucent::shape::Plane::new(Vec3::ZERO, Vec3::Y), floor);
    let scene = b.build().unwrap();
    let gaussian = Filter::Gaussian {
        radius: 2.0,
        sigma: 0.5,
    };
    let stats = |film: &Film| {
        // Inner pixels only: the border has fewer neighbours to share with.
        let v: Vec<f64> = (3..21)
            .flat_map(|y| (3..21).map(move |x| (x, y)))
            .map(|(x, y)| f64::from(film.pixel(x, y).g))
            .collect();
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let var = v.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / v.len() as f64;
        (mean, var)
    };
    let splat = film_filtered(&scene, 4, 2, 0, gaussian, FilterSampling::Splat);
    let importance = film_filtered(&scene, 4, 2, 0, gaussian, FilterSampling::Importance);
    let ((ms, vs), (mi, vi)) = (stats(&splat), stats(&importance));
    // The floor's radiance is ρ·L = 0.5 under a white sky; both estimate it.
    assert!(
        (ms - 0.5).abs() < 0.01 && (mi - 0.5).abs() < 0.02,
        "{ms} {mi}"
    );
    assert!(
        vs < vi / 2.0,
        "variance splatted {vs:.2e}, importance-sampled {vi:.2e}"
    );
    assert_eq!(
        splat,
        film_filtered(&scene, 4, 1, 0, gaussian, FilterSampling::Splat)
    );
}

#[test]
fn a_splatting_render_stopped_and_resumed_is_the_uninterrupted_one() {
    let grey = Material::lambertian(Rgb::gray(0.5));
    let scene = furnace(grey, 40);
    let settings = RenderSettings {
        integrator: Integrator::Path(PathTracer::default()),
        spp: 96,
        threads: 2,
        tile_size: 8,
        filter: Filter::Mitchell {
            radius: 2.0,
            b: 1.0 / 3.0,
            c: 1.0 / 3.0,
        },
        ..RenderSettings::default()
    };
    let run = |start: Option<Film>, stop_after: u64| {
        let cancel = AtomicBool::new(false);
        let progress = |done: u64, _| {
            if done >= stop_after {
                cancel.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        };
        let hooks = Hooks {
            cancel: &cancel,
            progress: &progress,
            checkpoint: None,
        };
        render(&scene, &settings, start, &hooks).unwrap()
    };
    let whole = run(None, u64::MAX);
    assert!(whole.complete);
    // Stopped in the second pass (past 64 samples a pixel), then resumed.
    let stopped = run(None, 40 * 40 * 70);
    assert!(!stopped.complete);
    let (least, most) = stopped.samples_range;
    assert!((64..96).contains(&least) && most <= 96, "{least}..{most}");
    let resumed = run(Some(stopped.film), u64::MAX);
    assert!(resumed.complete);
    assert_eq!(resumed.film, whole.film);
}

#[test]
fn a_thin_lens_blurs_what_is_out_of_focus() {
    // A small sphere at the focus distance stays sharp; one nearer is spread wider.
    let lit = |focus: f32| -> usize {
        let camera = Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 20.0, 32, 32)
            .unwrap()
            .with_lens(0.2, focus)
            .unwrap();
        let mut b = SceneBuilder::new(camera);
        let glow = b.material(Material {
            ke: Rgb::WHITE,
            ..Material::default()
        });
        b.sphere(
            Sphere {
                center: Vec3::ZERO,
                radius: 0.15,
            },
            glow,
        );
        let film = film_of(&b.build().unwrap(), 64, 0, 0);
        (0..32)
            .flat_map(|y| (0..32).map(move |x| (x, y)))
            .filter(|&(x, y)| film.pixel(x, y).r > 0.02)
            .count()
    };
    let (sharp, blurred) = (lit(5.0), lit(2.0));
    assert!(sharp > 4, "the sphere shows: {sharp} pixels");
    assert!(
        blurred > 2 * sharp,
        "in focus {sharp} pixels lit, out of focus {blurred}"
    );
}

#[test]
fn paths_in_lanes_make_the_image_of_paths_one_at_a_time() {
    // A Lambertian ball (shaded in lanes) beside a Beckmann-rough metal one (shaded per path) on a
    // Lambertian floor, under a white sky and a point light; 5 samples a pixel, so that lane
    // groups span pixels and end short. Kept in each pixel (the box filter) and splatted.
    let camera = Camera::new(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO, Vec3::Y, 40.0, 20, 15).unwrap();
    let mut b = SceneBuilder::new(camera);
    b.background(Rgb::gray(0.8));
    let floor = b.material(Material::lambertian(Rgb::new(0.7, 0.6, 0.5)));
    let ball = b.material(Material::lambertian(Rgb::new(0.2, 0.4, 0.8)));
    let metal = b.material(
        Material::physically_based(
            Surface::Conductor {
                eta: Texture::from(0.2),
                k: Texture::from(3.0),
                specular: Texture::from(1.0),
                roughness: Some(Roughness::isotropic(Distribution::Beckmann, 0.3)),
            },
            &[],
        )
        .0,
    );
    b.plane(
        lucent::shape::Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y),
        floor,
    );
    b.sphere(
        Sphere {
            center: Vec3::new(-0.6, -0.4, 0.0),
            radius: 0.6,
        },
        ball,
    );
    b.sphere(
        Sphere {
            center: Vec3::new(0.7, -0.5, 0.2),
            radius: 0.5,
        },
        metal,
    );
    b.light(lucent::light::Light::Point(
        lucent::light::point::PointLight {
            position: Vec3::new(1.0, 2.0, 2.0),
            intensity: Rgb::gray(4.0),
            falloff: lucent::light::point::Falloff::Quadratic,
        },
    ));
    let scene = b.build().unwrap();
    for filter in [
        Filter::default(),
        Filter::Gaussian {
            radius: 2.0,
            sigma: 0.5,
        },
    ] {
        let settings = |lanes, threads| RenderSettings {
            integrator: Integrator::Path(PathTracer::default()),
            spp: 5,
            threads,
            tile_size: 8,
            filter,
            lanes,
            ..RenderSettings::default()
        };
        let one_at_a_time = common::render_all(&scene, &settings(false, 1));
        let in_lanes = common::render_all(&scene, &settings(true, 2));
        assert_eq!(in_lanes.film, one_at_a_time.film, "{filter:?}");
        assert_eq!(in_lanes.stats.rays, one_at_a_time.stats.rays, "{filter:?}");
    }
}
