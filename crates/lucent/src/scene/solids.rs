//! The mathematical solids in a scene, alone and combined: adding them, what they may not be
//! (yet), and their hits.

use super::Scene;
use super::SceneError;
use super::builder::SceneBuilder;
use crate::Rgb;
use crate::shape::{Csg, CsgHit, Solid, SolidPoint, SurfaceHit, SurfaceId, Uv};
use lucent_accel::Ray;

impl SceneBuilder {
    /// Adds a solid (a box, cylinder, cone, disc or torus placed in the world); returns its
    /// object id.
    pub fn solid(&mut self, s: Solid, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.solids.push((s, tag));
        tag.object
    }

    /// Adds a combination of solids (its leaves carry their own materials, which shadow rays
    /// see where they cross them; `material` is the combination's as an object); returns its
    /// object id.
    pub fn csg(&mut self, c: Csg, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.csgs.push((c, tag));
        tag.object
    }

    /// What solids cannot be yet: area lights (their emission is not sampled) and moving; alone,
    /// they must be bounded; and a combination's leaves must name materials that exist.
    pub(super) fn check_solids(&self) -> Result<(), SceneError> {
        let lit = |material: u32| {
            self.material_at(material)
                .is_some_and(|m| !m.ke.is_black() && m.emission_map.is_none())
        };
        let alone = self
            .solids
            .iter()
            .map(|(s, tag)| (s.shape.name(), *tag, vec![tag.material]));
        let combined = self.csgs.iter().map(|(c, tag)| {
            let materials = (0..c.leaves() as u32).map(|i| c.material(i)).collect();
            ("combination of solids", *tag, materials)
        });
        if let Some((s, tag)) = self.solids.iter().find(|(s, _)| !s.is_bounded()) {
            return Err(SceneError::SolidUnbounded(tag.object, s.shape.name()));
        }
        for (name, tag, materials) in alone.chain(combined) {
            let count = self.material_count();
            if let Some(&material) = materials.iter().find(|&&m| m as usize >= count) {
                return Err(SceneError::NoSuchMaterial {
                    object: tag.object,
                    material,
                    count,
                });
            }
            if materials.iter().any(|&m| lit(m)) {
                return Err(SceneError::SolidCannotEmit(tag.object, name));
            }
            if self.motion_of(tag.object).is_some() {
                return Err(SceneError::SolidCannotMove(tag.object, name));
            }
        }
        Ok(())
    }
}

impl Scene {
    /// Solid `j`'s nearest crossing of `ray` in `(0, t_max)`, whose `t` is positive in `f32`
    /// too.
    #[inline]
    pub(super) fn solid_hit(&self, j: u32, ray: &Ray, t_max: f32) -> Option<(f64, u8)> {
        let (t, part) = self.solids[j as usize].0.nearest(ray, t_max)?;
        ((t as f32) > 0.0).then_some((t, part))
    }

    /// The tie key of solid `j`: after the spheres and the instances, in order.
    #[inline]
    pub(super) fn solid_key(&self, j: u32) -> (u32, u32) {
        ((self.spheres.len() + self.instances.len()) as u32 + j, 0)
    }

    /// The surface where `ray` crosses solid `j` at `t` on `part`.
    pub(super) fn solid_surface(&self, j: u32, ray: &Ray, t: f64, part: u8) -> SurfaceHit {
        let (solid, tag) = &self.solids[j as usize];
        let s = solid.surface(ray, t, part);
        self.solid_hit_at(s, t, tag.material, tag.object, SurfaceId::Solid(j))
    }

    /// Combination `j`'s nearest surface along `ray` in `(0, t_max)`, whose `t` is positive in
    /// `f32` too.
    #[inline]
    pub(super) fn csg_hit(&self, j: u32, ray: &Ray, t_max: f32) -> Option<CsgHit> {
        let hit = self.csgs[j as usize].0.nearest(ray, t_max)?;
        ((hit.t as f32) > 0.0).then_some(hit)
    }

    /// The tie key of combination `j`: after the single solids.
    #[inline]
    pub(super) fn csg_key(&self, j: u32) -> (u32, u32) {
        let before = self.spheres.len() + self.instances.len() + self.solids.len();
        (before as u32 + j, 0)
    }

    /// The surface of combination `j` at `hit` along `ray`, in its leaf's material.
    pub(super) fn csg_surface(&self, j: u32, ray: &Ray, hit: &CsgHit) -> SurfaceHit {
        let (csg, tag) = &self.csgs[j as usize];
        let s = csg.surface(ray, hit);
        let material = csg.material(hit.leaf);
        self.solid_hit_at(s, hit.t, material, tag.object, SurfaceId::Csg(j))
    }

    /// A hit on a solid's surface `s` at `t`.
    fn solid_hit_at(
        &self,
        s: SolidPoint,
        t: f64,
        material: u32,
        object: u32,
        surface: SurfaceId,
    ) -> SurfaceHit {
        SurfaceHit {
            t: t as f32,
            point: s.point,
            normal: s.normal,
            texture_coords: self.in_world(s.point),
            shading_normal: s.normal,
            uv: Uv::At(s.uv),
            color: Rgb::WHITE,
            material,
            object,
            surface,
            bary: [0.0; 3],
            error: s.error,
            dpdu: s.dpdu,
            dpdv: s.dpdv,
            tangent: None,
        }
    }
}
