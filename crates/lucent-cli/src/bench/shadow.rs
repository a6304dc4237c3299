//! Shadow beams against per-pixel shadow rays: the shadow rays the Whitted integrator traces
//! from the camera hits of one ray per pixel centre (1024×1024) towards each point light,
//! grouped by tile. Per pixel each ray starts at the accelerators' roots; with beams each tile
//! and light get one shadow beam over the rays' origins ([`Scene::shadow_beam`], its making
//! timed too), and each ray is traced through it ([`Scene::occlusion_in`]). The camera hits are
//! found before timing. (A scene lit only by directional lights, such as a mesh file with its
//! default light, gets point lights up their beams instead: see `light_points`.) The answers (blocked or not) are checked to be the same, ray by ray.
//! Each way runs five times, alternately; the fastest run counts.

use super::report::Measurement;
use lucent::accel::{Aabb, Ray, TraversalStats};
use lucent::light::Light;
use lucent::scene::Scene;
use lucent::spawn::{Leaving, spawn_ray};
use rayon::prelude::*;
use std::time::Instant;

/// Runs of each kind, alternating; the fastest counts. (Five: a default-scene run lasts some
/// tens of milliseconds, and on a shared machine three left its ratios ±20% apart.)
const REPEATS: usize = 5;

/// One tile's shadow rays towards one light: the light, the rays' origins' box, and each ray
/// with its length and the surface it leaves.
struct Group {
    light: glam::Vec3,
    origins: Aabb,
    rays: Vec<(Ray, f32, Leaving)>,
}

/// Where the scene's point and spot lights are; a scene with neither (a mesh file, lit by a
/// default directional light) gets stand-ins: for each directional light, a point up its
/// beam, one diagonal of the scene's box from its centre.
fn light_points(scene: &Scene) -> Vec<glam::Vec3> {
    let points: Vec<glam::Vec3> = scene.lights.iter().filter_map(Light::position).collect();
    if !points.is_empty() {
        return points;
    }
    let b = scene.bounds();
    let reach = (b.max - b.min).length();
    scene
        .lights
        .iter()
        .filter_map(|l| match l {
            Light::Directional(d) if reach.is_finite() => Some(b.center() - d.direction * reach),
            _ => None,
        })
        .collect()
}

/// The shadow rays of `scene` towards its point lights, grouped by tile of side `tile` and
/// light: from each pixel centre's camera hit, to each point light in front of the surface.
fn groups(scene: &Scene, tile: u32) -> Vec<Group> {
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let lights = light_points(scene);
    let tiles: Vec<(u32, u32)> = (0..h.div_ceil(tile))
        .flat_map(|ty| (0..w.div_ceil(tile)).map(move |tx| (tx * tile, ty * tile)))
        .collect();
    tiles
        .par_iter()
        .flat_map_iter(|&(x0, y0)| {
            let (x1, y1) = ((x0 + tile).min(w), (y0 + tile).min(h));
            let mut stats = TraversalStats::default();
            let hits: Vec<_> = (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter_map(|(x, y)| {
                    let ray = scene.camera.ray(x as f32 + 0.5, y as f32 + 0.5);
                    scene.intersect(&ray, &mut stats).map(|hit| (ray, hit))
                })
                .collect();
            lights
                .iter()
                .map(|&light| {
                    let mut g = Group {
                        light,
                        origins: Aabb::EMPTY,
                        rays: vec![],
                    };
                    for (ray, hit) in &hits {
                        // The side the camera sees, as the integrator decides it.
                        let ng = if hit.normal.dot(ray.dir) < 0.0 {
                            hit.normal
                        } else {
                            -hit.normal
                        };
                        let offset = light - hit.point;
                        let distance = offset.length();
                        // Not at the light (nor NaN), and the light in front of the surface.
                        let to_light = offset / distance;
                        if distance.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
                            || ng.dot(to_light) <= 0.0
                        {
                            continue;
                        }
                        let (shadow, from) = spawn_ray(hit, to_light);
                        g.origins = g.origins.union(Aabb::new(shadow.origin, shadow.origin));
                        g.rays.push((shadow, distance, from));
                    }
                    g
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The shadow rays of `scene` in tiles of `tile`, per pixel and as shadow beams, on `threads`.
/// `None` when the scene has no point light.
pub fn measure(
    scene: &Scene,
    tile: u32,
    threads: usize,
) -> anyhow::Result<Option<(Measurement, Measurement)>> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let groups = pool.install(|| groups(scene, tile));
    let rays: u64 = groups.iter().map(|g| g.rays.len() as u64).sum();
    if rays == 0 {
        return Ok(None);
    }
    let run = |beams: bool| {
        let start = Instant::now();
        let per_group: Vec<(u64, u64, TraversalStats)> = pool.install(|| {
            groups
                .par_iter()
                .map(|g| {
                    let mut stats = TraversalStats::default();
                    let beam = beams
                        .then(|| scene.shadow_beam(g.light, &g.origins))
                        .flatten();
                    // Each ray's answer, as one bit of a running hash: order-sensitive, so
                    // that the same count of other answers does not pass for the same.
                    let (mut blocked, mut answers) = (0u64, 0u64);
                    for (ray, t_max, from) in &g.rays {
                        let stop = |_, _| true;
                        let b = match &beam {
                            Some(beam) => {
                                scene.occlusion_in(beam, ray, *t_max, Some(*from), &mut stats, stop)
                            }
                            None => scene.occlusion(ray, *t_max, Some(*from), &mut stats, stop),
                        };
                        blocked += u64::from(b);
                        answers = answers.rotate_left(1) ^ u64::from(b);
                    }
                    (blocked, answers, stats)
                })
                .collect()
        });
        let seconds = start.elapsed().as_secs_f64();
        let mut total = TraversalStats::default();
        let mut hits = 0;
        let mut hash = Vec::with_capacity(per_group.len());
        for (b, a, s) in per_group {
            hits += b;
            hash.push(a);
            total += s;
        }
        let m = Measurement {
            rays,
            seconds,
            hits,
            stats: total,
        };
        (m, hash)
    };
    let fastest = |a: Option<Measurement>, b: Measurement| match a {
        Some(a) if a.seconds <= b.seconds => a,
        _ => b,
    };
    let (mut per_pixel, mut beam) = (None, None);
    for _ in 0..REPEATS {
        let (p, a) = run(false);
        let (b, s) = run(true);
        anyhow::ensure!(
            a == s && p.hits == b.hits,
            "shadow beams gave other occlusion answers than per-pixel shadow rays"
        );
        per_pixel = Some(fastest(per_pixel, p));
        beam = Some(fastest(beam, b));
    }
    Ok(Some((
        per_pixel.expect("measured"),
        beam.expect("measured"),
    )))
}
