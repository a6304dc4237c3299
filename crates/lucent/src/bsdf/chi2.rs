//! Test support: Pearson's χ² goodness-of-fit test of a direction sampler against the density
//! it claims, as pbrt-v4 and Mitsuba 3 test their BSDFs.
//!
//! The sphere is cut into a grid of `cos θ × φ` cells (equal solid angle per cell). Samples are
//! counted per cell; the expected count of a cell is `N·∫ pdf dω` over it, integrated
//! adaptively (tensor Gauss–Legendre, refined until two levels agree). Draws that are not
//! continuous directions — Dirac lobes, or `None` — go to one more cell whose expected count
//! is `N·(1 − ∫ pdf)`. Cells expecting fewer than 5 are pooled, and the statistic is referred
//! to the χ² distribution with (cells − 1) degrees of freedom.

use glam::Vec3;

/// Test draws: the crate's generator, with uniform directions on top.
pub(super) use crate::sampling::Rng;

/// Uniform directions from a generator.
pub(super) trait Directions {
    /// A uniform direction on the unit sphere.
    fn sphere(&mut self) -> Vec3;
}

impl Directions for Rng {
    fn sphere(&mut self) -> Vec3 {
        let z = 1.0 - 2.0 * self.f32();
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = std::f32::consts::TAU * self.f32();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// Grid resolution: 20 bands of `cos θ` (0.1 wide) by 40 sectors of `φ` (9°).
const COS_BINS: usize = 20;
const PHI_BINS: usize = 40;
/// Cells expecting fewer samples than this are pooled (Pearson's rule of thumb).
const MIN_EXPECTED: f64 = 5.0;

/// The result of one test.
#[derive(Debug)]
pub(super) struct Outcome {
    /// Pearson's statistic.
    pub chi2: f64,
    /// Degrees of freedom.
    pub dof: usize,
    /// The probability of a statistic at least this large if the sampler matches its pdf.
    pub p_value: f64,
}

/// The per-test significance that keeps the chance of any false rejection among `tests`
/// independent tests at `alpha` (Šidák): `1 − (1 − α)^(1/tests)`.
pub(super) fn sidak(alpha: f64, tests: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / tests as f64)
}

/// The unit direction at `(cos θ, φ)`.
fn direction(c: f64, phi: f64) -> Vec3 {
    let s = (1.0 - c * c).max(0.0).sqrt();
    Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32)
}

/// Draw `samples` directions (`None` = not a continuous direction) and test them against
/// `pdf`. `Err` for a failure no statistic is needed for: a non-unit or non-finite direction,
/// samples where the density is zero, or a density whose integral exceeds 1.
pub(super) fn test(
    sample: &dyn Fn(&mut Rng) -> Option<Vec3>,
    pdf: &dyn Fn(Vec3) -> f32,
    samples: usize,
    seed: u64,
) -> Result<Outcome, String> {
    let mut rng = Rng::new(seed);
    let mut observed = vec![0.0f64; COS_BINS * PHI_BINS + 1];
    let other = COS_BINS * PHI_BINS;
    for _ in 0..samples {
        let Some(w) = sample(&mut rng) else {
            observed[other] += 1.0;
            continue;
        };
        if !w.is_finite() || (w.length() - 1.0).abs() > 1e-4 {
            return Err(format!("sampled a direction that is not unit: {w}"));
        }
        let i = (((w.z as f64 + 1.0) * 0.5 * COS_BINS as f64) as usize).min(COS_BINS - 1);
        let mut phi = (w.y as f64).atan2(w.x as f64);
        if phi < 0.0 {
            phi += std::f64::consts::TAU;
        }
        let j = ((phi / std::f64::consts::TAU * PHI_BINS as f64) as usize).min(PHI_BINS - 1);
        observed[i * PHI_BINS + j] += 1.0;
    }

    let f = |c: f64, phi: f64| pdf(direction(c, phi)) as f64;
    // Integration error per cell: a twentieth of a sample, or 10⁻⁴ of the cell's count, far
    // below the Poisson noise √e of any cell (at most 10⁻³ e for e ≤ 10⁶).
    let tol = Tolerance {
        abs: 0.05 / samples as f64,
        rel: 1e-4,
    };
    let mut expected = vec![0.0f64; COS_BINS * PHI_BINS + 1];
    let mut total = 0.0;
    for i in 0..COS_BINS {
        let c0 = -1.0 + 2.0 * i as f64 / COS_BINS as f64;
        let c1 = -1.0 + 2.0 * (i + 1) as f64 / COS_BINS as f64;
        for j in 0..PHI_BINS {
            let p0 = std::f64::consts::TAU * j as f64 / PHI_BINS as f64;
            let p1 = std::f64::consts::TAU * (j + 1) as f64 / PHI_BINS as f64;
            let mass = integrate(&f, [c0, c1, p0, p1], tol);
            total += mass;
            expected[i * PHI_BINS + j] = mass * samples as f64;
        }
    }
    if total > 1.0 + 1e-3 {
        return Err(format!("the pdf integrates to {total} > 1"));
    }
    expected[other] = (1.0 - total).max(0.0) * samples as f64;
    for (k, (&o, &e)) in observed.iter().zip(&expected).enumerate() {
        // An "other" cell within integration error of 0 is left to the pooled statistic.
        if e == 0.0 && o > 0.0 && k != other {
            return Err(format!("{o} samples in cell {k}, where the pdf is 0"));
        }
    }
    let (chi2, dof) = pearson(&observed, &expected)?;
    Ok(Outcome {
        chi2,
        dof,
        p_value: chi2_survival(chi2, dof),
    })
}

/// Pearson's `Σ (o − e)²/e`, pooling the cells that expect fewer than [`MIN_EXPECTED`]
/// (smallest first, until the pool itself expects enough), and its degrees of freedom.
fn pearson(observed: &[f64], expected: &[f64]) -> Result<(f64, usize), String> {
    let mut order: Vec<usize> = (0..expected.len()).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    let (mut chi2, mut cells) = (0.0, 0usize);
    for k in order {
        let (o, e) = (observed[k], expected[k]);
        if e < MIN_EXPECTED || pool_e > 0.0 && pool_e < MIN_EXPECTED {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            cells += 1;
        }
    }
    if pool_e > 0.0 {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        cells += 1;
    } else if pool_o > 0.0 {
        return Err(format!("{pool_o} samples where the pdf expects none"));
    }
    if cells < 2 {
        return Err("fewer than two cells to compare".into());
    }
    Ok((chi2, cells - 1))
}

/// 3-point Gauss–Legendre on `[c0, c1] × [p0, p1]`: exact for polynomials of degree 5 in each
/// variable.
fn gauss3(f: &dyn Fn(f64, f64) -> f64, r: [f64; 4]) -> f64 {
    let x = 0.6f64.sqrt();
    let nodes = [-x, 0.0, x];
    let weights = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let (cm, ch) = (0.5 * (r[0] + r[1]), 0.5 * (r[1] - r[0]));
    let (pm, ph) = (0.5 * (r[2] + r[3]), 0.5 * (r[3] - r[2]));
    let mut sum = 0.0;
    for (a, wa) in nodes.iter().zip(weights) {
        for (b, wb) in nodes.iter().zip(weights) {
            sum += wa * wb * f(cm + ch * a, pm + ph * b);
        }
    }
    sum * ch * ph
}

/// The four quarters of a rectangle.
fn quarters(r: [f64; 4]) -> [[f64; 4]; 4] {
    let (cm, pm) = (0.5 * (r[0] + r[1]), 0.5 * (r[2] + r[3]));
    [
        [r[0], cm, r[2], pm],
        [cm, r[1], r[2], pm],
        [r[0], cm, pm, r[3]],
        [cm, r[1], pm, r[3]],
    ]
}

/// When a piece of an integral counts as converged: its two estimates differ by at most `abs`
/// or by `rel` of the estimate.
#[derive(Clone, Copy)]
struct Tolerance {
    abs: f64,
    rel: f64,
}

impl Tolerance {
    fn accepts(self, coarse: f64, fine: f64) -> bool {
        (fine - coarse).abs() <= self.abs.max(self.rel * fine.abs())
    }

    /// The share of the absolute tolerance one of a piece's parts gets (the usual halving,
    /// not quartering: the parts' errors rarely add up).
    fn split(self, parts: f64) -> Self {
        Self {
            abs: self.abs / parts,
            rel: self.rel,
        }
    }
}

/// Refine a rectangle whose one-piece estimate is `whole` until its quarters agree with it.
fn refine(f: &dyn Fn(f64, f64) -> f64, r: [f64; 4], whole: f64, tol: Tolerance, depth: u32) -> f64 {
    let q = quarters(r);
    let parts = q.map(|s| gauss3(f, s));
    let sum: f64 = parts.iter().sum();
    if depth == 0 || tol.accepts(whole, sum) {
        return sum;
    }
    q.iter()
        .zip(parts)
        .map(|(&s, p)| refine(f, s, p, tol.split(2.0), depth - 1))
        .sum()
}

/// `∫∫ f` over a cell, starting from a 4×4 split so that a peak narrower than the cell is
/// seen by some node before the refinement decides it has converged.
fn integrate(f: &dyn Fn(f64, f64) -> f64, r: [f64; 4], tol: Tolerance) -> f64 {
    let mut sum = 0.0;
    for a in quarters(r) {
        for b in quarters(a) {
            sum += refine(f, b, gauss3(f, b), tol.split(16.0), 9);
        }
    }
    sum
}

/// `ln Γ(x)` for `x > 0`: Stirling's series (to `x⁻⁷`) after shifting `x` past 15 with
/// `Γ(x) = Γ(x + 1)/x`; the first omitted term, `1/(1188 x⁹)`, is below 3e-14 there.
fn ln_gamma(mut x: f64) -> f64 {
    let mut shift = 0.0;
    while x < 15.0 {
        shift += x.ln();
        x += 1.0;
    }
    let inv = 1.0 / x;
    let inv2 = inv * inv;
    let series = inv * (1.0 / 12.0 - inv2 * (1.0 / 360.0 - inv2 * (1.0 / 1260.0 - inv2 / 1680.0)));
    (x - 0.5) * x.ln() - x + 0.5 * std::f64::consts::TAU.ln() + series - shift
}

/// The upper regularised incomplete gamma function `Q(a, x) = Γ(a, x)/Γ(a)`: its power series
/// (for `P = 1 − Q`) below `x = a + 1`, the Legendre continued fraction (modified Lentz)
/// above, where each converges quickly.
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let prefix = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        // P(a, x) = e^{−x} x^a / Γ(a) · Σ_n x^n / (a (a+1) … (a+n)).
        let (mut term, mut sum, mut an) = (1.0 / a, 1.0 / a, a);
        for _ in 0..100_000 {
            an += 1.0;
            term *= x / an;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        (1.0 - sum * prefix).max(0.0)
    } else {
        // Q(a, x) = e^{−x} x^a / Γ(a) · 1/(x + 1 − a − 1·(1 − a)/(x + 3 − a − 2·(2 − a)/(…))).
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..100_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (prefix * h).clamp(0.0, 1.0)
    }
}

/// `P(X ≥ x)` for `X ~ χ²(dof)`: `Q(dof/2, x/2)`.
pub(super) fn chi2_survival(x: f64, dof: usize) -> f64 {
    gamma_q(dof as f64 / 2.0, x / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chi2_tail_matches_tables() {
        // Critical values from statistical tables: (x, dof, P(X ≥ x)).
        for (x, dof, p) in [
            (3.841459, 1, 0.05),
            (6.634897, 1, 0.01),
            (23.209251, 10, 0.01),
            (124.342113, 100, 0.05),
            (135.806723, 100, 0.01),
            (1.0, 3, 0.801252),
        ] {
            let got = chi2_survival(x, dof);
            assert!(
                (got - p).abs() < 1e-5 * p.max(0.01) * 10.0,
                "χ²({dof}) ≥ {x}: {got}, want {p}"
            );
        }
        // dof = 2 is the exponential: P = e^{−x/2}.
        for x in [0.5f64, 3.0, 40.0] {
            assert!((chi2_survival(x, 2) - (-x / 2.0).exp()).abs() < 1e-11);
        }
        assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
    }

    #[test]
    fn uniform_sphere_sampling_passes_and_a_biased_one_fails() {
        let uniform = |r: &mut Rng| Some(r.sphere());
        let pdf = |_: Vec3| 1.0 / (4.0 * std::f32::consts::PI);
        let out = test(&uniform, &pdf, 200_000, 1).unwrap();
        assert!(out.p_value > 1e-3, "{out:?}");
        // 5% of the samples pushed into the upper hemisphere: clearly not uniform.
        let biased = |r: &mut Rng| {
            let w = r.sphere();
            Some(if w.z < 0.0 && r.f32() < 0.1 { -w } else { w })
        };
        let out = test(&biased, &pdf, 200_000, 1).unwrap();
        assert!(out.p_value < 1e-6, "{out:?}");
        // A lost sample mass the pdf does not admit to also fails.
        let lossy = |r: &mut Rng| (r.f32() > 0.01).then(|| r.sphere());
        let out = test(&lossy, &pdf, 200_000, 1).unwrap();
        assert!(out.p_value < 1e-6, "{out:?}");
    }

    #[test]
    fn samples_where_the_pdf_is_zero_are_an_error() {
        let sphere = |r: &mut Rng| Some(r.sphere());
        let upper = |w: Vec3| {
            if w.z > 0.0 {
                1.0 / std::f32::consts::TAU
            } else {
                0.0
            }
        };
        assert!(test(&sphere, &upper, 10_000, 3).is_err());
    }
}
