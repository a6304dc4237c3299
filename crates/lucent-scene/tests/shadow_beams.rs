//! Shadow beams change no occlusion answer: in every example scene, the shadow rays from the
//! camera hits of each 8×8 tile towards each point or spot light meet the same blockers (the
//! same materials and crossings, in any order) through the tile's shadow beam as from the
//! accelerators' roots.

mod common;

use common::examples;
use lucent::accel::{Aabb, TraversalStats};
use lucent::light::Light;
use lucent::spawn::spawn_ray;
use lucent_scene::{LoadOptions, SceneFile, Spanned};

#[test]
fn every_example_meets_the_same_blockers_through_shadow_beams() {
    const TILE: u32 = 8;
    let mut beams_made = 0;
    for path in examples() {
        let mut file = SceneFile::read_with(&path, &LoadOptions::default()).unwrap();
        file.desc.image.width = Spanned::new(0..0, 64);
        file.desc.image.height = Spanned::new(0..0, 48);
        let scene = file.build().unwrap().scene;
        let lights: Vec<_> = scene.lights.iter().filter_map(Light::position).collect();
        let mut stats = TraversalStats::default();
        for ty in 0..48 / TILE {
            for tx in 0..64 / TILE {
                let hits: Vec<_> = (0..TILE * TILE)
                    .filter_map(|k| {
                        let (x, y) = (tx * TILE + k % TILE, ty * TILE + k / TILE);
                        let ray = scene.camera.ray(x as f32 + 0.5, y as f32 + 0.5);
                        scene.intersect(&ray, &mut stats)
                    })
                    .collect();
                for &light in &lights {
                    let shadow_rays: Vec<_> = hits
                        .iter()
                        .filter_map(|hit| {
                            let offset = light - hit.point;
                            let distance = offset.length();
                            (distance > 0.0).then(|| {
                                let (ray, from) = spawn_ray(hit, offset / distance);
                                (ray, distance, from)
                            })
                        })
                        .collect();
                    let origins = shadow_rays.iter().fold(Aabb::EMPTY, |b, (r, _, _)| {
                        b.union(Aabb::new(r.origin, r.origin))
                    });
                    let Some(beam) = scene.shadow_beam(light, &origins) else {
                        continue;
                    };
                    beams_made += 1;
                    for (ray, t_max, from) in &shadow_rays {
                        let mut met = |through_beam: bool| {
                            let mut all = Vec::new();
                            let record = |material, crossings| {
                                all.push((material, crossings));
                                false
                            };
                            if through_beam {
                                scene.occlusion_in(
                                    &beam,
                                    ray,
                                    *t_max,
                                    Some(*from),
                                    &mut stats,
                                    record,
                                );
                            } else {
                                scene.occlusion(ray, *t_max, Some(*from), &mut stats, record);
                            }
                            all.sort_unstable();
                            all
                        };
                        assert_eq!(met(false), met(true), "{}: a shadow ray", path.display());
                    }
                }
            }
        }
    }
    assert!(
        beams_made > 20,
        "only {beams_made} shadow beams: a test of little"
    );
}
