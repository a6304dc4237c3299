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

/// `(sin 2πu, cos 2πu)` for `u` in `[0, 1]`: the turn reduced to the nearest quarter turn
/// (`u − q/4`, exact for all but the smallest `u`), [`sin_cos_quarter`] of what is left, and
/// the quarter turns put back by swapping and negating.
#[inline(always)]
pub fn sin_cos_turn<R: Real>(u: R) -> (R, R) {
    let at = |q: f32| u.ge(R::splat(q));
    // Which quarter turn `u` is nearest: 0, ¼, ½, ¾ or 1 (the same as 0).
    let (q1, q2, q3, q4) = (at(0.125), at(0.375), at(0.625), at(0.875));
    let nearest = R::select(
        q4,
        R::splat(1.0),
        R::select(
            q3,
            R::splat(0.75),
            R::select(
                q2,
                R::splat(0.5),
                R::select(q1, R::splat(0.25), R::splat(0.0)),
            ),
        ),
    );
    let (s, c) = sin_cos_quarter(R::splat(std::f32::consts::TAU) * (u - nearest));
    // A quarter turn maps (sin, cos) to (cos, −sin); a half turn to (−sin, −cos).
    let (one, two, three) = (q1 & !q2, q2 & !q3, q3 & !q4);
    let sin = R::select(one, c, R::select(two, -s, R::select(three, -c, s)));
    let cos = R::select(one, -s, R::select(two, -c, R::select(three, s, c)));
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

    #[test]
    fn a_whole_turn_is_accurate_and_the_same_in_lanes() {
        let n = 100_000;
        let mut worst = 0.0f64;
        for i in 0..=n {
            let u = i as f32 / n as f32;
            let (s, c) = sin_cos_turn(u);
            let (es, ec) = (std::f64::consts::TAU * f64::from(u)).sin_cos();
            worst = worst.max((f64::from(s) - es).abs().max((f64::from(c) - ec).abs()));
        }
        assert!(worst < 4e-7, "largest error {worst}");
        let us: [f32; 8] = [0.0, 0.1, 0.125, 0.3, 0.5, 0.62, 0.875, 0.999_999_9];
        let (ws, wc) = sin_cos_turn(f32x8::new(us));
        for (i, &u) in us.iter().enumerate() {
            let (s, c) = sin_cos_turn(u);
            assert_eq!(ws.as_array()[i].to_bits(), s.to_bits());
            assert_eq!(wc.as_array()[i].to_bits(), c.to_bits());
        }
    }
}
