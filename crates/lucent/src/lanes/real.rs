//! The number type the shared shading code is written over: `f32` for one path, [`f32x8`]
//! for eight paths in lanes. Every operation here is the same IEEE operation lane by lane
//! (no fused multiply–add, no approximations), so a lane of the wide code computes the bits
//! the scalar code computes.

use std::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Sub};

use wide::{Select, f32x8};

/// A condition per lane: `bool` for one path, a lane mask (all ones where true) for eight.
pub trait Mask:
    Copy + BitAnd<Output = Self> + BitOr<Output = Self> + BitXor<Output = Self> + Not<Output = Self>
{
    /// True when the condition holds in any lane.
    fn any(self) -> bool;
    /// True when it holds in every lane.
    fn all(self) -> bool;
    /// Per lane: `self == other`.
    #[inline(always)]
    fn same(self, other: Self) -> Self {
        !(self ^ other)
    }
}

/// A real number per lane.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Its conditions.
    type Mask: Mask;
    /// `v` in every lane.
    fn splat(v: f32) -> Self;
    /// The square root (correctly rounded, as `f32::sqrt`).
    fn sqrt(self) -> Self;
    /// `|self|`.
    fn abs(self) -> Self;
    /// The larger of the two; `other` when they are equal or either is NaN (x86's `maxps`).
    fn max(self, other: Self) -> Self;
    /// The smaller of the two; `other` when they are equal or either is NaN (x86's `minps`).
    fn min(self, other: Self) -> Self;
    /// `1` with the sign of `self` (of a zero's sign bit too, as `1f32.copysign(self)`).
    fn sign_one(self) -> Self;
    /// Per lane: `self > other`.
    fn gt(self, other: Self) -> Self::Mask;
    /// Per lane: `self >= other`.
    fn ge(self, other: Self) -> Self::Mask;
    /// Per lane: `self < other`.
    fn lt(self, other: Self) -> Self::Mask;
    /// Per lane: `self <= other`.
    fn le(self, other: Self) -> Self::Mask;
    /// Per lane: `self == other`.
    fn eq(self, other: Self) -> Self::Mask;
    /// Per lane: not NaN or infinite.
    fn finite(self) -> Self::Mask;
    /// Per lane: `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

impl Mask for bool {
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
    #[inline(always)]
    fn all(self) -> bool {
        self
    }
}

impl Real for f32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        if self > other { self } else { other }
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        if self < other { self } else { other }
    }
    #[inline(always)]
    fn sign_one(self) -> Self {
        1f32.copysign(self)
    }
    #[inline(always)]
    fn gt(self, other: Self) -> bool {
        self > other
    }
    #[inline(always)]
    fn ge(self, other: Self) -> bool {
        self >= other
    }
    #[inline(always)]
    fn lt(self, other: Self) -> bool {
        self < other
    }
    #[inline(always)]
    fn le(self, other: Self) -> bool {
        self <= other
    }
    #[inline(always)]
    fn eq(self, other: Self) -> bool {
        self == other
    }
    #[inline(always)]
    fn finite(self) -> bool {
        self.is_finite()
    }
    #[inline(always)]
    fn select(m: bool, a: Self, b: Self) -> Self {
        if m { a } else { b }
    }
}

impl Mask for f32x8 {
    #[inline(always)]
    fn any(self) -> bool {
        f32x8::any(self)
    }
    #[inline(always)]
    fn all(self) -> bool {
        f32x8::all(self)
    }
}

impl Real for f32x8 {
    type Mask = f32x8;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        f32x8::splat(v)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32x8::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32x8::abs(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        // maxps: the first where it is greater, else the second (NaN or equal included).
        self.simd_gt(other).select(self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        self.simd_lt(other).select(self, other)
    }
    #[inline(always)]
    fn sign_one(self) -> Self {
        // The sign bit of self on 1.0.
        (self & f32x8::splat(-0.0)) | f32x8::ONE
    }
    #[inline(always)]
    fn gt(self, other: Self) -> Self {
        self.simd_gt(other)
    }
    #[inline(always)]
    fn ge(self, other: Self) -> Self {
        self.simd_ge(other)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> Self {
        self.simd_lt(other)
    }
    #[inline(always)]
    fn le(self, other: Self) -> Self {
        self.simd_le(other)
    }
    #[inline(always)]
    fn eq(self, other: Self) -> Self {
        self.simd_eq(other)
    }
    #[inline(always)]
    fn finite(self) -> Self {
        self.is_finite()
    }
    #[inline(always)]
    fn select(m: Self, a: Self, b: Self) -> Self {
        Select::select(m, a, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Awkward values: zeros of both signs, NaN, infinities, subnormals, ordinary numbers.
    const VALUES: [f32; 10] = [
        0.0,
        -0.0,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1e-40,
        -2.5,
        0.75,
        1.0,
        3.0e38,
    ];

    fn lanes(f: impl Fn(usize) -> f32) -> f32x8 {
        f32x8::new(std::array::from_fn(f))
    }

    #[test]
    fn every_lane_computes_the_scalar_bits() {
        for (i, &a) in VALUES.iter().enumerate() {
            for &b in &VALUES {
                let wa = lanes(|k| if k == i % 8 { a } else { 0.5 });
                let wb = f32x8::splat(b);
                let l = i % 8;
                let bits = |x: f32x8| x.to_array()[l].to_bits();
                let mask = |x: f32x8| x.to_array()[l].to_bits() != 0;
                assert_eq!(
                    bits(Real::max(wa, wb)),
                    Real::max(a, b).to_bits(),
                    "{a} max {b}"
                );
                assert_eq!(
                    bits(Real::min(wa, wb)),
                    Real::min(a, b).to_bits(),
                    "{a} min {b}"
                );
                assert_eq!(bits(wa.sign_one()), a.sign_one().to_bits(), "{a}");
                let (ws, ss) = (Real::sqrt(wa).to_array()[l], Real::sqrt(a));
                assert!(
                    ws.to_bits() == ss.to_bits() || (ws.is_nan() && ss.is_nan()),
                    "√{a}"
                );
                assert_eq!(mask(Real::gt(wa, wb)), a > b);
                assert_eq!(mask(Real::ge(wa, wb)), a >= b);
                assert_eq!(mask(Real::lt(wa, wb)), a < b);
                assert_eq!(mask(Real::le(wa, wb)), a <= b);
                assert_eq!(mask(Real::eq(wa, wb)), a == b);
                assert_eq!(mask(Real::finite(wa)), a.is_finite());
                let m = Real::gt(wa, wb);
                let s = <f32x8 as Real>::select(m, f32x8::splat(1.0), f32x8::splat(2.0));
                assert_eq!(s.to_array()[l], if a > b { 1.0 } else { 2.0 });
            }
        }
    }

    #[test]
    fn masks_combine_as_booleans() {
        let t = f32x8::splat(1.0).simd_gt(f32x8::ZERO);
        let f = !t;
        assert!(t.all() && !f.any());
        assert!(t.same(t).all() && f.same(f).all() && !t.same(f).any());
        assert!(true.same(true) && !true.same(false));
    }
}
