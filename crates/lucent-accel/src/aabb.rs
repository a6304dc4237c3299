//! Axis-aligned bounding boxes and the ray–box slab test.

use crate::Ray;
use glam::Vec3;

/// An axis-aligned box `[min, max]`; empty when any `min` component exceeds `max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The corner with the smallest coordinates.
    pub min: Vec3,
    /// The corner with the largest coordinates.
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    /// The box that contains nothing; the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// The box with the given corners.
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The smallest box holding all `points`.
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, |b, p| b.grow(p))
    }

    /// This box grown to hold `p`.
    pub fn grow(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both.
    pub fn union(self, other: Aabb) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// `max - min`.
    pub fn extent(&self) -> Vec3 {
        self.max - self.min
    }

    /// The centre point.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Surface area (0 for an empty box).
    pub fn surface_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Entry distance of `ray` into the box if it enters before `t_max`, by the slab method.
    ///
    /// Robust in the sense of Ize (2013): the far distance is widened by a few ulps so that
    /// rounding never loses a box the ray grazes. A ray parallel to a slab whose origin lies
    /// exactly in one of the slab's planes gives 0 · ∞ = NaN there; such a slab is taken as no
    /// constraint, since the origin is inside it (boundaries included).
    pub fn hit(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let t0 = (self.min - ray.origin) * ray.inv_dir;
        let t1 = (self.max - ray.origin) * ray.inv_dir;
        let in_plane = t0.is_nan_mask() | t1.is_nan_mask();
        let near = Vec3::select(in_plane, Vec3::NEG_INFINITY, t0.min(t1));
        let far = Vec3::select(in_plane, Vec3::INFINITY, t0.max(t1));
        let t_enter = near.x.max(near.y).max(near.z).max(0.0);
        // 1 + 2·gamma(3), gamma(n) = n·eps/(1 − n·eps): Ize's bound on the slab test's rounding.
        let t_exit = far.x.min(far.y).min(far.z).min(t_max) * 1.000_000_4;
        (t_enter <= t_exit).then_some(t_enter)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Aabb {
        Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0))
    }

    #[test]
    fn ray_through_the_box_enters_at_the_near_face() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        assert_eq!(unit().hit(&ray, f32::INFINITY), Some(4.0));
    }

    #[test]
    fn ray_beside_the_box_misses() {
        let ray = Ray::new(Vec3::new(2.0, 0.0, -5.0), Vec3::Z);
        assert_eq!(unit().hit(&ray, f32::INFINITY), None);
    }

    #[test]
    fn box_beyond_t_max_is_skipped() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        assert_eq!(unit().hit(&ray, 3.0), None);
    }

    #[test]
    fn ray_starting_inside_enters_at_zero() {
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(unit().hit(&ray, f32::INFINITY), Some(0.0));
    }

    #[test]
    fn ray_in_a_face_plane_is_not_lost() {
        // Origin in the plane x = 1 with dir.x = 0: (1 - 1) · inf = NaN for that slab.
        for x in [1.0, -1.0] {
            let ray = Ray::new(Vec3::new(x, 0.0, -5.0), Vec3::Z);
            assert_eq!(unit().hit(&ray, f32::INFINITY), Some(4.0));
        }
    }

    #[test]
    fn empty_box_has_no_area_and_union_identity() {
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
        assert_eq!(Aabb::EMPTY.union(unit()), unit());
        assert_eq!(unit().surface_area(), 24.0);
    }
}
