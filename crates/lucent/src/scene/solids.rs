//! The mathematical solids in a scene: adding them, what they may not be (yet), and their hits.

use super::Scene;
use super::SceneError;
use super::builder::SceneBuilder;
use crate::Rgb;
use crate::shape::{Solid, SurfaceHit, SurfaceId, Uv};
use lucent_accel::Ray;

impl SceneBuilder {
    /// Adds a solid (a box, cylinder, cone, disc or torus placed in the world); returns its
    /// object id.
    pub fn solid(&mut self, s: Solid, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.solids.push((s, tag));
        tag.object
    }

    /// What solids cannot be yet: area lights (their emission is not sampled) and moving.
    pub(super) fn check_solids(&self) -> Result<(), SceneError> {
        for (s, tag) in &self.solids {
            let lit = self
                .material_at(tag.material)
                .is_some_and(|m| !m.ke.is_black() && m.emission_map.is_none());
            if lit {
                return Err(SceneError::SolidCannotEmit(tag.object, s.shape.name()));
            }
            if self.motion_of(tag.object).is_some() {
                return Err(SceneError::SolidCannotMove(tag.object, s.shape.name()));
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
        SurfaceHit {
            t: t as f32,
            point: s.point,
            normal: s.normal,
            texture_coords: self.in_world(s.point),
            shading_normal: s.normal,
            uv: Uv::At(s.uv),
            color: Rgb::WHITE,
            material: tag.material,
            object: tag.object,
            surface: SurfaceId::Solid(j),
            bary: [0.0; 3],
            error: s.error,
            dpdu: s.dpdu,
            dpdv: s.dpdv,
            tangent: None,
        }
    }
}
