//! Real roots of polynomials of degree ≤ 4 in an interval, in `f64`.
//!
//! A quartic's closed form (Ferrari's) loses most of its digits near double roots, which is
//! where a ray grazes a torus. Instead, the roots of the derivative split the interval into
//! pieces on which the polynomial is monotone; each piece whose ends differ in sign holds one
//! root, found by Newton's method kept inside a bisection bracket. The derivative's roots come
//! the same way, down to a quadratic solved in closed form. Only roots where the sign changes
//! are reported: a ray that touches a surface without crossing it does not hit it, so the
//! crossings of a closed surface always alternate between entering and leaving.

use arrayvec::ArrayVec;

/// The roots found, smallest first.
pub type Roots = ArrayVec<f64, 4>;

/// `c[0] + c[1]·x + c[2]·x² + …` at `x` (Horner).
pub fn eval(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * x + k)
}

/// The two roots of `a·x² + b·x + c` where it changes sign (a positive discriminant), smaller
/// first: the larger-magnitude root from `q = −(b + sign(b)·√disc)/2`, the other as `c/q`, so
/// that nothing nearly equal is subtracted.
pub fn quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        return (b != 0.0).then(|| {
            let x = -c / b;
            (x, x)
        });
    }
    let disc = b * b - 4.0 * a * c;
    if disc.is_nan() || disc <= 0.0 {
        return None;
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let (x0, x1) = if q == 0.0 {
        // b = 0 and c = 0 cannot give a positive discriminant with q = 0; kept for safety.
        (0.0, 0.0)
    } else {
        (c / q, q / a)
    };
    Some((x0.min(x1), x0.max(x1)))
}

/// The roots in `[lo, hi]` of the polynomial with coefficients `c` (lowest power first,
/// degree ≤ 4) at which it changes sign, smallest first.
pub fn roots_in(c: &[f64], lo: f64, hi: f64) -> Roots {
    let mut out = Roots::new();
    let degree = match c.iter().rposition(|&k| k != 0.0) {
        Some(d) => d,
        None => return out,
    };
    let c = &c[..=degree];
    let ordered = lo <= hi;
    if !ordered || c.iter().any(|k| !k.is_finite()) {
        return out;
    }
    match degree {
        0 => {}
        1 => {
            let x = -c[0] / c[1];
            if (lo..=hi).contains(&x) {
                out.push(x);
            }
        }
        2 => {
            if let Some((x0, x1)) = quadratic(c[2], c[1], c[0]) {
                out.extend([x0, x1].into_iter().filter(|x| (lo..=hi).contains(x)));
            }
        }
        _ => {
            let derivative: ArrayVec<f64, 4> = c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, &k)| k * i as f64)
                .collect();
            let mut ends = ArrayVec::<f64, 5>::new();
            ends.push(lo);
            ends.extend(
                roots_in(&derivative, lo, hi)
                    .into_iter()
                    .filter(|&x| x > lo && x < hi),
            );
            ends.push(hi);
            let signs: ArrayVec<f64, 5> = ends.iter().map(|&x| eval(c, x)).collect();
            for i in 0..ends.len() - 1 {
                let (fa, fb) = (signs[i], signs[i + 1]);
                if fa * fb < 0.0 {
                    out.push(bracketed(c, &derivative, ends[i], ends[i + 1], fa));
                } else if fa == 0.0 && i > 0 && signs[i - 1] * fb < 0.0 {
                    // Exactly zero at a critical point that the polynomial crosses.
                    out.push(ends[i]);
                }
            }
        }
    }
    out
}

/// The root of `c` in `[a, b]`, where it is monotone and `c(a) = fa` has the other sign from
/// `c(b)`: Newton steps, each replaced by bisection when it would leave the bracket.
fn bracketed(c: &[f64], derivative: &[f64], mut a: f64, mut b: f64, fa: f64) -> f64 {
    let mut x = 0.5 * (a + b);
    for _ in 0..100 {
        let fx = eval(c, x);
        if fx == 0.0 {
            return x;
        }
        if (fx < 0.0) == (fa < 0.0) {
            a = x;
        } else {
            b = x;
        }
        let newton = x - fx / eval(derivative, x);
        let next = if newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        if next == x || b - a <= f64::EPSILON * a.abs().max(b.abs()) {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The coefficients of `∏ (x − r)`.
    fn from_roots(roots: &[f64]) -> Vec<f64> {
        let mut c = vec![1.0];
        for &r in roots {
            let mut next = vec![0.0; c.len() + 1];
            for (i, &k) in c.iter().enumerate() {
                next[i + 1] += k;
                next[i] -= r * k;
            }
            c = next;
        }
        c
    }

    #[test]
    fn a_quartic_with_four_roots_gives_them_in_order() {
        let c = from_roots(&[3.0, -1.5, 0.25, 7.0]);
        let got = roots_in(&c, -10.0, 10.0);
        let want = [-1.5, 0.25, 3.0, 7.0];
        assert_eq!(got.len(), 4, "{got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{got:?}");
        }
        // Only those inside the interval.
        assert_eq!(roots_in(&c, 0.0, 5.0).as_slice().len(), 2);
    }

    #[test]
    fn a_double_root_is_touched_not_crossed() {
        // (x − 1)²(x − 3)(x + 2): crossings at −2 and 3 only.
        let got = roots_in(&from_roots(&[1.0, 1.0, 3.0, -2.0]), -5.0, 5.0);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!((got[0] + 2.0).abs() < 1e-12 && (got[1] - 3.0).abs() < 1e-12);
    }

    #[test]
    fn a_triple_root_is_crossed_once() {
        let got = roots_in(&from_roots(&[0.5, 0.5, 0.5]), -5.0, 5.0);
        assert_eq!(got.len(), 1, "{got:?}");
        assert!((got[0] - 0.5).abs() < 1e-5, "{got:?}");
    }

    #[test]
    fn the_quadratic_keeps_a_tiny_root_accurate() {
        // x² − 1e8·x + 1: roots 1e-8 and 1e8; the naive formula loses the small one.
        let (x0, x1) = quadratic(1.0, -1e8, 1.0).unwrap();
        assert!((x0 - 1e-8).abs() < 1e-20, "{x0}");
        assert!((x1 - 1e8).abs() < 1e-6, "{x1}");
        assert_eq!(quadratic(1.0, 0.0, 1.0), None);
        assert_eq!(
            quadratic(1.0, 2.0, 1.0),
            None,
            "a double root is not crossed"
        );
    }

    proptest! {
        /// Random quartics with four distinct real roots: each found, to within a tolerance
        /// set by how close the roots lie (a root's condition number).
        #[test]
        fn quartic_roots_match_the_roots_they_were_made_from(
            mut r in proptest::collection::vec(-50.0f64..50.0, 4),
            scale in 0.01f64..100.0,
        ) {
            r.sort_by(f64::total_cmp);
            let gap = r.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
            prop_assume!(gap > 1e-3);
            let c: Vec<f64> = from_roots(&r).iter().map(|k| k * scale).collect();
            let got = roots_in(&c, -60.0, 60.0);
            prop_assert_eq!(got.len(), 4, "{:?} from {:?}", got, r);
            for (g, w) in got.iter().zip(&r) {
                prop_assert!((g - w).abs() < 1e-9 * (1.0 + w.abs()) / gap.min(1.0), "{:?} vs {:?}", got, r);
            }
        }
    }
}
