//! A 3-vector of [`Real`]s: glam's `Vec3` for one path, eight vectors in lanes for eight. Its
//! operations are glam's, in glam's order, so that `V3<f32>` gives `Vec3`'s bits.

use std::ops::{Add, Div, Mul, Neg, Sub};

use glam::Vec3;
use wide::f32x8;

use super::LANES;
use super::real::Real;

/// A 3-vector per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<R> {
    /// First coordinate.
    pub x: R,
    /// Second coordinate.
    pub y: R,
    /// Third coordinate.
    pub z: R,
}

impl<R: Real> V3<R> {
    /// The vector `(x, y, z)`.
    #[inline(always)]
    pub fn new(x: R, y: R, z: R) -> Self {
        Self { x, y, z }
    }

    /// `(v, v, v)` in every lane.
    #[inline(always)]
    pub fn splat(v: Vec3) -> Self {
        Self::new(R::splat(v.x), R::splat(v.y), R::splat(v.z))
    }

    /// `x·x' + y·y' + z·z'`, summed left to right (as glam).
    #[inline(always)]
    pub fn dot(self, o: Self) -> R {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }

    /// The cross product, as glam computes it.
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - o.y * self.z,
            self.z * o.x - o.z * self.x,
            self.x * o.y - o.x * self.y,
        )
    }

    /// `|v|²`.
    #[inline(always)]
    pub fn length_squared(self) -> R {
        self.dot(self)
    }

    /// `v · (1/|v|)`, as glam's `normalize` (not finite for a zero vector).
    #[inline(always)]
    pub fn normalize(self) -> Self {
        self * (R::splat(1.0) / self.length_squared().sqrt())
    }

    /// `v · (1/|v|)` where that reciprocal is finite and positive, else `fallback`: glam's
    /// `normalize_or`.
    #[inline(always)]
    pub fn normalize_or(self, fallback: Vec3) -> Self {
        let rcp = R::splat(1.0) / self.length_squared().sqrt();
        let usable = rcp.finite() & rcp.gt(R::splat(0.0));
        Self::select(usable, self * rcp, Self::splat(fallback))
    }

    /// `self` mirrored about unit `n`: `self − 2(n·self)·n`, as `optics::reflect`.
    #[inline(always)]
    pub fn reflect(self, n: Self) -> Self {
        self - n * (R::splat(2.0) * n.dot(self))
    }

    /// Per lane: `a` where `m`, else `b`.
    #[inline(always)]
    pub fn select(m: R::Mask, a: Self, b: Self) -> Self {
        Self::new(
            R::select(m, a.x, b.x),
            R::select(m, a.y, b.y),
            R::select(m, a.z, b.z),
        )
    }
}

impl<R: Real> Add for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<R: Real> Sub for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<R: Real> Neg for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl<R: Real> Mul<R> for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: R) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
}

impl<R: Real> Div<R> for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn div(self, s: R) -> Self {
        Self::new(self.x / s, self.y / s, self.z / s)
    }
}

impl From<Vec3> for V3<f32> {
    #[inline(always)]
    fn from(v: Vec3) -> Self {
        Self::new(v.x, v.y, v.z)
    }
}

impl From<V3<f32>> for Vec3 {
    #[inline(always)]
    fn from(v: V3<f32>) -> Self {
        Vec3::new(v.x, v.y, v.z)
    }
}

impl V3<f32x8> {
    /// Eight vectors, one per lane.
    #[inline(always)]
    pub fn gather(v: &[Vec3; LANES]) -> Self {
        Self::new(
            f32x8::new(std::array::from_fn(|i| v[i].x)),
            f32x8::new(std::array::from_fn(|i| v[i].y)),
            f32x8::new(std::array::from_fn(|i| v[i].z)),
        )
    }

    /// The vector of lane `i`.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(
            self.x.as_array()[i],
            self.y.as_array()[i],
            self.z.as_array()[i],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vectors() -> [Vec3; LANES] {
        std::array::from_fn(|i| {
            let f = i as f32;
            Vec3::new(0.3 * f - 1.1, 1.7 - 0.21 * f * f, 0.05 + f.sqrt())
        })
    }

    #[test]
    fn lanes_and_glam_agree_bit_for_bit() {
        let a = vectors();
        let b: [Vec3; LANES] = std::array::from_fn(|i| a[(i + 3) % LANES] * 1.37);
        let (wa, wb) = (V3::gather(&a), V3::gather(&b));
        for i in 0..LANES {
            let (sa, sb) = (V3::from(a[i]), V3::from(b[i]));
            assert_eq!(wa.dot(wb).as_array()[i].to_bits(), a[i].dot(b[i]).to_bits());
            assert_eq!(sa.dot(sb).to_bits(), a[i].dot(b[i]).to_bits());
            assert_eq!(wa.cross(wb).lane(i), a[i].cross(b[i]));
            assert_eq!(Vec3::from(sa.cross(sb)), a[i].cross(b[i]));
            assert_eq!(wa.normalize().lane(i), a[i].normalize());
            assert_eq!(Vec3::from(sa.normalize()), a[i].normalize());
            assert_eq!((wa + wb * wa.x).lane(i), a[i] + b[i] * a[i].x);
            assert_eq!((-(wa - wb)).lane(i), -(a[i] - b[i]));
        }
    }
}
