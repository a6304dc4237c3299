//! Whitted's adaptive supersampling: every corner traced once, the depth limit, the two
//! extreme thresholds, and the same image on any number of threads or tile size.

mod common;

use glam::Vec3;
use lucent::Rgb;
use lucent::camera::Camera;
use lucent::integrator::Integrator;
use lucent::material::Material;
use lucent::render::{RenderSettings, Rendered, Sampling};
use lucent::sampling::sobol::Sampler;
use lucent::scene::{Scene, SceneBuilder};
use lucent::schedule::adaptive::Adaptive;
use lucent::shape::Sphere;

const W: u32 = 23;
const H: u32 = 17;

/// A white sphere on black, seen flat by the raycast integrator: a hard edge, a smooth inside.
fn scene() -> Scene {
    let camera = Camera::new(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, 30.0, W, H).unwrap();
    let mut b = SceneBuilder::new(camera);
    let m = b.material(Material::diffuse(Rgb::WHITE));
    b.sphere(
        Sphere {
            center: Vec3::new(0.3, -0.2, 0.0),
            radius: 1.6,
        },
        m,
    );
    b.build().unwrap()
}

fn adaptive(scene: &Scene, threshold: f32, depth: u32, threads: usize, tile: u32) -> Rendered {
    let a = Adaptive {
        threshold,
        depth,
        block: 0,
    };
    render_with(scene, a, threads, tile)
}

fn render_with(scene: &Scene, a: Adaptive, threads: usize, tile: u32) -> Rendered {
    let settings = RenderSettings {
        integrator: Integrator::Raycast,
        threads,
        tile_size: tile,
        sampling: Sampling::Adaptive(a),
        ..RenderSettings::default()
    };
    common::render_all(scene, &settings)
}

/// Corners a pixel uses when split at every level down to `depth`.
fn full(depth: u32) -> u32 {
    4 + 5 * (4u32.pow(depth) - 1) / 3
}

#[test]
fn threshold_zero_splits_everywhere_and_traces_each_corner_once() {
    let scene = scene();
    for depth in [0, 1, 3] {
        let r = adaptive(&scene, 0.0, depth, 2, 4);
        let step = 1u64 << depth;
        // Every lattice point of the image, once: shared corners are not traced twice.
        let lattice = (u64::from(W) * step + 1) * (u64::from(H) * step + 1);
        assert_eq!(r.stats.rays.camera, lattice, "depth {depth}");
        assert!(r.density.iter().all(|&n| n == full(depth)), "depth {depth}");
        assert!(r.complete);
    }
}

#[test]
fn an_infinite_threshold_takes_one_set_of_corners_per_pixel() {
    let r = adaptive(&scene(), f32::INFINITY, 3, 2, 5);
    assert_eq!(r.stats.rays.camera, u64::from((W + 1) * (H + 1)));
    assert!(r.density.iter().all(|&n| n == 4));
}

#[test]
fn only_edges_are_split_down_to_the_depth_limit() {
    let scene = scene();
    let r = adaptive(&scene, 0.1, 2, 2, 8);
    let (mut flat, mut split) = (0, 0);
    for y in 0..H {
        for x in 0..W {
            let n = r.density[(y * W + x) as usize];
            assert!((4..=full(2)).contains(&n), "{n}");
            let v = r.film.pixel(x, y).r;
            if v == 0.0 || v == 1.0 {
                flat += u32::from(n == 4);
            } else {
                // A pixel that straddles the silhouette was split.
                split += 1;
                assert!(n > 4, "({x}, {y}) {v} {n}");
            }
        }
    }
    assert!(flat > W * H / 2 && split > 10, "{flat} {split}");
    // Every ray traced was needed by some pixel, and no more than the full lattice.
    let lattice = u64::from((4 * W + 1) * (4 * H + 1));
    assert!(r.stats.rays.camera < lattice / 3);
}

#[test]
fn the_image_is_the_same_on_any_threads_and_tiles() {
    let scene = scene();
    let a = adaptive(&scene, 0.05, 3, 1, 16);
    let b = adaptive(&scene, 0.05, 3, 2, 3);
    assert_eq!(a.film, b.film);
    assert_eq!(a.density, b.density);
    assert_eq!(a.stats.rays.camera, b.stats.rays.camera);
}

#[test]
fn edge_pixels_approach_the_covered_area() {
    // The deeper the subdivision, the closer an edge pixel's value comes to the share of it
    // that the sphere covers, estimated here by a dense uniform grid.
    let scene = scene();
    let coarse = adaptive(&scene, 0.0, 1, 2, 8);
    let fine = adaptive(&scene, 0.0, 5, 2, 8);
    let mut err = [0.0f64; 2];
    for y in 0..H {
        for x in 0..W {
            let mut covered = 0;
            let n = 64;
            for j in 0..n {
                for i in 0..n {
                    let ray = scene.camera.ray(
                        x as f32 + (i as f32 + 0.5) / n as f32,
                        y as f32 + (j as f32 + 0.5) / n as f32,
                    );
                    let mut stats = Default::default();
                    covered += u32::from(
                        Integrator::Raycast
                            .radiance(&scene, &ray, &mut Sampler::new(0, 0, 0), &mut stats)
                            .r
                            > 0.5,
                    );
                }
            }
            let truth = f64::from(covered) / f64::from(n * n);
            for (e, r) in err.iter_mut().zip([&coarse, &fine]) {
                *e += (f64::from(r.film.pixel(x, y).r) - truth).abs();
            }
        }
    }
    assert!(err[1] < err[0] / 4.0, "{err:?}");
}

fn quadtree(scene: &Scene, threshold: f32, block: u32, threads: usize) -> Rendered {
    let a = Adaptive {
        threshold,
        depth: 2,
        block,
    };
    render_with(scene, a, threads, 16)
}

#[test]
fn a_quadtree_starts_with_one_corner_per_block() {
    let scene = scene();
    // No split anywhere: a block inside the image takes its 4 corners; a block that crosses
    // the image's right or bottom edge is split into quarters, down to pixels, which look at
    // their neighbours' corners too. Each distinct corner is one ray.
    fn corners(x: u32, y: u32, size: u32, out: &mut std::collections::HashSet<(u32, u32)>) {
        if x >= W || y >= H {
            return;
        }
        let square = |x: u32, y: u32, s: u32| [(x, y), (x + s, y), (x, y + s), (x + s, y + s)];
        if size == 1 {
            // A pixel also looks at the corners of its neighbours (the neighbour test).
            out.extend(square(x, y, 1));
            let (x, y) = (x as i64, y as i64);
            for (nx, ny) in [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)] {
                if (0..W as i64).contains(&nx) && (0..H as i64).contains(&ny) {
                    out.extend(square(nx as u32, ny as u32, 1));
                }
            }
            return;
        }
        if x + size <= W && y + size <= H {
            out.extend(square(x, y, size));
            return;
        }
        let h = size / 2;
        for (bx, by) in [(x, y), (x + h, y), (x, y + h), (x + h, y + h)] {
            corners(bx, by, h, out);
        }
    }
    let mut expected = std::collections::HashSet::new();
    for y in (0..H).step_by(8) {
        for x in (0..W).step_by(8) {
            corners(x, y, 8, &mut expected);
        }
    }
    let r = quadtree(&scene, f32::INFINITY, 3, 2);
    assert_eq!(r.stats.rays.camera, expected.len() as u64);
    assert!(expected.len() < ((W + 1) * (H + 1) / 3) as usize);
    // Threshold 0 splits every block down to the full lattice, as adaptive sampling does.
    let full = quadtree(&scene, 0.0, 3, 2);
    assert_eq!(full.stats.rays.camera, u64::from((4 * W + 1) * (4 * H + 1)));
    assert_eq!(full.film, adaptive(&scene, 0.0, 2, 2, 16).film);
}

#[test]
fn a_quadtree_finds_the_edges_and_repeats_exactly() {
    let scene = scene();
    let a = quadtree(&scene, 0.1, 3, 1);
    let b = quadtree(&scene, 0.1, 3, 2);
    assert_eq!(a.film, b.film);
    // Far fewer rays than per-pixel adaptive sampling, and the same image away from edges:
    // inside the sphere and in the empty corners every pixel is exact.
    let per_pixel = adaptive(&scene, 0.1, 2, 2, 16);
    assert!(a.stats.rays.camera < per_pixel.stats.rays.camera);
    let exact = (0..H)
        .flat_map(|y| (0..W).map(move |x| (x, y)))
        .filter(|&(x, y)| a.film.pixel(x, y) == per_pixel.film.pixel(x, y))
        .count();
    assert!(exact > (W * H * 3 / 4) as usize, "{exact}");
}
