//! Beams against per-pixel tracing: the same camera rays (one per pixel centre of the scene's
//! camera at 1024×1024), the same tiles traced whole by one thread in the same order; per pixel
//! each ray starts at the accelerators' roots, with beams each tile's rays go through the
//! tile's [`lucent::scene::Beam`] (the beams' making included). The hits are checked to be the
//! same (count and distances). Beams are also traced in packets: eight neighbours of a row
//! of the tile at once ([`Scene::intersect_packet_in`]). Each is run five times, alternately; the fastest run counts.

use super::report::Measurement;
use lucent::accel::TraversalStats;
use lucent::accel::wide_bvh::PACKET;
use lucent::scene::Scene;
use rayon::prelude::*;
use std::time::Instant;

/// Runs of each kind, alternating; the fastest counts. (Five: a default-scene run lasts some
/// tens of milliseconds, and on a shared machine three left its ratios ±20% apart.)
const REPEATS: usize = 5;

/// Tile sides measured.
pub const TILES: [u32; 2] = [8, 16];

/// One scene on one thread count with one tile size: per pixel, then beams.
pub struct BeamRow {
    /// The scene's file name.
    pub scene: String,
    /// Side of the square tiles.
    pub tile: u32,
    /// Threads.
    pub threads: usize,
    /// Each ray from the roots.
    pub per_pixel: Measurement,
    /// Each tile as a beam.
    pub beam: Measurement,
    /// Each tile as a beam, its rays eight at a time ([`Scene::intersect_packet_in`]).
    pub packets: Measurement,
    /// The shadow rays towards point lights: per pixel, and as shadow beams (`None` without a
    /// point light).
    pub shadow: Option<(Measurement, Measurement)>,
}

/// How a tile's camera rays are traced.
#[derive(Clone, Copy, PartialEq)]
enum Way {
    PerPixel,
    Beam,
    Packets,
}

/// The camera rays of `scene` in tiles of `tile`, per pixel, as beams, and as beams traced in
/// packets (eight neighbours of a row), on `threads`.
pub fn measure(
    scene: &Scene,
    tile: u32,
    threads: usize,
) -> anyhow::Result<(Measurement, Measurement, Measurement)> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let tiles: Vec<(u32, u32)> = (0..h.div_ceil(tile))
        .flat_map(|ty| (0..w.div_ceil(tile)).map(move |tx| (tx * tile, ty * tile)))
        .collect();
    let run = |way: Way| {
        let start = Instant::now();
        let (hits, sum, stats) = pool.install(|| {
            tiles
                .par_iter()
                .map(|&(x0, y0)| {
                    let (x1, y1) = ((x0 + tile).min(w), (y0 + tile).min(h));
                    let beam = (way != Way::PerPixel)
                        .then(|| {
                            let f = scene
                                .camera
                                .frustum((x0 as f32, y0 as f32), (x1 as f32, y1 as f32));
                            f.map(|f| scene.beam(&f))
                        })
                        .flatten();
                    let mut stats = TraversalStats::default();
                    let (mut hits, mut sum) = (0u64, 0u64);
                    let mut count = |hit: Option<lucent::shape::SurfaceHit>| {
                        if let Some(hit) = hit {
                            hits += 1;
                            sum = sum.wrapping_add(u64::from(hit.t.to_bits()));
                        }
                    };
                    let ray = |x: u32, y: u32| scene.camera.ray(x as f32 + 0.5, y as f32 + 0.5);
                    for y in y0..y1 {
                        match (&beam, way) {
                            (Some(b), Way::Packets) => {
                                let mut hits = [None; PACKET];
                                for xs in (x0..x1).step_by(PACKET) {
                                    let n = PACKET.min((x1 - xs) as usize);
                                    // On the stack: the timed loop allocates nothing.
                                    let rays: [_; PACKET] =
                                        std::array::from_fn(|k| ray(xs + k.min(n - 1) as u32, y));
                                    scene.intersect_packet_in(b, &rays[..n], &mut stats, &mut hits);
                                    hits[..n].iter().for_each(|h| count(*h));
                                }
                            }
                            (Some(b), _) => (x0..x1)
                                .for_each(|x| count(scene.intersect_in(b, &ray(x, y), &mut stats))),
                            (None, _) => (x0..x1)
                                .for_each(|x| count(scene.intersect(&ray(x, y), &mut stats))),
                        }
                    }
                    (hits, sum, stats)
                })
                .reduce(
                    || (0, 0, TraversalStats::default()),
                    |(h1, s1, mut t1), (h2, s2, t2)| {
                        t1 += t2;
                        (h1 + h2, s1.wrapping_add(s2), t1)
                    },
                )
        });
        let m = Measurement {
            rays: u64::from(w) * u64::from(h),
            seconds: start.elapsed().as_secs_f64(),
            hits,
            stats,
        };
        (m, sum)
    };
    // Alternated, the fastest of each kept: the machine may be shared, and both kinds should
    // meet the same disturbances.
    let fastest = |a: Option<Measurement>, b: Measurement| match a {
        Some(a) if a.seconds <= b.seconds => a,
        _ => b,
    };
    let (mut per_pixel, mut beam, mut packets) = (None, None, None);
    for _ in 0..REPEATS {
        let (p, a) = run(Way::PerPixel);
        let (b, s) = run(Way::Beam);
        let (k, q) = run(Way::Packets);
        anyhow::ensure!(
            a == s && a == q && p.hits == b.hits && p.hits == k.hits,
            "beam tracing found other hits than per-pixel tracing"
        );
        per_pixel = Some(fastest(per_pixel, p));
        beam = Some(fastest(beam, b));
        packets = Some(fastest(packets, k));
    }
    Ok((
        per_pixel.expect("measured"),
        beam.expect("measured"),
        packets.expect("measured"),
    ))
}

/// The rows as tables (camera rays, then shadow rays): Mrays/s per pixel and with beams, their
/// ratio, nodes per ray.
pub fn table(rows: &[BeamRow]) -> String {
    let mut out = String::from("\nBeam tracing of camera rays (same rays, same tiles):\n");
    out.push_str(HEADER);
    for r in rows {
        out.push_str(&line(r, &r.per_pixel, &r.beam));
    }
    out.push_str("\nBeams in packets of eight rays against per pixel (same rays, same tiles):\n");
    out.push_str(HEADER);
    for r in rows {
        out.push_str(&line(r, &r.per_pixel, &r.packets));
    }
    out.push_str("\nShadow beams towards point lights (same shadow rays, same tiles):\n");
    out.push_str(HEADER);
    for r in rows {
        if let Some((p, b)) = &r.shadow {
            out.push_str(&line(r, p, b));
        }
    }
    out
}

const HEADER: &str = "scene                       tile threads  per-pixel     beam  ratio  nodes/ray (pixel → beam)  triangles/ray\n";

fn line(r: &BeamRow, per_pixel: &Measurement, beam: &Measurement) -> String {
    let nodes = |m: &Measurement| m.stats.nodes_visited as f64 / m.rays.max(1) as f64;
    let prims = |m: &Measurement| m.stats.primitives_tested as f64 / m.rays.max(1) as f64;
    format!(
        "{:<27} {:>4} {:>7} {:>10.3} {:>8.3} {:>5.2}×  {:>6.2} → {:<6.2}  {:>12.1} → {:.1}\n",
        r.scene,
        r.tile,
        r.threads,
        per_pixel.mrays(),
        beam.mrays(),
        beam.mrays() / per_pixel.mrays(),
        nodes(per_pixel),
        nodes(beam),
        prims(per_pixel),
        prims(beam),
    )
}
