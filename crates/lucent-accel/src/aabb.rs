//! Axis-aligned bounding boxes and the ray–box slab test.

use crate::Ray;
use glam::Vec3;

/// `1 + 2·γ(3)` with `γ(n) = n·ε / (1 − n·ε)`: Ize's bound on the slab test's rounding,
/// applied to the exit distance so that a box the ray touches is never lost.
pub const ROUNDING_SLACK: f32 = 1.000_000_4;

/// Relative slack (about 128 ulps) on every comparison of a box's entry with `t_max`, the
/// nearest hit so far. That hit's distance comes from a primitive's own test, with its own
/// rounding; without the slack, a box whose computed entry lands a few ulps beyond it could be
/// skipped although it holds a hit as near (a tie) or, by rounding, nearer.
pub const CULL_SLACK: f32 = 1.0 + 1.0 / 65536.0;

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

    /// True when a bound is NaN: the box of a primitive that no ray can hit.
    pub fn has_nan(&self) -> bool {
        self.min.is_nan() || self.max.is_nan()
    }

    /// The box itself, or [`Aabb::EMPTY`] when it has a NaN bound, so that unions stay clean.
    pub fn or_empty_if_nan(self) -> Self {
        if self.has_nan() { Self::EMPTY } else { self }
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

    /// Entry distance of `ray` into the box if it enters before `t_max`, by the slab method;
    /// boundaries count as inside. See [`Aabb::hit_interval`].
    #[inline]
    pub fn hit(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        self.hit_interval(ray, t_max).map(|(enter, _)| enter)
    }

    /// Entry and exit distances of `ray` through the box, if it enters before `t_max`; the
    /// entry is at least 0 and the exit at most `t_max` (widened as below).
    ///
    /// Robust in the sense of Ize (2013): the exit distance is widened by [`ROUNDING_SLACK`] so
    /// that rounding never loses a box the ray touches, and `t_max` by [`CULL_SLACK`]. A ray parallel to a slab whose origin
    /// lies exactly in one of the slab's planes gets `0 · ∞ = NaN` there; that slab is then no
    /// constraint, since the origin is inside it.
    #[inline]
    pub fn hit_interval(&self, ray: &Ray, t_max: f32) -> Option<(f32, f32)> {
        let t0 = (self.min - ray.origin) * ray.inv_dir;
        let t1 = (self.max - ray.origin) * ray.inv_dir;
        let in_plane = t0.is_nan_mask() | t1.is_nan_mask();
        let near = Vec3::select(in_plane, Vec3::NEG_INFINITY, t0.min(t1));
        let far = Vec3::select(in_plane, Vec3::INFINITY, t0.max(t1));
        let t_enter = near.x.max(near.y).max(near.z).max(0.0);
        let t_exit = (far.x.min(far.y).min(far.z) * ROUNDING_SLACK).min(t_max * CULL_SLACK);
        (t_enter <= t_exit).then_some((t_enter, t_exit))
    }

    /// [`Aabb::hit`] for a ray with no zero direction component (no NaN can arise): the fast
    /// path of the hierarchies' traversal loops.
    #[inline]
    pub fn hit_nonparallel(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let t0 = (self.min - ray.origin) * ray.inv_dir;
        let t1 = (self.max - ray.origin) * ray.inv_dir;
        let near = t0.min(t1);
        let far = t0.max(t1);
        let t_enter = near.x.max(near.y).max(near.z).max(0.0);
        let t_exit = (far.x.min(far.y).min(far.z) * ROUNDING_SLACK).min(t_max * CULL_SLACK);
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
        // Origin in the plane x = ±1 with dir.x = 0: (±1 ∓ 1) · ∞ = NaN for that slab.
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
