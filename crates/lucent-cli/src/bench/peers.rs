//! Peers on the same rays: Embree 3 (Intel's CPU ray tracing kernels, through the `embree`
//! crate and Debian's `libembree-dev`) and obvhs (a Rust BVH crate: a compressed 8-wide BVH).
//! Built only with the cargo features `bench-embree` and `bench-obvhs`.
//!
//! Peers see the scene as a soup of world-space triangles, so they are measured only on scenes
//! made of meshes alone (spheres and planes are lucent's own). Each traces one ray at a time
//! (`rtcIntersect1` / `rtcOccluded1`; obvhs `ray_traverse` / `ray_traverse_miss`), as lucent does.

use super::single_ray::Contender;
use glam::Vec3;

/// Builds every peer compiled in over the world-space `triangles` (timed); one contender each.
#[allow(clippy::vec_init_then_push)] // which pushes exist depends on the features
pub fn build(triangles: &[[Vec3; 3]]) -> anyhow::Result<Vec<Contender<'static>>> {
    #[allow(unused_mut)]
    let mut peers = Vec::new();
    #[cfg(feature = "bench-embree")]
    peers.push(embree_peer::build(triangles));
    #[cfg(feature = "bench-obvhs")]
    peers.push(obvhs_peer::build(triangles));
    let _ = triangles;
    Ok(peers)
}

#[cfg(feature = "bench-embree")]
mod embree_peer {
    use super::super::single_ray::{Contender, SingleRay, least_build_time};
    use cgmath::{Vector3, Vector4};
    use embree::{
        CommittedScene, Device, Geometry, IntersectContext, Ray, RayHit, Scene, TriangleMesh,
    };
    use glam::Vec3;
    use lucent::accel::TraversalStats;
    use std::time::Instant;

    /// The device outlives the scene committed on it (both leaked: a bench builds one each
    /// per scene and exits soon after).
    struct Embree(CommittedScene<'static>);

    impl SingleRay for Embree {
        fn closest(&self, o: Vec3, d: Vec3, t_max: f32, _: &mut TraversalStats) -> bool {
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

        fn occluded(&self, o: Vec3, d: Vec3, t_max: f32, _: &mut TraversalStats) -> bool {
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

    /// Embree's structure over `triangles`, its build timed as the least of
    /// [`BUILD_ROUNDS`](super::super::single_ray::BUILD_ROUNDS) (mesh buffers filled and the
    /// scene committed). The device and the scenes are leaked, so that a committed scene (which
    /// borrows them) can outlive this call; a bench builds these per scene measured, and exits
    /// soon after.
    pub fn build(triangles: &[[Vec3; 3]]) -> Contender<'static> {
        let device: &'static Device = Box::leak(Box::new(Device::new()));
        let (committed, build_ms) = least_build_time(|| commit(device, triangles));
        Contender {
            name: "embree3".into(),
            build_ms,
            info: None,
            tracer: Box::new(Embree(committed)),
        }
    }

    /// One build of Embree's structure on `device`, and its time in milliseconds.
    fn commit(device: &'static Device, triangles: &[[Vec3; 3]]) -> (CommittedScene<'static>, f64) {
        let n = triangles.len();
        let start = Instant::now();
        let mut mesh = TriangleMesh::unanimated(device, n, 3 * n);
        {
            let mut verts = mesh.vertex_buffer.map();
            for (i, t) in triangles.iter().enumerate() {
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
        let scene: &'static mut Scene<'static> = Box::leak(Box::new(Scene::new(device)));
        scene.attach_geometry(geometry);
        let scene: &'static Scene<'static> = scene;
        let committed = scene.commit();
        (committed, start.elapsed().as_secs_f64() * 1e3)
    }
}

#[cfg(feature = "bench-obvhs")]
mod obvhs_peer {
    use super::super::single_ray::{Contender, SingleRay, least_build_time};
    use glam::{Vec3, Vec3A};
    use lucent::accel::TraversalStats;
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

    impl SingleRay for Obvhs {
        fn closest(&self, o: Vec3, d: Vec3, t_max: f32, _: &mut TraversalStats) -> bool {
            let ray = Ray::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            let mut hit = RayHit::none();
            self.bvh
                .ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray))
        }

        fn occluded(&self, o: Vec3, d: Vec3, t_max: f32, _: &mut TraversalStats) -> bool {
            let ray = Ray::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            !self
                .bvh
                .ray_traverse_miss(ray, |ray, id| self.triangles[id].intersect(ray))
        }
    }

    /// obvhs's compressed wide BVH over `triangles`, its build timed as the least of
    /// [`BUILD_ROUNDS`](super::super::single_ray::BUILD_ROUNDS).
    pub fn build(triangles: &[[Vec3; 3]]) -> Contender<'static> {
        let (tracer, build_ms) = least_build_time(|| {
            let start = Instant::now();
            let tris: Vec<Triangle> = triangles
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
            let ms = start.elapsed().as_secs_f64() * 1e3;
            (Obvhs { bvh, triangles }, ms)
        });
        Contender {
            name: "obvhs".into(),
            build_ms,
            info: None,
            tracer: Box::new(tracer),
        }
    }
}
