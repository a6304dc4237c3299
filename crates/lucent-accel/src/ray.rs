//! A ray with its reciprocal direction precomputed for box tests.

use glam::Vec3;

/// The half-line `origin + t · dir`, `t > 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3,
    /// Its direction; not necessarily of unit length.
    pub dir: Vec3,
    /// `1 / dir` per component (±∞ where a component is zero), for slab tests.
    pub inv_dir: Vec3,
}

impl Ray {
    /// A ray from `origin` along `dir`.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin,
            dir,
            inv_dir: dir.recip(),
        }
    }

    /// Whether the ray can be traced: a finite origin and a finite, non-zero direction. The
    /// accelerators report every other ray as missing everything.
    #[inline]
    pub fn is_traceable(&self) -> bool {
        // `0·x` is ±0 for a finite x and NaN for ±∞ and NaN: all six components in one
        // vector test (every ray made is checked, so this is on the hot path).
        let finite = self.origin * 0.0 + self.dir * 0.0;
        finite.cmpeq(Vec3::ZERO).all() && self.dir.cmpne(Vec3::ZERO).any()
    }

    /// True when a component of the direction is zero: the ray is parallel to a slab, and a
    /// slab test may meet `0 · ∞ = NaN` (see [`crate::Aabb::hit`]).
    #[inline]
    pub fn has_parallel_axis(&self) -> bool {
        self.dir.cmpeq(Vec3::ZERO).any()
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}
