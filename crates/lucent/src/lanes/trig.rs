//! Sine and cosine as polynomials, the same in every lane: the shared sampling code cannot call
//! the C library's `sinf` (whose bits a vector version could not reproduce).

use super::real::Real;

/// `(sin x, cos x)` for `|x| ≤ π/4`, within 2·10⁻⁷ of the true values.
///
/// The minimax polynomials of Cephes' `sinf` and `cosf` (Moshier, 1989) on that range:
/// `sin x ≈ x + x³·(s₁ + x²·(s₂ + x²·s₃))`, `cos x ≈ 1 − x²/2 + x⁴·(c₁ + x²·(c₂ + x²·c₃))`.
#[inline(always)]
pub fn sin_cos_quarter<R: Real>(x: R) -> (R, R) {
    let z = x * x;
    let sin = ((R::splat(-1.951_529_6e-4) * z + R::splat(8.332_161e-3)) * z
        - R::splat(1.666_665_5e-1))
        * z
        * x
        + x;
    let cos = ((R::splat(2.443_315_7e-5) * z - R::splat(1.388_731_6e-3)) * z
        + R::splat(4.166_664_6e-2))
        * z
        * z
        - R::splat(0.5) * z
        + R::splat(1.0);
    (sin, cos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use wide::f32x8;

    #[test]
    fn the_polynomials_are_accurate_on_their_range() {
        let n = 100_000;
        let mut worst = 0.0f64;
        for i in 0..=n {
            let x = std::f32::consts::FRAC_PI_4 * (2.0 * i as f32 / n as f32 - 1.0);
            let (s, c) = sin_cos_quarter(x);
            let (es, ec) = f64::from(x).sin_cos();
            worst = worst.max((f64::from(s) - es).abs().max((f64::from(c) - ec).abs()));
        }
        assert!(worst < 2e-7, "largest error {worst}");
        assert_eq!(sin_cos_quarter(0.0f32), (0.0, 1.0));
    }

    #[test]
    fn lanes_give_the_scalar_bits() {
        let xs: [f32; 8] = std::array::from_fn(|i| (i as f32 - 3.7) * 0.2);
        let (ws, wc) = sin_cos_quarter(f32x8::new(xs));
        for (i, &x) in xs.iter().enumerate() {
            let (s, c) = sin_cos_quarter(x);
            assert_eq!(ws.as_array()[i].to_bits(), s.to_bits());
            assert_eq!(wc.as_array()[i].to_bits(), c.to_bits());
        }
    }
}
