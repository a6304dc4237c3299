//! Packets change no hit: in every example scene, the camera rays of each 8×8 tile (through
//! pixel centres and tile corners) traced eight at a time through the tile's beam
//! ([`lucent::scene::Scene::intersect_packet_in`]) hit what each hits alone from the roots,
//! bit for bit — partial packets at the image's right edge included.

mod common;

use common::examples;
use lucent::accel::TraversalStats;
use lucent::accel::wide_bvh::PACKET;
use lucent_scene::{LoadOptions, SceneFile, Spanned};

#[test]
fn every_example_hits_the_same_in_packets() {
    const TILE: u32 = 8;
    // 61 wide: the last tile of each row is 5 pixels, a partial packet.
    let (w, h) = (61, 40);
    // Over the wide BVH (packets through cuts) and the binary one (ray by ray).
    for (path, accel) in examples()
        .into_iter()
        .flat_map(|p| ["wide", "bvh"].map(|a| (p.clone(), a)))
    {
        let mut file = SceneFile::read_with(&path, &LoadOptions::default()).unwrap();
        file.desc.image.width = Spanned::new(0..0, w);
        file.desc.image.height = Spanned::new(0..0, h);
        file.desc.render.accelerator = Spanned::new(0..0, accel.to_string());
        let scene = file.build().unwrap().scene;
        let mut stats = TraversalStats::default();
        for y0 in (0..h).step_by(TILE as usize) {
            for x0 in (0..w).step_by(TILE as usize) {
                let (x1, y1) = ((x0 + TILE).min(w), (y0 + TILE).min(h));
                let (fx0, fy0, fx1, fy1) = (x0 as f32, y0 as f32, x1 as f32, y1 as f32);
                let Some(frustum) = scene.camera.frustum((fx0, fy0), (fx1, fy1)) else {
                    continue;
                };
                let beam = scene.beam(&frustum);
                // Pixel centres, and the tile's corners (rays on the beam's edges).
                let mut points: Vec<(f32, f32)> = (y0..y1)
                    .flat_map(|y| (x0..x1).map(move |x| (x as f32 + 0.5, y as f32 + 0.5)))
                    .collect();
                points.extend([(fx0, fy0), (fx1, fy0), (fx1, fy1), (fx0, fy1)]);
                let rays: Vec<_> = points
                    .iter()
                    .map(|&(x, y)| scene.camera.ray(x, y))
                    .collect();
                for chunk in rays.chunks(PACKET) {
                    let mut hits = [None; PACKET];
                    scene.intersect_packet_in(&beam, chunk, &mut stats, &mut hits);
                    for (ray, hit) in chunk.iter().zip(&hits) {
                        let alone = scene.intersect(ray, &mut stats);
                        let key = |h: &Option<lucent::shape::SurfaceHit>| {
                            h.as_ref().map(|h| {
                                (
                                    h.t.to_bits(),
                                    h.surface,
                                    h.point.to_array().map(f32::to_bits),
                                )
                            })
                        };
                        assert_eq!(key(&alone), key(hit), "{}: {ray:?}", path.display());
                    }
                    assert!(hits[chunk.len()..].iter().all(Option::is_none));
                }
            }
        }
    }
}
