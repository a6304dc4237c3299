//! Packets: up to eight camera rays of one beam through the scene at once.
//!
//! [`Scene::intersect_packet_in`] does for each ray what [`Scene::intersect_in`] does — the
//! planes the beam may reach, then the top-level primitives it touches, in the beam's order,
//! each behind the same box test — but a mesh's triangles are searched for all the rays that
//! enter its box together, through [`WideTriangleBvh::closest_hits_in`], which finds each
//! ray's own hit bit for bit. Each ray's nearest hit is then offered, taken and turned into a
//! surface exactly as alone, so the hits are the same. Beams whose primitives are not all
//! spheres and packed meshes with a cut (other accelerators, very large top levels) are traced
//! ray by ray.

use super::query::{Candidate, Nearest, inclusive, sphere_hit};
use super::{Beam, MeshAccel, Scene};
use crate::shape::{Primitive, SurfaceHit};
use arrayvec::ArrayVec;
use lucent_accel::wide_bvh::{PACKET, PackedHit};
use lucent_accel::{Ray, TraversalStats, WideTriangleBvh};

impl Scene {
    /// [`Scene::intersect_in`] for up to [`PACKET`] rays of `beam` at once (rays beyond, or
    /// beyond `out`, are not traced): `out[i]` becomes ray `i`'s hit, the same bit for bit.
    /// (Written in place: eight hits are most of a kilobyte, and moving them cost a tenth
    /// of a packet's time.)
    pub fn intersect_packet_in(
        &self,
        beam: &Beam,
        rays: &[Ray],
        stats: &mut TraversalStats,
        out: &mut [Option<SurfaceHit>],
    ) {
        let rays = &rays[..rays.len().min(PACKET).min(out.len())];
        // Spheres, and meshes with a packed tree and their cut: anything else goes ray by ray.
        let packable = beam.top.as_ref().filter(|top| {
            top.iter()
                .all(|(p, cut)| match self.primitives[*p as usize] {
                    Primitive::Sphere(_) => true,
                    _ => self.packed_mesh(*p).is_some() && cut.is_some(),
                })
        });
        // Moving objects are outside the beam's still top level: their scenes go ray by ray.
        let packable = packable.filter(|_| self.moving.is_none());
        let Some(touched) = packable else {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.intersect_in(beam, r, stats);
            }
            return;
        };
        let mut nearest: [Nearest; PACKET] = std::array::from_fn(|_| Nearest {
            t: f32::INFINITY,
            key: None,
            candidate: None,
        });
        for (ray, nearest) in rays.iter().zip(&mut nearest) {
            for (i, (plane, _)) in self.planes.iter().enumerate() {
                if !beam.planes[i] {
                    continue;
                }
                if let Some(t) = plane.intersect(ray, nearest.t) {
                    *nearest = Nearest {
                        t,
                        key: None,
                        candidate: Some(Candidate::Plane(i as u32, t)),
                    };
                }
            }
        }
        let mut t_max: [f32; PACKET] = std::array::from_fn(|i| nearest[i].t);
        for (p, cut) in touched {
            let bounds = &self.primitive_bounds[*p as usize];
            // On the stack: a packet is eight rays, and this runs per packet and primitive.
            // (A mesh with a cut needs no box test: the cut's boxes cull as well.)
            let entering: ArrayVec<usize, PACKET> = (0..rays.len())
                .filter(|&i| cut.is_some() || bounds.hit(&rays[i], t_max[i]).is_some())
                .collect();
            if entering.is_empty() {
                continue;
            }
            match (self.primitives[*p as usize], cut) {
                (Primitive::Sphere(s), _) => {
                    let sphere = &self.spheres[s as usize].0;
                    for &i in &entering {
                        if let Some(t) = sphere_hit(sphere, &rays[i], inclusive(t_max[i]), None)
                            && nearest[i].offer(t, (s, 0), Candidate::Sphere(s, t))
                        {
                            t_max[i] = nearest[i].t;
                        }
                    }
                }
                (mesh, Some(cut)) => {
                    let Some((packed, transform)) = self.packed_mesh(*p) else {
                        continue;
                    };
                    let local: ArrayVec<Ray, PACKET> = entering
                        .iter()
                        .map(|&i| transform.map_or(rays[i], |t| t.ray_to_object(&rays[i])))
                        .collect();
                    let limits: ArrayVec<f32, PACKET> =
                        entering.iter().map(|&i| t_max[i]).collect();
                    let hits = packed.closest_hits_in(cut, &local, &limits, stats);
                    for (&i, hit) in entering.iter().zip(hits) {
                        if self.offer_packed(mesh, hit, &mut nearest[i]) {
                            t_max[i] = nearest[i].t;
                        }
                    }
                }
                // Not packable: traced ray by ray above.
                (_, None) => {}
            }
        }
        for ((o, ray), nearest) in out.iter_mut().zip(rays).zip(&nearest) {
            *o = nearest.candidate.as_ref().map(|c| self.surface(ray, c));
        }
    }

    /// The packed tree of top-level primitive `p`'s mesh, and the placement its rays are
    /// carried into object space by (`None` for world space), if it has one.
    fn packed_mesh(&self, p: u32) -> Option<(&WideTriangleBvh, Option<crate::shape::Transform>)> {
        let (accel, transform) = match self.primitives[p as usize] {
            Primitive::Sphere(_) | Primitive::Solid(_) | Primitive::Csg(_) => return None,
            Primitive::Merged => (&self.merged.as_ref()?.entry.accel, None),
            Primitive::Instance(k) => {
                let instance = &self.instances[k as usize].0;
                (
                    &self.meshes[instance.mesh as usize].accel,
                    instance.transform,
                )
            }
        };
        match accel {
            MeshAccel::Packed(packed) => Some((packed, transform)),
            _ => None,
        }
    }

    /// Offers a packed tree's hit on top-level primitive `mesh` to `nearest`, as the single
    /// ray's search does; whether it was taken.
    fn offer_packed(&self, mesh: Primitive, hit: Option<PackedHit>, nearest: &mut Nearest) -> bool {
        let Some((i, hit, v)) = hit else { return false };
        match mesh {
            Primitive::Merged => {
                let Some(m) = &self.merged else { return false };
                let (k, tri) = m.source(i);
                let candidate = Candidate::Triangle(k, tri, hit, v, true);
                nearest.offer(hit.t, self.triangle_key(k, tri), candidate)
            }
            Primitive::Instance(k) => {
                let candidate = Candidate::Triangle(k, i, hit, v, false);
                nearest.offer(hit.t, self.triangle_key(k, i), candidate)
            }
            Primitive::Sphere(_) | Primitive::Solid(_) | Primitive::Csg(_) => false,
        }
    }
}
