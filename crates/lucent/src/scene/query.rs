//! Ray queries: the nearest surface, and what blocks a shadow ray.

use super::Beam;
use super::{MeshAccel, Scene};
use crate::Rgb;
use crate::shape::{Primitive, Roots, SurfaceHit, SurfaceId, TriangleHit, Uv, gamma, triangle};
use crate::spawn::Leaving;
use glam::{Vec2, Vec3};
use lucent_accel::wide_bvh::PackedHit;
use lucent_accel::{Accelerator, Cut, Ray, TraversalStats, WideTriangleBvh};

/// The nearest hit found so far, before its surface is worked out.
#[derive(Clone, Copy)]
pub(super) enum Candidate {
    Plane(u32, f32),
    Sphere(u32, f32),
    /// Solid, the crossing's `t` as found (in `f64`), and the part of its surface.
    Solid(u32, f64, u8),
    /// Combination of solids, and its visible crossing.
    Csg(u32, crate::shape::CsgHit),
    /// Instance, triangle, hit and vertices in the instance's object space — or in world space
    /// for a merged instance (the last field true).
    Triangle(u32, u32, TriangleHit, [Vec3; 3], bool),
}

/// The running nearest hit, with the tie rule: at equal `t`, the lower key wins, and planes
/// (which carry no key) win over everything else.
pub(super) struct Nearest {
    pub(super) t: f32,
    /// (top-level primitive, triangle) of the current candidate; `None` for a plane or nothing.
    pub(super) key: Option<(u32, u32)>,
    pub(super) candidate: Option<Candidate>,
}

impl Nearest {
    /// Takes a hit at `t` with `key` if it is nearer, or as near and first in order.
    #[inline]
    pub(super) fn offer(&mut self, t: f32, key: (u32, u32), candidate: Candidate) -> bool {
        let better = t < self.t || (t == self.t && self.key.is_some_and(|k| key < k));
        if better {
            self.t = t;
            self.key = Some(key);
            self.candidate = Some(candidate);
        }
        better
    }
}

/// What a search of one mesh's triangles updates: the running nearest hit and the counters,
/// and where the mesh's traversal starts for a beam's ray (`None`: at its root).
struct MeshSearch<'a, 'b> {
    nearest: &'a mut Nearest,
    stats: &'a mut TraversalStats,
    cut: Option<&'b Cut>,
}

/// The packed tree's nearest hit, from the beam's cut when there is one.
#[inline]
fn closest_packed(
    packed: &WideTriangleBvh,
    cut: Option<&Cut>,
    ray: &Ray,
    t_max: f32,
    skip: Option<u32>,
    stats: &mut TraversalStats,
) -> Option<PackedHit> {
    match cut {
        Some(cut) => packed.closest_hit_in(cut, ray, t_max, skip, stats),
        None => packed.closest_hit(ray, t_max, skip, stats),
    }
}

/// `t_max` moved up by one ulp, so that shape tests (which want `t < t_max`) report a hit at
/// exactly `t_max` too, for the tie rule to judge.
#[inline]
pub(super) fn inclusive(t_max: f32) -> f32 {
    if t_max < f32::INFINITY {
        t_max.next_up()
    } else {
        t_max
    }
}

/// The sphere's hit in `(0, t_max)` for a ray that may be leaving it (see [`crate::spawn`]):
/// none when leaving outwards, only the far side when leaving inwards.
#[inline]
pub(super) fn sphere_hit(
    sphere: &crate::shape::Sphere,
    ray: &Ray,
    t_max: f32,
    leaving_it: Option<bool>,
) -> Option<f32> {
    match leaving_it {
        None => sphere.intersect(ray, t_max),
        Some(true) => None,
        Some(false) => match sphere.roots(ray) {
            Roots::Pierce(_, t1) if t1 > 0.0 && t1 < t_max => Some(t1),
            _ => None,
        },
    }
}

/// Whether `from` leaves sphere `i`, and outwards.
#[inline]
fn leaving_sphere(from: Option<Leaving>, i: u32) -> Option<bool> {
    from.filter(|l| l.surface == SurfaceId::Sphere(i))
        .map(|l| l.outward)
}

/// The triangle of instance `k` that `from` leaves, if any.
#[inline]
fn leaving_triangle(from: Option<Leaving>, k: u32) -> Option<u32> {
    match from?.surface {
        SurfaceId::Triangle { instance, index } if instance == k => Some(index),
        _ => None,
    }
}

/// The merged triangle that `from` leaves, if any.
#[inline]
fn merged_skip(m: &super::Merged, from: Option<Leaving>) -> Option<u32> {
    match from?.surface {
        SurfaceId::Triangle { instance, index } => m.index(instance, index),
        _ => None,
    }
}

/// Calls `blocker(triangle)` for the triangles of `entry` on `local` (the ray in the mesh's
/// space) in `(0, t_max)` until it returns `true`; returns whether it did.
fn blockers_in<F>(
    entry: &super::MeshEntry,
    cut: Option<&Cut>,
    local: &Ray,
    test: crate::shape::TriangleTest,
    t_max: f32,
    stats: &mut TraversalStats,
    mut blocker: F,
) -> bool
where
    F: FnMut(u32) -> bool,
{
    match &entry.accel {
        MeshAccel::Generic(accel) => accel.any_hit(local, t_max, stats, |tri| {
            test.intersect(local, entry.mesh.vertices(tri), t_max)
                .is_some()
                && blocker(tri)
        }),
        MeshAccel::Packed(packed) => match cut {
            Some(cut) => packed.any_hit_in(cut, local, t_max, stats, blocker),
            None => packed.any_hit(local, t_max, stats, blocker),
        },
        MeshAccel::Unused => false,
    }
}

impl Scene {
    /// The nearest surface along `ray` (`t > 0`), if any.
    pub fn intersect(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        self.intersect_from(ray, None, stats)
    }

    /// The nearest surface along a ray that leaves surface `from` (made by
    /// [`crate::spawn::spawn_ray`]), which is left out as the self-intersection policy says.
    pub fn intersect_from(
        &self,
        ray: &Ray,
        from: Option<Leaving>,
        stats: &mut TraversalStats,
    ) -> Option<SurfaceHit> {
        self.nearest_surface(ray, from, None, stats)
    }

    /// [`Scene::intersect`] for a ray of `beam` (from the frustum's origin, inside it): the
    /// same hit, bit for bit, tested against only what the beam can reach (see
    /// [`Scene::beam`]).
    pub fn intersect_in(
        &self,
        beam: &Beam,
        ray: &Ray,
        stats: &mut TraversalStats,
    ) -> Option<SurfaceHit> {
        self.nearest_surface(ray, None, Some(beam), stats)
    }

    fn nearest_surface(
        &self,
        ray: &Ray,
        from: Option<Leaving>,
        beam: Option<&Beam>,
        stats: &mut TraversalStats,
    ) -> Option<SurfaceHit> {
        let mut nearest = Nearest {
            t: f32::INFINITY,
            key: None,
            candidate: None,
        };
        for (i, (plane, _)) in self.planes.iter().enumerate() {
            if from.is_some_and(|l| l.surface == SurfaceId::Plane(i as u32))
                || beam.is_some_and(|b| !b.planes[i])
            {
                continue;
            }
            if let Some(t) = plane.intersect(ray, nearest.t) {
                nearest = Nearest {
                    t,
                    key: None,
                    candidate: Some(Candidate::Plane(i as u32, t)),
                };
            }
        }
        let mut mesh_stats = TraversalStats::default();
        let mut leaf =
            |primitive: Primitive, cut: Option<&Cut>, t_max: &mut f32, nearest: &mut Nearest| {
                let found = match primitive {
                    Primitive::Sphere(i) => {
                        let sphere = &self.spheres[i as usize].0;
                        match sphere_hit(sphere, ray, inclusive(*t_max), leaving_sphere(from, i)) {
                            Some(t) => nearest.offer(t, (i, 0), Candidate::Sphere(i, t)),
                            None => false,
                        }
                    }
                    Primitive::Solid(j) => match self.solid_hit(j, ray, inclusive(*t_max)) {
                        Some((t, part)) => {
                            nearest.offer(t as f32, self.solid_key(j), Candidate::Solid(j, t, part))
                        }
                        None => false,
                    },
                    Primitive::Csg(j) => match self.csg_hit(j, ray, inclusive(*t_max)) {
                        Some(h) => nearest.offer(h.t as f32, self.csg_key(j), Candidate::Csg(j, h)),
                        None => false,
                    },
                    Primitive::Instance(k) => {
                        let skip = leaving_triangle(from, k);
                        let mut search = MeshSearch {
                            nearest: &mut *nearest,
                            stats: &mut mesh_stats,
                            cut,
                        };
                        self.nearest_in_instance(k, ray, *t_max, skip, &mut search)
                    }
                    Primitive::Merged => {
                        let mut search = MeshSearch {
                            nearest: &mut *nearest,
                            stats: &mut mesh_stats,
                            cut,
                        };
                        self.nearest_in_merged(ray, *t_max, from, &mut search)
                    }
                };
                if found {
                    *t_max = nearest.t;
                }
                found
            };
        let prims = self.primitives.as_slice();
        match beam.and_then(|b| b.top.as_ref()) {
            // The primitives the beam touches, in any order: the nearest hit and its tie rule
            // do not depend on it. The box test is the one the accelerators make; a mesh with
            // a cut needs none, its cut's boxes (inside the mesh's) cull as well.
            Some(touched) => {
                let mut t_max = nearest.t;
                for (p, cut) in touched {
                    if cut.is_some() || self.primitive_bounds[*p as usize].hit(ray, t_max).is_some()
                    {
                        leaf(prims[*p as usize], cut.as_ref(), &mut t_max, &mut nearest);
                    }
                }
            }
            // One top-level primitive (a scene merged into one mesh) needs no top level.
            None if prims.len() == 1 => {
                leaf(prims[0], None, &mut { nearest.t }, &mut nearest);
            }
            None => {
                let t_max = nearest.t;
                self.accel.closest_hit(ray, t_max, stats, |p, tm| {
                    leaf(prims[p as usize], None, tm, &mut nearest)
                });
            }
        }
        // The moving objects, beyond what stands still (a beam knows only the static level);
        // the tie rule does not depend on which level a primitive is in.
        if let Some(m) = &self.moving {
            let t_max = nearest.t;
            m.accel.closest_hit(ray, t_max, stats, |p, tm| {
                leaf(m.primitives[p as usize], None, tm, &mut nearest)
            });
        }
        *stats += mesh_stats;
        nearest.candidate.as_ref().map(|c| self.surface(ray, c))
    }

    /// The tie key of triangle `tri` of instance `k`: instances after the spheres (whose key
    /// is `(sphere, 0)`), in order.
    #[inline]
    pub(super) fn triangle_key(&self, k: u32, tri: u32) -> (u32, u32) {
        (self.spheres.len() as u32 + k, tri)
    }

    /// Offers the hits of instance `k` nearer than `t_max` (or tied with it) to `nearest`,
    /// leaving out triangle `skip`; returns whether one was taken.
    fn nearest_in_instance(
        &self,
        k: u32,
        ray: &Ray,
        t_max: f32,
        skip: Option<u32>,
        search: &mut MeshSearch,
    ) -> bool {
        let MeshSearch {
            nearest,
            stats,
            cut,
        } = search;
        let instance = &self.instances[k as usize].0;
        let local = instance.transform.map_or(*ray, |t| t.ray_to_object(ray));
        let entry = &self.meshes[instance.mesh as usize];
        let key = |tri| self.triangle_key(k, tri);
        match &entry.accel {
            MeshAccel::Generic(accel) => accel.closest_hit(&local, t_max, stats, |tri, tm| {
                if skip == Some(tri) {
                    return false;
                }
                let v = entry.mesh.vertices(tri);
                match self.triangle_test.intersect(&local, v, inclusive(*tm)) {
                    Some(hit)
                        if nearest.offer(
                            hit.t,
                            key(tri),
                            Candidate::Triangle(k, tri, hit, v, false),
                        ) =>
                    {
                        *tm = hit.t;
                        true
                    }
                    _ => false,
                }
            }),
            MeshAccel::Packed(packed) => {
                match closest_packed(packed, *cut, &local, t_max, skip, stats) {
                    Some((tri, hit, v)) => {
                        nearest.offer(hit.t, key(tri), Candidate::Triangle(k, tri, hit, v, false))
                    }
                    None => false,
                }
            }
            MeshAccel::Unused => false,
        }
    }

    /// Offers the hits of the merged instances nearer than `t_max` (or tied with it) to
    /// `nearest`, leaving out the triangle `from` leaves; returns whether one was taken.
    fn nearest_in_merged(
        &self,
        ray: &Ray,
        t_max: f32,
        from: Option<Leaving>,
        search: &mut MeshSearch,
    ) -> bool {
        let MeshSearch {
            nearest,
            stats,
            cut,
        } = search;
        let Some(m) = &self.merged else { return false };
        let skip = merged_skip(m, from);
        let mut offer = |i: u32, hit: TriangleHit, v: [Vec3; 3]| {
            let (k, tri) = m.source(i);
            let candidate = Candidate::Triangle(k, tri, hit, v, true);
            nearest.offer(hit.t, self.triangle_key(k, tri), candidate)
        };
        match &m.entry.accel {
            MeshAccel::Generic(accel) => accel.closest_hit(ray, t_max, stats, |i, tm| {
                if skip == Some(i) {
                    return false;
                }
                let v = m.entry.mesh.vertices(i);
                match self.triangle_test.intersect(ray, v, inclusive(*tm)) {
                    Some(hit) if offer(i, hit, v) => {
                        *tm = hit.t;
                        true
                    }
                    _ => false,
                }
            }),
            MeshAccel::Packed(packed) => {
                match closest_packed(packed, *cut, ray, t_max, skip, stats) {
                    Some((i, hit, v)) => offer(i, hit, v),
                    None => false,
                }
            }
            MeshAccel::Unused => false,
        }
    }

    /// Whether hits on `material` need their surface's tangents (unknown indices do).
    #[inline]
    fn needs_tangents(&self, material: u32) -> bool {
        self.material_needs(material).tangents
    }

    pub(super) fn surface(&self, ray: &Ray, candidate: &Candidate) -> SurfaceHit {
        match *candidate {
            Candidate::Plane(i, t) => {
                let (plane, tag) = &self.planes[i as usize];
                // Remove the along-normal rounding error of o + t·d.
                let p = ray.at(t);
                let point = p - plane.normal * plane.normal.dot(p - plane.point);
                let coords = plane.surface_coords(point);
                SurfaceHit {
                    dpdu: plane.tangent,
                    dpdv: plane.bitangent,
                    tangent: None,
                    t,
                    point,
                    normal: plane.normal,
                    texture_coords: coords,
                    shading_normal: plane.normal,
                    uv: Uv::At(coords.truncate()),
                    color: Rgb::WHITE,
                    material: tag.material,
                    object: tag.object,
                    surface: SurfaceId::Plane(i),
                    bary: [0.0; 3],
                    error: gamma(6) * (point.abs() + plane.point.abs()),
                }
            }
            Candidate::Sphere(i, t) => {
                let (sphere, tag) = &self.spheres[i as usize];
                let point = sphere.project_to_surface(ray.at(t));
                let normal = sphere.normal_at(point);
                let map = self
                    .sphere_maps
                    .get(i as usize)
                    .copied()
                    .unwrap_or_default();
                let (dpdu, dpdv) = if self.needs_tangents(tag.material) {
                    map.tangents(normal, sphere.radius)
                } else {
                    (Vec3::ZERO, Vec3::ZERO)
                };
                SurfaceHit {
                    dpdu,
                    dpdv,
                    tangent: None,
                    t,
                    point,
                    normal,
                    texture_coords: self.in_world(point),
                    shading_normal: normal,
                    uv: Uv::Sphere(map),
                    color: Rgb::WHITE,
                    material: tag.material,
                    object: tag.object,
                    surface: SurfaceId::Sphere(i),
                    bary: [0.0; 3],
                    error: gamma(6) * (sphere.center.abs() + (point - sphere.center).abs()),
                }
            }
            Candidate::Solid(j, t, part) => self.solid_surface(j, ray, t, part),
            Candidate::Csg(j, hit) => self.csg_surface(j, ray, &hit),
            Candidate::Triangle(k, tri, hit, v, world) => {
                let (instance, tag) = &self.instances[k as usize];
                let mesh = &self.meshes[instance.mesh as usize].mesh;
                // Point and error from the vertices the ray met; normals from the object's
                // own, so that they keep their side under a mirroring placement.
                // (A merged instance without a placement is in world space as it is.)
                let object = if world && instance.transform.is_some() {
                    mesh.vertices(tri)
                } else {
                    v
                };
                let here = hit.point(v);
                let [b0, b1, b2] = hit.bary;
                let here_error =
                    gamma(7) * ((b0 * v[0]).abs() + (b1 * v[1]).abs() + (b2 * v[2]).abs());
                // A placed triangle's world normal, computed at build for merged placements
                // (see `Merged::normals`): the same bits, without two square roots and
                // divisions in a chain.
                let placed_normal = (world && mesh.normals.is_empty())
                    .then(|| self.merged.as_ref()?.normal(k, tri))
                    .flatten();
                // A triangle that was hit has an area, so its normal exists.
                let face_normal = || triangle::normal(object).unwrap_or(Vec3::Z);
                let local_normal = match placed_normal {
                    // Only the world normal is used below.
                    Some(_) => Vec3::Z,
                    None => face_normal(),
                };
                // Loaded only for the vertex attributes a mesh has: for incoherent rays it is a
                // cache miss, which was a sixth of the surface's time on a mesh without them.
                let corners = || mesh.triangles[tri as usize].map(|i| i as usize);
                let local_shading = if mesh.normals.is_empty() {
                    local_normal
                } else {
                    let n = corners()
                        .iter()
                        .zip(hit.bary)
                        .fold(Vec3::ZERO, |a, (&i, b)| a + b * mesh.normals[i]);
                    // Degenerate or reversed vertex normals fall back to / turn to the face's.
                    match n.try_normalize() {
                        Some(n) if n.dot(local_normal) < 0.0 => -n,
                        Some(n) => n,
                        None => local_normal,
                    }
                };
                let needs_tangents = self.needs_tangents(tag.material);
                let (uv, tangents) = if mesh.uvs.is_empty() {
                    let [a, b, c] = object;
                    (Vec2::new(b1, b2), (b - a, c - a))
                } else {
                    let corner_uvs = corners().map(|i| mesh.uvs[i]);
                    let uv = corner_uvs
                        .iter()
                        .zip(hit.bary)
                        .fold(Vec2::ZERO, |a, (&t, b)| a + b * t);
                    let tangents = if needs_tangents {
                        triangle::uv_tangents(object, corner_uvs)
                            .unwrap_or_else(|| face_normal().any_orthonormal_pair())
                    } else {
                        (Vec3::ZERO, Vec3::ZERO)
                    };
                    (uv, tangents)
                };
                let color = if mesh.colors.is_empty() {
                    Rgb::WHITE
                } else {
                    corners()
                        .iter()
                        .zip(hit.bary)
                        .fold(Rgb::BLACK, |a, (&i, b)| a + mesh.colors[i] * b)
                };
                let (point, error) = match instance.transform {
                    Some(t) if !world => {
                        (t.point_to_world(here), t.error_to_world(here, here_error))
                    }
                    _ => (here, here_error),
                };
                // Without vertex normals the shading normal is the face's: carried once.
                let normals_to_world = |t: &crate::shape::Transform| {
                    let normal = placed_normal.unwrap_or_else(|| t.normal_to_world(local_normal));
                    let shading = if mesh.normals.is_empty() {
                        normal
                    } else {
                        t.normal_to_world(local_shading)
                    };
                    (normal, shading)
                };
                let (normal, shading_normal, dpdu, dpdv) = match instance.transform {
                    Some(t) if needs_tangents => {
                        let (normal, shading) = normals_to_world(&t);
                        (
                            normal,
                            shading,
                            t.vector_to_world(tangents.0),
                            t.vector_to_world(tangents.1),
                        )
                    }
                    Some(t) => {
                        let (normal, shading) = normals_to_world(&t);
                        (normal, shading, Vec3::ZERO, Vec3::ZERO)
                    }
                    None if needs_tangents => (local_normal, local_shading, tangents.0, tangents.1),
                    None => (local_normal, local_shading, Vec3::ZERO, Vec3::ZERO),
                };
                let tangent = needs_tangents
                    .then(|| mesh.tangent_at(corners(), hit.bary))
                    .flatten()
                    .map(|t| match instance.transform {
                        // A mirroring placement turns the bitangent against `n × t`.
                        Some(m) => m.vector_to_world(t.truncate()).extend(t.w * m.handedness()),
                        None => t,
                    });
                SurfaceHit {
                    dpdu,
                    dpdv,
                    tangent,
                    t: hit.t,
                    point,
                    normal,
                    texture_coords: self.in_world(point),
                    shading_normal,
                    uv: Uv::At(uv),
                    color,
                    material: tag.material,
                    object: tag.object,
                    surface: SurfaceId::Triangle {
                        instance: k,
                        index: tri,
                    },
                    bary: hit.bary,
                    error,
                }
            }
        }
    }

    /// Walks the surfaces that block `ray` in `(0, t_max)`, calling `blocker(material,
    /// crossings)` for each shape (`crossings`: how many times the segment passes its surface;
    /// each triangle of a mesh counts as a shape of its own) until it returns `true`; returns
    /// whether it did. No shape is reported twice; the surface `from` is left out as the
    /// self-intersection policy says.
    pub fn occlusion<F>(
        &self,
        ray: &Ray,
        t_max: f32,
        from: Option<Leaving>,
        stats: &mut TraversalStats,
        blocker: F,
    ) -> bool
    where
        F: FnMut(u32, u32) -> bool,
    {
        self.blockers(ray, t_max, from, None, stats, blocker)
    }

    /// [`Scene::occlusion`], tested against only what `beam` can reach when there is one
    /// (see [`Scene::occlusion_in`]).
    pub(super) fn blockers<F>(
        &self,
        ray: &Ray,
        t_max: f32,
        from: Option<Leaving>,
        beam: Option<&Beam>,
        stats: &mut TraversalStats,
        mut blocker: F,
    ) -> bool
    where
        F: FnMut(u32, u32) -> bool,
    {
        for (i, (plane, tag)) in self.planes.iter().enumerate() {
            if from.is_some_and(|l| l.surface == SurfaceId::Plane(i as u32))
                || beam.is_some_and(|b| !b.planes[i])
            {
                continue;
            }
            if plane.intersect(ray, t_max).is_some() && blocker(tag.material, 1) {
                return true;
            }
        }
        let mut mesh_stats = TraversalStats::default();
        let mut leaf = |primitive: Primitive, cut: Option<&Cut>| match primitive {
            Primitive::Sphere(i) => {
                let (sphere, tag) = &self.spheres[i as usize];
                let crossings = match leaving_sphere(from, i) {
                    None => sphere.crossings(ray, t_max),
                    leaving => u32::from(sphere_hit(sphere, ray, t_max, leaving).is_some()),
                };
                crossings > 0 && blocker(tag.material, crossings)
            }
            Primitive::Solid(j) => {
                let (solid, tag) = &self.solids[j as usize];
                let crossings = solid.crossings(ray, t_max).len() as u32;
                crossings > 0 && blocker(tag.material, crossings)
            }
            Primitive::Csg(j) => {
                let (csg, tag) = &self.csgs[j as usize];
                if csg.all_wear(tag.material) {
                    let crossings = csg.crossings(ray, t_max);
                    crossings > 0 && blocker(tag.material, crossings)
                } else {
                    csg.blocking(ray, t_max, |material| blocker(material, 1))
                }
            }
            Primitive::Instance(k) => {
                let material = self.instances[k as usize].1.material;
                let skip = leaving_triangle(from, k);
                self.blockers_in_instance(k, cut, ray, t_max, &mut mesh_stats, |tri| {
                    skip != Some(tri) && blocker(material, 1)
                })
            }
            Primitive::Merged => {
                let Some(m) = &self.merged else { return false };
                let skip = merged_skip(m, from);
                let blocked = |i: u32| {
                    let k = m.owner_of(i);
                    skip != Some(i) && blocker(self.instances[k as usize].1.material, 1)
                };
                blockers_in(
                    &m.entry,
                    cut,
                    ray,
                    self.triangle_test,
                    t_max,
                    &mut mesh_stats,
                    blocked,
                )
            }
        };
        let prims = self.primitives.as_slice();
        let mut blocked = match beam.and_then(|b| b.top.as_ref()) {
            // The primitives the beam touches, with the accelerators' box test.
            Some(touched) => touched.iter().any(|(p, cut)| {
                self.primitive_bounds[*p as usize].hit(ray, t_max).is_some()
                    && leaf(prims[*p as usize], cut.as_ref())
            }),
            None if prims.len() == 1 => leaf(prims[0], None),
            None => self
                .accel
                .any_hit(ray, t_max, stats, |p| leaf(prims[p as usize], None)),
        };
        if !blocked && let Some(m) = &self.moving {
            blocked = m
                .accel
                .any_hit(ray, t_max, stats, |p| leaf(m.primitives[p as usize], None));
        }
        *stats += mesh_stats;
        blocked
    }

    /// Calls `blocker(triangle)` for the triangles of instance `k` on `ray` in `(0, t_max)`
    /// until it returns `true`; returns whether it did.
    fn blockers_in_instance<F>(
        &self,
        k: u32,
        cut: Option<&Cut>,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        blocker: F,
    ) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        let instance = &self.instances[k as usize].0;
        let local = instance.transform.map_or(*ray, |t| t.ray_to_object(ray));
        let entry = &self.meshes[instance.mesh as usize];
        blockers_in(
            entry,
            cut,
            &local,
            self.triangle_test,
            t_max,
            stats,
            blocker,
        )
    }

    /// True when anything lies on `ray` in `(0, t_max)`.
    pub fn occluded(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats) -> bool {
        self.occlusion(ray, t_max, None, stats, |_, _| true)
    }
}
