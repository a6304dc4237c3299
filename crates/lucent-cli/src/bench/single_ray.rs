//! Like for like: lucent's triangle kernel and the peers, each given a ray as an origin, a
//! direction and a segment length, as the peers' single-ray queries take them, on the same
//! rays, measured in turn so that a noisy machine cannot favour whoever ran first. lucent's
//! whole scene query (which also works out the surface at the hit) takes the same turns.
//!
//! Each contender builds its own ray from (origin, direction) inside the timed loop — lucent's
//! kernel included, its reciprocal direction and all — and answers hit or miss (closest hit)
//! or blocked or not (occlusion). Every set is cut into [`CHUNKS`] runs of consecutive rays,
//! and each chunk is traced by the contenders one after another, [`ROUNDS`] times over: a
//! contender's time is the sum over chunks of its fastest time on each; who goes first on a
//! chunk (and finds its rays out of cache) changes from chunk to chunk and round to round. A
//! machine that slows for a moment then slows every contender on the same chunk (they run
//! within a few hundredths of a second of each other), and the slow round of that chunk does
//! not count.
//!
//! The kernel's and the peers' builds (over the same triangle soup) are timed as the least of
//! [`BUILD_ROUNDS`] builds each; the scene query's row keeps the time of the one build of the
//! whole scene that loading it made.

use super::rays::RaySet;
use super::report::{self, Measurement, Row, SETS};
use glam::Vec3;
use lucent::accel::{Ray, TraversalStats, WideTriangleBvh};
use std::time::Instant;

/// Rounds of the contenders in turn; the fastest of each on each chunk counts.
const ROUNDS: usize = 5;

/// Runs of consecutive rays a set is cut into, each traced by all contenders in turn.
const CHUNKS: usize = 16;

/// A structure traced one ray at a time.
pub trait SingleRay: Sync {
    /// Whether the ray hits within `t_max` (the nearest hit found, as a closest-hit query).
    fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32, stats: &mut TraversalStats) -> bool;
    /// Whether anything lies within `t_max`.
    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32, stats: &mut TraversalStats) -> bool;
}

/// One structure in the comparison: its row's description and its queries.
pub struct Contender<'a> {
    /// The row name.
    pub name: String,
    /// Build time in milliseconds.
    pub build_ms: f64,
    /// Nodes, depth and bytes per primitive, where known.
    pub info: Option<(usize, usize, f64)>,
    /// The queries.
    pub tracer: Box<dyn SingleRay + 'a>,
}

/// The wide BVH's triangle kernel alone.
pub struct Kernel(pub WideTriangleBvh);

impl SingleRay for Kernel {
    fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32, stats: &mut TraversalStats) -> bool {
        self.0
            .closest_hit(&Ray::new(origin, dir), t_max, None, stats)
            .is_some()
    }

    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32, stats: &mut TraversalStats) -> bool {
        self.0
            .any_hit(&Ray::new(origin, dir), t_max, stats, |_| true)
    }
}

/// The whole scene query a render makes (the surface at the hit included), as a contender.
pub struct SceneQuery<'a>(pub &'a lucent::scene::Scene);

impl SingleRay for SceneQuery<'_> {
    fn closest(&self, origin: Vec3, dir: Vec3, _t_max: f32, stats: &mut TraversalStats) -> bool {
        self.0.intersect(&Ray::new(origin, dir), stats).is_some()
    }

    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32, stats: &mut TraversalStats) -> bool {
        self.0.occluded(&Ray::new(origin, dir), t_max, stats)
    }
}

/// The kernel as a contender, built over world-space `triangles` (timed).
pub fn kernel(triangles: &[[Vec3; 3]]) -> Contender<'static> {
    let positions: Vec<Vec3> = triangles.iter().flatten().copied().collect();
    let indices: Vec<[u32; 3]> = (0..triangles.len() as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    let (bvh, build_ms) = least_build_time(|| {
        let start = Instant::now();
        let bvh = WideTriangleBvh::new(&positions, &indices);
        (bvh, start.elapsed().as_secs_f64() * 1e3)
    });
    let (nodes, depth, bytes) = bvh.info();
    Contender {
        name: report::KERNEL.to_string(),
        build_ms,
        info: Some((nodes, depth, bytes as f64 / triangles.len().max(1) as f64)),
        tracer: Box::new(Kernel(bvh)),
    }
}

/// Builds timed per contender: the least of these counts. A build is short, and one build's
/// time moved by ±20% from run to run with the machine (first touches of fresh memory most).
pub const BUILD_ROUNDS: usize = 5;

/// Runs `build` (which returns what it built and its time in milliseconds) [`BUILD_ROUNDS`]
/// times: the last structure, and the least time.
pub fn least_build_time<T>(mut build: impl FnMut() -> (T, f64)) -> (T, f64) {
    let (mut built, mut least) = build();
    for _ in 1..BUILD_ROUNDS {
        let (again, ms) = build();
        built = again;
        least = least.min(ms);
    }
    (built, least)
}

/// Measures every contender on every set and thread count, in turn (see the module's docs);
/// one row each, in the order given.
pub fn measure_in_turn(
    scene: &str,
    primitives: usize,
    contenders: &[Contender],
    sets: &[RaySet],
    threads: &[usize],
) -> anyhow::Result<Vec<Row>> {
    let mut rows: Vec<Row> = contenders
        .iter()
        .map(|c| Row {
            scene: scene.to_string(),
            primitives,
            accel: c.name.clone(),
            build_ms: c.build_ms,
            nodes: c.info.map(|i| i.0),
            depth: c.info.map(|i| i.1),
            bytes_per_prim: c.info.map(|i| i.2),
            measurements: vec![],
        })
        .collect();
    for (set_name, set) in SETS.iter().zip(sets) {
        let occlusion = *set_name == "occlusion";
        let n = set.rays.len();
        let chunks: Vec<std::ops::Range<usize>> = (0..CHUNKS)
            .map(|c| c * n / CHUNKS..(c + 1) * n / CHUNKS)
            .filter(|r| !r.is_empty())
            .collect();
        for &t in threads {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(t).build()?;
            // best[contender][chunk]: the fastest run so far.
            let mut best: Vec<Vec<Option<Measurement>>> =
                vec![vec![None; chunks.len()]; contenders.len()];
            for round in 0..ROUNDS {
                for (k, chunk) in chunks.iter().enumerate() {
                    // Whoever goes first on a chunk finds its rays out of cache: take turns.
                    for j in 0..contenders.len() {
                        let i = (j + round + k) % contenders.len();
                        let c = &contenders[i];
                        let m = pool
                            .install(|| trace(c.tracer.as_ref(), set, chunk.clone(), occlusion));
                        let best = &mut best[i][k];
                        if let Some(b) = best
                            && b.hits != m.hits
                        {
                            anyhow::bail!(
                                "{set_name}: {} answered {} hits on rays {chunk:?}, then {}",
                                c.name,
                                b.hits,
                                m.hits
                            );
                        }
                        if best.is_none_or(|b| m.seconds < b.seconds) {
                            *best = Some(m);
                        }
                    }
                }
            }
            for (row, best) in rows.iter_mut().zip(best) {
                let total = best
                    .into_iter()
                    .map(|m| m.expect("ROUNDS > 0"))
                    .fold(Measurement::default(), Measurement::plus);
                row.measurements.push((set_name, t, total));
            }
        }
    }
    for row in &rows {
        eprintln!("  {}", row.summary());
    }
    Ok(rows)
}

/// One timed pass of `tracer` over the rays `range` of `set`, on the current thread pool.
fn trace(
    tracer: &dyn SingleRay,
    set: &RaySet,
    range: std::ops::Range<usize>,
    occlusion: bool,
) -> Measurement {
    Measurement::timed(range.len(), |k, stats| {
        let i = range.start + k;
        let (r, t_max) = (&set.rays[i], set.t_max[i]);
        if occlusion {
            tracer.occluded(r.origin, r.dir, t_max, stats)
        } else {
            tracer.closest(r.origin, r.dir, t_max, stats)
        }
    })
}
