//! Special functions the scattering models need: the error function and its inverse (the
//! Beckmann microfacet distribution is a Gaussian of slopes), and Gauss–Legendre quadrature
//! (for the tables of rough layers computed when a scene is built).

use std::f64::consts::PI;

/// The error function `erf(x) = 2/√π ∫₀ˣ e^(−t²) dt`: its Taylor series below ½ (exactly 0 at
/// 0), Abramowitz & Stegun 7.1.26 above (absolute error below 1.5·10⁻⁷); odd in `x`; ±1 at
/// ±∞, NaN for NaN.
pub fn erf(x: f32) -> f32 {
    if x.abs() < 0.5 {
        let x2 = x * x;
        let series = 1.0
            - x2 * (1.0 / 3.0 - x2 * (0.1 - x2 * (1.0 / 42.0 - x2 * (1.0 / 216.0 - x2 / 1320.0))));
        return std::f32::consts::FRAC_2_SQRT_PI * x * series;
    }
    const P: f32 = 0.327_591_1;
    const A: [f32; 5] = [
        0.254_829_6,
        -0.284_496_74,
        1.421_413_8,
        -1.453_152_1,
        1.061_405_4,
    ];
    let a = x.abs();
    let t = 1.0 / (1.0 + P * a);
    let poly = t * (A[0] + t * (A[1] + t * (A[2] + t * (A[3] + t * A[4]))));
    let y = 1.0 - poly * (-a * a).exp();
    y.copysign(x)
}

/// The inverse error function on `(−1, 1)`, by Giles 2010, "Approximating the erfinv function"
/// (GPU Computing Gems; relative error about 10⁻⁷ in single precision), polished by one Newton
/// step against [`erf`] so that the pair inverts each other to the precision of `erf`.
/// `x` is clamped to `±(1 − 2⁻²⁴)`: the result stays finite (|erfinv| < 4).
pub fn erfinv(x: f32) -> f32 {
    let x = x.clamp(-1.0 + f32::EPSILON * 0.5, 1.0 - f32::EPSILON * 0.5);
    let mut w = -((1.0 - x) * (1.0 + x)).ln();
    let p = if w < 5.0 {
        w -= 2.5;
        [
            3.432_739_4e-7,
            -3.523_387_7e-6,
            -4.391_506_5e-6,
            2.185_808_7e-4,
            -1.253_725e-3,
            -4.177_681_6e-3,
            0.246_640_73,
            1.501_409_4,
        ]
        .iter()
        .fold(2.810_226_4e-8, |p, c| c + p * w)
    } else {
        w = w.sqrt() - 3.0;
        [
            1.009_505_6e-4,
            1.349_343_2e-3,
            -3.673_428_4e-3,
            5.739_507_7e-3,
            -7.622_461_3e-3,
            9.438_870_5e-3,
            1.001_674,
            2.832_976_8,
        ]
        .iter()
        .fold(-2.002_142_6e-4, |p, c| c + p * w)
    };
    let y = p * x;
    // Newton on erf(y) − x: erf'(y) = 2/√π·e^(−y²).
    let derivative = std::f32::consts::FRAC_2_SQRT_PI * (-y * y).exp();
    if derivative > 1e-30 {
        y - (erf(y) - x) / derivative
    } else {
        y
    }
}

/// The `n`-point Gauss–Legendre rule on `[−1, 1]`: nodes ascending and their weights (summing
/// to 2), exact for polynomials of degree `2n − 1`. The nodes are the roots of the Legendre
/// polynomial `P_n`, found by Newton's method from Tricomi's estimate
/// `cos(π(i + 3/4)/(n + 1/2))`, in double precision.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut rule: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // P_n(x) and P_n'(x) by the three-term recurrence.
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let k = k as f64;
                    (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                }
                let pn = if n == 0 { p0 } else { p1 };
                let pn1 = if n <= 1 { 1.0 } else { p0 };
                dp = n as f64 * (x * pn - pn1) / (x * x - 1.0);
                let step = pn / dp;
                x -= step;
                if step.abs() < 1e-15 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect();
    rule.sort_by(|a, b| a.0.total_cmp(&b.0));
    rule
}

#[cfg(test)]
mod tests {
    use super::*;

    /// erf in double precision by its Taylor series (|x| ≤ 3) or continued fraction, the oracle.
    fn erf64(x: f64) -> f64 {
        if x.abs() > 3.0 {
            // erfc by Lentz's continued fraction.
            let a = x.abs();
            let mut f = a;
            let (mut c, mut d) = (a, 0.0);
            for k in 1..200 {
                let an = k as f64 / 2.0;
                d = 1.0 / (a + an * d);
                c = a + an / c;
                let delta = c * d;
                f *= delta;
                if (delta - 1.0).abs() < 1e-16 {
                    break;
                }
            }
            let erfc = (-a * a).exp() / (f * PI.sqrt());
            return (1.0 - erfc).copysign(x);
        }
        let mut term = x;
        let mut sum = x;
        for n in 1..200 {
            term *= -x * x / n as f64;
            let add = term / (2 * n + 1) as f64;
            sum += add;
            if add.abs() < 1e-17 {
                break;
            }
        }
        sum * 2.0 / PI.sqrt()
    }

    #[test]
    fn erf_matches_its_series() {
        for i in -400..=400 {
            let x = i as f32 / 80.0;
            let want = erf64(f64::from(x));
            assert!(
                (f64::from(erf(x)) - want).abs() < 3e-7,
                "erf({x}) = {} vs {want}",
                erf(x)
            );
        }
        assert_eq!(erf(f32::INFINITY), 1.0);
        assert_eq!(erf(f32::NEG_INFINITY), -1.0);
        assert!(erf(f32::NAN).is_nan());
    }

    #[test]
    fn erfinv_inverts_erf() {
        for i in -999..=999 {
            let y = i as f32 / 1000.0;
            let x = erfinv(y);
            let back = erf64(f64::from(x));
            assert!(
                (back - f64::from(y)).abs() < 6e-7,
                "erf(erfinv({y})) = {back}"
            );
        }
        for y in [1.0f32, -1.0, 0.999_999_9] {
            assert!(
                erfinv(y).is_finite() && erfinv(y).abs() < 4.0,
                "{y}: {}",
                erfinv(y)
            );
        }
        assert_eq!(erfinv(0.0), 0.0);
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        for n in [1, 2, 5, 32] {
            let rule = gauss_legendre(n);
            assert_eq!(rule.len(), n);
            let sum: f64 = rule.iter().map(|r| r.1).sum();
            assert!((sum - 2.0).abs() < 1e-12, "n {n}: weights {sum}");
            // ∫₋₁¹ x^k dx = 2/(k+1) for even k, 0 for odd, up to degree 2n − 1.
            for k in 0..2 * n as i32 {
                let got: f64 = rule.iter().map(|(x, w)| w * x.powi(k)).sum();
                let want = if k % 2 == 0 {
                    2.0 / f64::from(k + 1)
                } else {
                    0.0
                };
                assert!((got - want).abs() < 1e-12, "n {n}, x^{k}: {got} vs {want}");
            }
        }
        // Not exact beyond: x^(2n) with one node.
        let one = gauss_legendre(1);
        assert!((one.iter().map(|(x, w)| w * x * x).sum::<f64>() - 2.0 / 3.0).abs() > 0.5);
    }
}
