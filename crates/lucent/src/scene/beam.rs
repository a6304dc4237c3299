//! Beams through the scene: what the rays of one screen tile can hit, found once per tile.
//!
//! A [`Beam`] is made from a [`Frustum`] (the tile's corner rays from a pinhole) by
//! [`Scene::beam`]: the infinite planes some ray of it may reach, the top-level primitives
//! whose boxes it touches, and for each mesh among them the [`Cut`] of its wide BVH where the
//! rays start (the subtrees the frustum touches; see `lucent_accel::wide_bvh::cut`). Then
//! [`Scene::intersect_in`] traces each ray of the tile against only those. A placed (transformed)
//! mesh gets its cut from the frustum carried into its object space, as its rays are.
//!
//! The hit is the one [`Scene::intersect`] finds, bit for bit: every culling test is
//! conservative, and the nearest hit with its tie rule does not depend on the order in which
//! primitives are offered (see the scene's module docs). The caller's part of the contract:
//! every ray traced through a beam starts at the frustum's origin and heads inside it.
//!
//! **Shadow beams.** The shadow rays from a group of points (a tile's camera hits) towards one
//! point light all lie in the cone from the light over the points' box
//! ([`Frustum::from_point_over`]); [`Scene::shadow_beam`] makes a beam of it, and
//! [`Scene::occlusion_in`] walks the blockers of each shadow ray through it: the same blockers
//! as [`Scene::occlusion`], though not in the same order.

use super::Scene;
use crate::shape::Primitive;
use crate::spawn::Leaving;
use glam::Vec3;
use lucent_accel::{Aabb, Cut, Frustum, Ray, TraversalStats};

/// Top-level primitives beyond which a beam keeps the top-level accelerator rather than a list.
const TOP_BUDGET: usize = 64;

/// Most entries of a shadow beam's cut of one mesh: its rays are cheap (any hit, often
/// stopped early), so a cut pays only while quick to make.
const SHADOW_BUDGET: usize = 16;

/// What the rays of one beam can hit (see the module's docs).
#[derive(Clone, Debug)]
pub struct Beam {
    /// For each infinite plane: whether a ray of the beam may reach it.
    pub(super) planes: Vec<bool>,
    /// The top-level primitives the frustum touches, each with its cut if it is a mesh with a
    /// wide BVH; `None`: all of them, through the top-level accelerator.
    pub(super) top: Option<Vec<(u32, Option<Cut>)>>,
}

impl Beam {
    /// Top-level primitives the beam's rays are tested against (`None`: all, through the
    /// accelerator).
    pub fn candidates(&self) -> Option<usize> {
        self.top.as_ref().map(Vec::len)
    }
}

impl Scene {
    /// What the rays inside `frustum` can hit; see the module's docs.
    pub fn beam(&self, frustum: &Frustum) -> Beam {
        self.beam_within(frustum, lucent_accel::wide_bvh::CUT_BUDGET)
    }

    /// [`Scene::beam`] with cuts of at most `budget` entries per mesh.
    fn beam_within(&self, frustum: &Frustum, budget: usize) -> Beam {
        let planes = self
            .planes
            .iter()
            .map(|(p, _)| frustum.may_reach_plane(p.point, p.normal))
            .collect();
        let top = (self.primitives.len() <= TOP_BUDGET).then(|| {
            (0..self.primitives.len() as u32)
                .filter(|&p| frustum.touches(&self.primitive_bounds[p as usize]))
                .map(|p| (p, self.cut_of(p, frustum, budget)))
                .collect()
        });
        Beam { planes, top }
    }

    /// The beam of the shadow rays from points of `origins` towards a point light at `light`
    /// (see the module's docs); `None` when the light is not clear of the box.
    pub fn shadow_beam(&self, light: Vec3, origins: &Aabb) -> Option<Beam> {
        Some(self.beam_within(&Frustum::from_point_over(light, origins)?, SHADOW_BUDGET))
    }

    /// [`Scene::occlusion`] for a shadow ray of `beam` (from a point of the box the beam was
    /// made over, towards its light, `t_max` no farther than the light): `blocker` is called
    /// for the same shapes with the same crossings, but maybe in another order; the answer is
    /// the same when `blocker`'s is independent of the order (say, "stop at the first").
    pub fn occlusion_in<F>(
        &self,
        beam: &Beam,
        ray: &Ray,
        t_max: f32,
        from: Option<Leaving>,
        stats: &mut TraversalStats,
        blocker: F,
    ) -> bool
    where
        F: FnMut(u32, u32) -> bool,
    {
        self.blockers(ray, t_max, from, Some(beam), stats, blocker)
    }

    /// The cut of top-level primitive `p`'s mesh for `frustum` (world space), if it has a wide
    /// BVH of packed triangles.
    fn cut_of(&self, p: u32, frustum: &Frustum, budget: usize) -> Option<Cut> {
        match self.primitives[p as usize] {
            Primitive::Sphere(_) | Primitive::Solid(_) | Primitive::Csg(_) => None,
            Primitive::Merged => self.merged.as_ref()?.entry.accel.cut(frustum, budget),
            Primitive::Instance(k) => {
                let instance = &self.instances[k as usize].0;
                let entry = &self.meshes[instance.mesh as usize];
                match instance.transform {
                    None => entry.accel.cut(frustum, budget),
                    Some(t) => {
                        // The corner rays in object space, as `ray_to_object` carries each ray.
                        let o = frustum.origin();
                        let local = frustum.corners().map(|d| t.ray_to_object(&Ray::new(o, d)));
                        let f = Frustum::new(local[0].origin, local.map(|r| r.dir))?;
                        entry.accel.cut(&f, budget)
                    }
                }
            }
        }
    }
}

impl super::MeshAccel {
    /// The cut of this accelerator for `frustum` (in its own space), if it is a packed wide BVH.
    fn cut(&self, frustum: &Frustum, budget: usize) -> Option<Cut> {
        match self {
            super::MeshAccel::Packed(bvh) => Some(bvh.cut_within(frustum, budget)),
            _ => None,
        }
    }
}
