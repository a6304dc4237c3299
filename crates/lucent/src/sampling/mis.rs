//! Multiple importance sampling (Veach 1997): the weights that combine a sample drawn from one
//! density with the samples another would draw, here the light's and the BSDF's.

use crate::lanes::Real;

/// The power heuristic with exponent 2 for a sample of density `a` against one of density `b`.
#[inline]
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    power_heuristic_of(a, b)
}

/// [`power_heuristic`] for any [`Real`], written once for one path and for lanes: 0 where `a`
/// is not positive or either density is NaN, 1 where `a` is infinite.
#[inline(always)]
pub fn power_heuristic_of<R: Real>(a: R, b: R) -> R {
    // As a ratio, so that squares of huge densities cannot overflow: a²/(a²+b²) = 1/(1+(b/a)²).
    let one = R::splat(1.0);
    let r = b / a;
    let w = one / (one + r * r);
    let w = R::select(a.eq(R::splat(f32::INFINITY)), one, w);
    let none = !a.gt(R::splat(0.0)) | !b.eq(b);
    R::select(none, R::splat(0.0), w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_power_heuristic_weights_sum_to_one() {
        for (a, b) in [(1.0, 1.0), (3.0, 0.5), (0.0, 2.0), (1e-20, 1e-20)] {
            let sum = power_heuristic(a, b) + power_heuristic(b, a);
            assert!((sum - 1.0).abs() < 1e-6, "{a}, {b}: {sum}");
        }
        assert_eq!(power_heuristic(f32::INFINITY, 1.0), 1.0);
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
    }
}
