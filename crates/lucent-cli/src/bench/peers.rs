//! Peers on the same rays: Embree 3 (Intel's CPU ray tracing kernels, through the `embree`
//! crate and Debian's `libembree-dev`) and obvhs (a Rust BVH crate: a compressed 8-wide BVH).
//! Built only with the cargo features `bench-embree` and `bench-obvhs`.
//!
//! Peers see the scene as a soup of world-space triangles, so they are measured only on scenes
//! made of meshes alone (spheres and planes are lucent's own). Each traces one ray at a time
//! (`rtcIntersect1` / `rtcOccluded1`; obvhs `ray_traverse` / `ray_traverse_miss`), as lucent does.

use super::rays::RaySet;
use super::report::{Measurement, Row, SETS};
use glam::Vec3;
use lucent::accel::TraversalStats;
use rayon::prelude::*;
use std::time::Instant;

/// A peer's structure, ready for queries.
pub trait Peer: Sync {
    /// Closest hit: whether the ray hits within `t_max`.
    fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool;
    /// Occlusion: whether anything lies within `t_max`.
    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool;
}

/// What every peer is measured on.
pub struct Job<'a> {
    /// The scene's file name.
    pub scene: &'a str,
    /// World-space triangles.
    pub triangles: &'a [[Vec3; 3]],
    /// The ray sets, in [`SETS`] order.
    pub sets: &'a [RaySet],
    /// Thread counts.
    pub threads: &'a [usize],
}

/// Builds and measures every peer compiled in; one row each.
#[allow(clippy::vec_init_then_push)] // which pushes exist depends on the features
pub fn run(job: &Job) -> anyhow::Result<Vec<Row>> {
    #[allow(unused_mut)]
    let mut rows = Vec::new();
    #[cfg(feature = "bench-embree")]
    rows.push(embree_peer::run(job)?);
    #[cfg(feature = "bench-obvhs")]
    rows.push(obvhs_peer::run(job)?);
    let _ = job;
    Ok(rows)
}

/// Measures `peer` on every set and thread count of `job` into a row.
fn measure_all(job: &Job, name: &str, build_ms: f64, peer: &dyn Peer) -> anyhow::Result<Row> {
    let mut row = Row {
        scene: job.scene.to_string(),
        primitives: job.triangles.len(),
        accel: name.to_string(),
        build_ms,
        nodes: None,
        depth: None,
        bytes_per_prim: None,
        measurements: vec![],
    };
    for (set_name, set) in SETS.iter().zip(job.sets) {
        for &threads in job.threads {
            row.measurements.push((
                set_name,
                threads,
                measure(peer, set, threads, *set_name == "occlusion")?,
            ));
        }
    }
    eprintln!("  {}", row.summary());
    Ok(row)
}

/// Traces all rays of `set` with `peer` on `threads` threads.
fn measure(
    peer: &dyn Peer,
    set: &RaySet,
    threads: usize,
    occlusion: bool,
) -> anyhow::Result<Measurement> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let start = Instant::now();
    let hits: u64 = pool.install(|| {
        (0..set.rays.len())
            .into_par_iter()
            .with_min_len(1024)
            .map(|i| {
                let r = &set.rays[i];
                let hit = if occlusion {
                    peer.occluded(r.origin, r.dir, set.t_max[i])
                } else {
                    peer.closest(r.origin, r.dir, set.t_max[i])
                };
                u64::from(hit)
            })
            .sum()
    });
    let seconds = start.elapsed().as_secs_f64();
    Ok(Measurement {
        rays: set.rays.len() as u64,
        seconds,
        hits,
        stats: TraversalStats::default(),
    })
}

#[cfg(feature = "bench-embree")]
mod embree_peer {
    use super::{Job, Peer, measure_all};
    use cgmath::{Vector3, Vector4};
    use embree::{
        CommittedScene, Device, Geometry, IntersectContext, Ray, RayHit, Scene, TriangleMesh,
    };
    use glam::Vec3;
    use std::time::Instant;

    struct Embree<'a>(CommittedScene<'a>);

    impl Peer for Embree<'_> {
        fn closest(&self, o: Vec3, d: Vec3, t_max: f32) -> bool {
            let mut ctx = IntersectContext::incoherent();
            let mut ray = RayHit::new(Ray::segment(
                Vector3::new(o.x, o.y, o.z),
                Vector3::new(d.x, d.y, d.z),
                0.0,
                t_max,
            ));
            self.0.intersect(&mut ctx, &mut ray);
            ray.hit.hit()
        }

        fn occluded(&self, o: Vec3, d: Vec3, t_max: f32) -> bool {
            let mut ctx = IntersectContext::incoherent();
            let mut ray = Ray::segment(
                Vector3::new(o.x, o.y, o.z),
                Vector3::new(d.x, d.y, d.z),
                0.0,
                t_max,
            );
            self.0.occluded(&mut ctx, &mut ray);
            // Embree marks an occluded ray by setting tfar to −∞.
            ray.tfar == f32::NEG_INFINITY
        }
    }

    pub fn run(job: &Job) -> anyhow::Result<super::Row> {
        let device = Device::new();
        let n = job.triangles.len();
        let start = Instant::now();
        let mut mesh = TriangleMesh::unanimated(&device, n, 3 * n);
        {
            let mut verts = mesh.vertex_buffer.map();
            for (i, t) in job.triangles.iter().enumerate() {
                for (k, p) in t.iter().enumerate() {
                    verts[3 * i + k] = Vector4::new(p.x, p.y, p.z, 0.0);
                }
            }
        }
        {
            let mut ids = mesh.index_buffer.map();
            for i in 0..n {
                let b = 3 * i as u32;
                ids[i] = Vector3::new(b, b + 1, b + 2);
            }
        }
        let mut geometry = Geometry::Triangle(mesh);
        geometry.commit();
        let mut scene = Scene::new(&device);
        scene.attach_geometry(geometry);
        let committed = scene.commit();
        let build_ms = start.elapsed().as_secs_f64() * 1e3;
        measure_all(job, "embree3", build_ms, &Embree(committed))
    }
}

#[cfg(feature = "bench-obvhs")]
mod obvhs_peer {
    use super::{Job, Peer, measure_all};
    use glam::{Vec3, Vec3A};
    use obvhs::BvhBuildParams;
    use obvhs::cwbvh::CwBvh;
    use obvhs::cwbvh::builder::build_cwbvh_from_tris;
    use obvhs::ray::{Ray, RayHit};
    use obvhs::triangle::Triangle;
    use std::time::{Duration, Instant};

    struct Obvhs {
        bvh: CwBvh,
        /// Triangles in the BVH's primitive order.
        triangles: Vec<Triangle>,
    }

    impl Peer for Obvhs {
        fn closest(&self, o: Vec3, d: Vec3, t_max: f32) -> bool {
            let ray = Ray::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            let mut hit = RayHit::none();
            self.bvh
                .ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray))
        }

        fn occluded(&self, o: Vec3, d: Vec3, t_max: f32) -> bool {
            let ray = Ray::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            !self
                .bvh
                .ray_traverse_miss(ray, |ray, id| self.triangles[id].intersect(ray))
        }
    }

    pub fn run(job: &Job) -> anyhow::Result<super::Row> {
        let start = Instant::now();
        let tris: Vec<Triangle> = job
            .triangles
            .iter()
            .map(|t| Triangle {
                v0: Vec3A::from(t[0]),
                v1: Vec3A::from(t[1]),
                v2: Vec3A::from(t[2]),
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        // Reorder the triangles as its README suggests, to save an indirection per test.
        let triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| tris[i as usize])
            .collect();
        let build_ms = start.elapsed().as_secs_f64() * 1e3;
        measure_all(job, "obvhs", build_ms, &Obvhs { bvh, triangles })
    }
}
