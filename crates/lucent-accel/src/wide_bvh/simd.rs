//! Eight-lane SIMD for the hot loops, with AVX2 where the processor has it.
//!
//! The traversal and triangle-pack kernels are written once, generic over [`Simd`], an
//! instruction set for eight `f32` lanes:
//! - [`Sse`]: two SSE registers (the `wide` crate's `f32x4`), on every x86-64 processor;
//! - [`Avx`]: one AVX register, for processors with AVX2. An `Avx` value exists only once AVX2
//!   and FMA have been detected ([`Avx::detect`]), which is what makes its instructions sound.
//!
//! Each query runs its kernel with `Avx` inside a twin compiled with
//! `#[target_feature(enable = "avx2,fma")]`, so that the intrinsics inline into one tight loop, or
//! with `Sse` otherwise. Every operation is the IEEE single-precision operation per lane, so
//! both give results bit for bit equal to the same arithmetic on scalars.
//!
//! This module and the calls of the AVX2 twins are the only `unsafe` code of the crate.

use super::lanes::Lanes;
use wide::f32x4;

/// Eight `f32` lanes of arithmetic; `V` is the register type.
pub trait Simd: Copy {
    /// Eight lanes.
    type V: Copy;
    /// All lanes `x`.
    fn splat(self, x: f32) -> Self::V;
    /// The lanes of `l`.
    fn load(self, l: &Lanes) -> Self::V;
    /// Back to memory.
    fn store(self, v: Self::V) -> Lanes;
    /// `a + b`.
    fn add(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a − b`.
    fn sub(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a · b`.
    fn mul(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a / b`.
    fn div(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a < b ? a : b` (the second operand when either is NaN).
    fn min(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a > b ? a : b` (the second operand when either is NaN).
    fn max(self, a: Self::V, b: Self::V) -> Self::V;
    /// Bit `i` set where `v[i]`, as a signed integer, is above zero.
    fn positive(self, v: &[u32; 8]) -> u32;
    /// Bit `i` set where `a[i] ≤ b[i]` (false for NaN).
    fn le(self, a: Self::V, b: Self::V) -> u32;
    /// Bit `i` set where `a[i] < b[i]` (false for NaN).
    fn lt(self, a: Self::V, b: Self::V) -> u32;
    /// Bit `i` set where `a[i] == b[i]` (false for NaN).
    fn eq(self, a: Self::V, b: Self::V) -> u32;
}

/// Two SSE registers per eight lanes: on every x86-64 processor (and portable elsewhere,
/// through the `wide` crate's fallbacks).
#[derive(Clone, Copy, Debug)]
pub struct Sse;

impl Simd for Sse {
    type V = [f32x4; 2];

    #[inline(always)]
    fn splat(self, x: f32) -> Self::V {
        [f32x4::splat(x); 2]
    }

    #[inline(always)]
    fn load(self, l: &Lanes) -> Self::V {
        let [a, b]: [[f32; 4]; 2] = bytemuck::cast(l.0);
        [f32x4::from(a), f32x4::from(b)]
    }

    #[inline(always)]
    fn store(self, v: Self::V) -> Lanes {
        Lanes(bytemuck::cast([v[0].to_array(), v[1].to_array()]))
    }

    #[inline(always)]
    fn add(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] + b[0], a[1] + b[1]]
    }

    #[inline(always)]
    fn sub(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] - b[0], a[1] - b[1]]
    }

    #[inline(always)]
    fn mul(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] * b[0], a[1] * b[1]]
    }

    #[inline(always)]
    fn div(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] / b[0], a[1] / b[1]]
    }

    #[inline(always)]
    fn min(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0].fast_min(b[0]), a[1].fast_min(b[1])]
    }

    #[inline(always)]
    fn max(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0].fast_max(b[0]), a[1].fast_max(b[1])]
    }

    #[inline(always)]
    fn positive(self, v: &[u32; 8]) -> u32 {
        let [a, b]: [[i32; 4]; 2] = bytemuck::cast(*v);
        let zero = wide::i32x4::ZERO;
        let mask = |x: [i32; 4]| wide::i32x4::from(x).simd_gt(zero).to_bitmask();
        mask(a) | mask(b) << 4
    }

    #[inline(always)]
    fn le(self, a: Self::V, b: Self::V) -> u32 {
        a[0].simd_le(b[0]).to_bitmask() | a[1].simd_le(b[1]).to_bitmask() << 4
    }

    #[inline(always)]
    fn lt(self, a: Self::V, b: Self::V) -> u32 {
        a[0].simd_lt(b[0]).to_bitmask() | a[1].simd_lt(b[1]).to_bitmask() << 4
    }

    #[inline(always)]
    fn eq(self, a: Self::V, b: Self::V) -> u32 {
        a[0].simd_eq(b[0]).to_bitmask() | a[1].simd_eq(b[1]).to_bitmask() << 4
    }
}

/// One AVX register per eight lanes. Only [`Avx::detect`] makes one, on a processor with AVX2
/// and FMA.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Debug)]
pub struct Avx(());

#[cfg(target_arch = "x86_64")]
impl Avx {
    /// An `Avx` when the processor has AVX2 and FMA (detected once, then cached by the
    /// standard library).
    #[inline(always)]
    pub fn detect() -> Option<Self> {
        (std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma"))
            .then_some(Avx(()))
    }
}

#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
mod avx {
    use super::{Avx, Lanes, Simd};
    use std::arch::x86_64::*;

    // SAFETY (every method): an `Avx` exists only when the processor has AVX2 and FMA (see
    // `Avx::detect`), so its AVX instructions can run; the arguments are registers, not
    // pointers, so nothing else can go wrong.
    impl Simd for Avx {
        type V = __m256;

        #[inline(always)]
        fn splat(self, x: f32) -> __m256 {
            unsafe { _mm256_set1_ps(x) }
        }

        #[inline(always)]
        fn load(self, l: &Lanes) -> __m256 {
            bytemuck::cast(l.0)
        }

        #[inline(always)]
        fn store(self, v: __m256) -> Lanes {
            Lanes(bytemuck::cast(v))
        }

        #[inline(always)]
        fn add(self, a: __m256, b: __m256) -> __m256 {
            unsafe { _mm256_add_ps(a, b) }
        }

        #[inline(always)]
        fn sub(self, a: __m256, b: __m256) -> __m256 {
            unsafe { _mm256_sub_ps(a, b) }
        }

        #[inline(always)]
        fn mul(self, a: __m256, b: __m256) -> __m256 {
            unsafe { _mm256_mul_ps(a, b) }
        }

        #[inline(always)]
        fn div(self, a: __m256, b: __m256) -> __m256 {
            unsafe { _mm256_div_ps(a, b) }
        }

        #[inline(always)]
        fn min(self, a: __m256, b: __m256) -> __m256 {
            unsafe { _mm256_min_ps(a, b) }
        }

        #[inline(always)]
        fn max(self, a: __m256, b: __m256) -> __m256 {
            unsafe { _mm256_max_ps(a, b) }
        }

        #[inline(always)]
        fn positive(self, v: &[u32; 8]) -> u32 {
            let v: __m256i = bytemuck::cast(*v);
            unsafe {
                let gt = _mm256_cmpgt_epi32(v, _mm256_setzero_si256());
                _mm256_movemask_ps(_mm256_castsi256_ps(gt)) as u32
            }
        }

        #[inline(always)]
        fn le(self, a: __m256, b: __m256) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(a, b)) as u32 }
        }

        #[inline(always)]
        fn lt(self, a: __m256, b: __m256) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(a, b)) as u32 }
        }

        #[inline(always)]
        fn eq(self, a: __m256, b: __m256) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_EQ_OQ>(a, b)) as u32 }
        }
    }
}

/// Asks the processor to start loading the cache lines of `value` (a hint: it never faults
/// and changes no result).
#[inline(always)]
pub fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let p = std::ptr::from_ref(value).cast::<i8>();
        let lines = size_of::<T>().div_ceil(64);
        for line in 0..lines {
            // SAFETY: a prefetch reads nothing and cannot fault, whatever the address; the
            // addresses are inside `value` anyway.
            #[allow(unsafe_code)]
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(p.add(line * 64));
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}
