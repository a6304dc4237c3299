//! Ray queries: the nearest surface, and what blocks a shadow ray.

use super::Scene;
use crate::shape::{Primitive, SurfaceHit, TriangleHit, triangle};
use lucent_accel::{Accelerator, Ray, TraversalStats};

/// The nearest hit found so far, before its surface is worked out.
#[derive(Clone, Copy)]
enum Candidate {
    Plane(u32, f32),
    Sphere(u32, f32),
    /// Instance, triangle, hit in the instance's object space.
    Triangle(u32, u32, TriangleHit),
}

/// The running nearest hit, with the tie rule: at equal `t`, the lower key wins, and planes
/// (which carry no key) win over everything else.
struct Nearest {
    t: f32,
    /// (top-level primitive, triangle) of the current candidate; `None` for a plane or nothing.
    key: Option<(u32, u32)>,
    candidate: Option<Candidate>,
}

impl Nearest {
    /// Takes a hit at `t` with `key` if it is nearer, or as near and first in order.
    #[inline]
    fn offer(&mut self, t: f32, key: (u32, u32), candidate: Candidate) -> bool {
        let better = t < self.t || (t == self.t && self.key.is_some_and(|k| key < k));
        if better {
            self.t = t;
            self.key = Some(key);
            self.candidate = Some(candidate);
        }
        better
    }
}

/// `t_max` moved up by one ulp, so that shape tests (which want `t < t_max`) report a hit at
/// exactly `t_max` too, for the tie rule to judge.
#[inline]
fn inclusive(t_max: f32) -> f32 {
    if t_max < f32::INFINITY {
        t_max.next_up()
    } else {
        t_max
    }
}

impl Scene {
    /// The nearest surface along `ray` (`t > 0`), if any.
    pub fn intersect(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        let mut nearest = Nearest {
            t: f32::INFINITY,
            key: None,
            candidate: None,
        };
        for (i, (plane, _)) in self.planes.iter().enumerate() {
            if let Some(t) = plane.intersect(ray, nearest.t) {
                nearest = Nearest {
                    t,
                    key: None,
                    candidate: Some(Candidate::Plane(i as u32, t)),
                };
            }
        }
        let test = self.triangle_test;
        let mut mesh_stats = TraversalStats::default();
        self.accel.closest_hit(ray, nearest.t, stats, |p, t_max| {
            match self.primitives[p as usize] {
                Primitive::Sphere(i) => {
                    match self.spheres[i as usize].0.intersect(ray, inclusive(*t_max)) {
                        Some(t) if nearest.offer(t, (p, 0), Candidate::Sphere(i, t)) => {
                            *t_max = t;
                            true
                        }
                        _ => false,
                    }
                }
                Primitive::Instance(k) => {
                    let instance = &self.instances[k as usize].0;
                    let local = instance.transform.map_or(*ray, |t| t.ray_to_object(ray));
                    let entry = &self.meshes[instance.mesh as usize];
                    let found =
                        entry
                            .accel
                            .closest_hit(&local, *t_max, &mut mesh_stats, |tri, tm| {
                                match test.intersect(
                                    &local,
                                    entry.mesh.vertices(tri),
                                    inclusive(*tm),
                                ) {
                                    Some(hit)
                                        if nearest.offer(
                                            hit.t,
                                            (p, tri),
                                            Candidate::Triangle(k, tri, hit),
                                        ) =>
                                    {
                                        *tm = hit.t;
                                        true
                                    }
                                    _ => false,
                                }
                            });
                    if found {
                        *t_max = nearest.t;
                    }
                    found
                }
            }
        });
        *stats += mesh_stats;
        nearest.candidate.map(|c| self.surface(ray, c))
    }

    fn surface(&self, ray: &Ray, candidate: Candidate) -> SurfaceHit {
        match candidate {
            Candidate::Plane(i, t) => {
                let (plane, tag) = &self.planes[i as usize];
                // Remove the along-normal rounding error of o + t·d.
                let p = ray.at(t);
                let point = p - plane.normal * plane.normal.dot(p - plane.point);
                let texture_coords = plane.surface_coords(point);
                SurfaceHit {
                    t,
                    point,
                    normal: plane.normal,
                    texture_coords,
                    material: tag.material,
                    object: tag.object,
                }
            }
            Candidate::Sphere(i, t) => {
                let (sphere, tag) = &self.spheres[i as usize];
                let point = sphere.project_to_surface(ray.at(t));
                let normal = sphere.normal_at(point);
                SurfaceHit {
                    t,
                    point,
                    normal,
                    texture_coords: point,
                    material: tag.material,
                    object: tag.object,
                }
            }
            Candidate::Triangle(k, tri, hit) => {
                let (instance, tag) = &self.instances[k as usize];
                let v = self.meshes[instance.mesh as usize].mesh.vertices(tri);
                let local_point = hit.point(v);
                // A triangle that was hit has an area, so its normal exists.
                let local_normal = triangle::normal(v).unwrap_or(glam::Vec3::Z);
                let (point, normal) = match instance.transform {
                    Some(t) => (
                        t.point_to_world(local_point),
                        t.normal_to_world(local_normal),
                    ),
                    None => (local_point, local_normal),
                };
                SurfaceHit {
                    t: hit.t,
                    point,
                    normal,
                    texture_coords: point,
                    material: tag.material,
                    object: tag.object,
                }
            }
        }
    }

    /// Walks the surfaces that block `ray` in `(0, t_max)`, calling `blocker(material,
    /// crossings)` for each shape (`crossings`: how many times the segment passes its surface;
    /// each triangle of a mesh counts as a shape of its own) until it returns `true`; returns
    /// whether it did. No shape is reported twice.
    pub fn occlusion<F>(
        &self,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        mut blocker: F,
    ) -> bool
    where
        F: FnMut(u32, u32) -> bool,
    {
        for (plane, tag) in &self.planes {
            if plane.intersect(ray, t_max).is_some() && blocker(tag.material, 1) {
                return true;
            }
        }
        let test = self.triangle_test;
        let mut mesh_stats = TraversalStats::default();
        let blocked =
            self.accel
                .any_hit(ray, t_max, stats, |p| match self.primitives[p as usize] {
                    Primitive::Sphere(i) => {
                        let (sphere, tag) = &self.spheres[i as usize];
                        match sphere.crossings(ray, t_max) {
                            0 => false,
                            n => blocker(tag.material, n),
                        }
                    }
                    Primitive::Instance(k) => {
                        let (instance, tag) = &self.instances[k as usize];
                        let local = instance.transform.map_or(*ray, |t| t.ray_to_object(ray));
                        let entry = &self.meshes[instance.mesh as usize];
                        entry.accel.any_hit(&local, t_max, &mut mesh_stats, |tri| {
                            test.intersect(&local, entry.mesh.vertices(tri), t_max)
                                .is_some()
                                && blocker(tag.material, 1)
                        })
                    }
                });
        *stats += mesh_stats;
        blocked
    }

    /// True when anything lies on `ray` in `(0, t_max)`.
    pub fn occluded(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats) -> bool {
        self.occlusion(ray, t_max, stats, |_, _| true)
    }
}
