//! An algebraic surface: where a polynomial `P(x, y, z)` of degree at most 4 is zero, inside
//! where it is negative (POV-Ray's `quadric`, `cubic`, `quartic` and `poly`; a plane,
//! a paraboloid, a hyperboloid, a torus, a piriform…).
//!
//! Along a ray `P` is a polynomial of the same degree in the ray's parameter; its coefficients
//! come from expanding each term `x^i·y^j·z^k` with `x = oₓ + s·uₓ` and so on, about the
//! point of the line nearest the shape's origin (kept within the part of the line asked
//! for), so that a ray from far away keeps its digits. Its roots come from [`poly::roots_in`]. Such a surface may be unbounded (a
//! plane, a paraboloid): then only a combination that cuts it (an intersection, a difference)
//! or a box given with it can bound it.

use super::{Crossings, Frame, poly};
use glam::{DVec2, DVec3};

/// How many terms a polynomial of degree 4 in three variables has.
pub const TERMS: usize = 35;

/// The powers `[i, j, k]` of `x`, `y`, `z` of each coefficient, in POV-Ray's order: the
/// power of `x` from 4 down, within it that of `y`, within that of `z`.
pub const POWERS: [[u8; 3]; TERMS] = powers(4);

/// The powers of a polynomial of `degree` (≤ 4) in POV-Ray's order; the first
/// `(degree + 1)(degree + 2)(degree + 3)/6` entries are filled.
pub const fn powers(degree: u8) -> [[u8; 3]; TERMS] {
    let mut out = [[0u8; 3]; TERMS];
    let mut n = 0;
    let mut i = degree as i32;
    while i >= 0 {
        let mut j = degree as i32 - i;
        while j >= 0 {
            let mut k = degree as i32 - i - j;
            while k >= 0 {
                out[n] = [i as u8, j as u8, k as u8];
                n += 1;
                k -= 1;
            }
            j -= 1;
        }
        i -= 1;
    }
    out
}

/// How many coefficients a polynomial of `degree` has.
pub const fn term_count(degree: u8) -> usize {
    let d = degree as usize;
    (d + 1) * (d + 2) * (d + 3) / 6
}

/// A polynomial's coefficients in the order of [`POWERS`].
pub type Coefficients = [f64; TERMS];

/// The coefficients of the polynomial whose terms are `(coefficient, [i, j, k])` (powers of
/// total at most 4; a power repeated adds up); `None` when a term's degree is above 4.
pub fn from_terms(terms: &[(f64, [u8; 3])]) -> Option<Coefficients> {
    let mut c = [0.0; TERMS];
    for &(k, p) in terms {
        let at = POWERS.iter().position(|&q| q == p)?;
        c[at] += k;
    }
    Some(c)
}

/// The coefficients of POV-Ray's `poly { degree, <…> }` (and `cubic`, `quartic`): its values in
/// the order of [`powers`]`(degree)`; `None` unless there are [`term_count`]`(degree)` of them
/// and the degree is 1 to 4.
pub fn from_pov(degree: u8, values: &[f64]) -> Option<Coefficients> {
    if !(1..=4).contains(&degree) || values.len() != term_count(degree) {
        return None;
    }
    let terms: Vec<(f64, [u8; 3])> = values
        .iter()
        .zip(powers(degree))
        .map(|(&k, p)| (k, p))
        .collect();
    from_terms(&terms)
}

/// The half-space `n·x − offset < 0` (behind a plane of normal `n`), as a polynomial of
/// degree 1.
pub fn half_space(n: DVec3, offset: f64) -> Coefficients {
    let terms = [
        (n.x, [1, 0, 0]),
        (n.y, [0, 1, 0]),
        (n.z, [0, 0, 1]),
        (-offset, [0, 0, 0]),
    ];
    // Powers of degree 1 are always among the terms.
    from_terms(&terms).unwrap_or([0.0; TERMS])
}

/// The degree: the highest total power with a coefficient other than 0.
pub fn degree(c: &Coefficients) -> u8 {
    c.iter()
        .zip(POWERS)
        .filter(|(k, _)| **k != 0.0)
        .map(|(_, [i, j, k])| i + j + k)
        .max()
        .unwrap_or(0)
}

/// `x⁰ … x⁴`.
fn power_table(x: f64) -> [f64; 5] {
    let x2 = x * x;
    [1.0, x, x2, x2 * x, x2 * x2]
}

/// `P(p)`.
pub fn value(c: &Coefficients, p: DVec3) -> f64 {
    let (x, y, z) = (power_table(p.x), power_table(p.y), power_table(p.z));
    c.iter()
        .zip(POWERS)
        .filter(|(k, _)| **k != 0.0)
        .map(|(k, [i, j, l])| k * x[i as usize] * y[j as usize] * z[l as usize])
        .sum()
}

/// The gradient of `P` at `p`: the outward normal, not of unit length.
pub fn normal(c: &Coefficients, p: DVec3) -> DVec3 {
    let (x, y, z) = (power_table(p.x), power_table(p.y), power_table(p.z));
    // d/dx of x^i is i·x^(i−1); a power of 0 contributes nothing.
    let down = |t: &[f64; 5], i: u8| {
        if i == 0 {
            0.0
        } else {
            f64::from(i) * t[i as usize - 1]
        }
    };
    let mut g = DVec3::ZERO;
    for (k, [i, j, l]) in c.iter().zip(POWERS) {
        if *k == 0.0 {
            continue;
        }
        let (xi, yj, zl) = (x[i as usize], y[j as usize], z[l as usize]);
        g += *k
            * DVec3::new(
                down(&x, i) * yj * zl,
                xi * down(&y, j) * zl,
                xi * yj * down(&z, l),
            );
    }
    g
}

/// `(a₀ + a₁·s)^n` for `n` = 0..4, each lowest power first.
fn binomial_powers(a0: f64, a1: f64) -> [[f64; 5]; 5] {
    let mut out = [[0.0; 5]; 5];
    out[0][0] = 1.0;
    for n in 1..5 {
        for m in 0..=n {
            let from_lower = if m < n { out[n - 1][m] * a0 } else { 0.0 };
            let from_s = if m > 0 { out[n - 1][m - 1] * a1 } else { 0.0 };
            out[n][m] = from_lower + from_s;
        }
    }
    out
}

/// The coefficients, lowest power first, of `s ↦ P(o + s·u)`.
pub fn along(c: &Coefficients, o: DVec3, u: DVec3) -> [f64; 5] {
    let (x, y, z) = (
        binomial_powers(o.x, u.x),
        binomial_powers(o.y, u.y),
        binomial_powers(o.z, u.z),
    );
    let mut out = [0.0; 5];
    for (k, [i, j, l]) in c.iter().zip(POWERS) {
        if *k == 0.0 {
            continue;
        }
        let (px, py, pz) = (&x[i as usize], &y[j as usize], &z[l as usize]);
        // The product of three polynomials whose degrees add up to at most 4.
        for a in 0..=i as usize {
            for b in 0..=j as usize {
                let ab = px[a] * py[b];
                if ab == 0.0 {
                    continue;
                }
                for (e, zc) in pz.iter().enumerate().take(l as usize + 1) {
                    out[a + b + e] += k * ab * zc;
                }
            }
        }
    }
    out
}

/// Cauchy's bound: every real root of `q` (lowest power first) lies within it of 0.
fn root_bound(q: &[f64; 5]) -> Option<f64> {
    let n = q.iter().rposition(|&k| k != 0.0)?;
    let lead = q[n].abs();
    Some(1.0 + q[..n].iter().fold(0.0f64, |m, k| m.max(k.abs() / lead)))
}

/// The crossings of the line `o + t·d` with the surface for `t` in `[t0, t1]` (the part of
/// the line in the shape's box, or as wide as asked when it has none; either end may be
/// infinite).
pub fn crossings(c: &Coefficients, o: DVec3, d: DVec3, [t0, t1]: [f64; 2], out: &mut Crossings) {
    let length = d.length();
    if !(length > 0.0 && t0 <= t1) {
        return;
    }
    // Expand about the nearest point to the origin, kept within the range.
    let nearest = -o.dot(d) / (length * length);
    let base = nearest.clamp(t0, t1);
    if !base.is_finite() {
        return;
    }
    let u = d / length;
    let q = along(c, o + d * base, u);
    let Some(bound) = root_bound(&q) else {
        return;
    };
    let lo = ((t0 - base) * length).max(-bound);
    let hi = ((t1 - base) * length).min(bound);
    for s in poly::roots_in(&q, lo, hi) {
        out.push((base + s / length, 0));
    }
}

/// Coordinates: `(x, y)`, with two directions across the normal as the tangents (an
/// algebraic surface has no parametrisation of its own).
pub fn frame(c: &Coefficients, p: DVec3) -> Frame {
    let n = normal(c, p).normalize_or(DVec3::Z);
    let (dpdu, dpdv) = n.any_orthonormal_pair();
    Frame {
        uv: DVec2::new(p.x, p.y),
        dpdu,
        dpdv,
    }
}

/// Whether `p` lies inside: where the polynomial is negative.
pub fn contains(c: &Coefficients, p: DVec3) -> bool {
    value(c, p) < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::solid::torus;

    fn unit_sphere() -> Coefficients {
        from_terms(&[
            (1.0, [2, 0, 0]),
            (1.0, [0, 2, 0]),
            (1.0, [0, 0, 2]),
            (-1.0, [0, 0, 0]),
        ])
        .unwrap()
    }

    fn all(c: &Coefficients, o: DVec3, d: DVec3, range: [f64; 2]) -> Vec<f64> {
        let mut out = Crossings::new();
        crossings(c, o, d, range, &mut out);
        out.iter().map(|x| x.0).collect()
    }

    #[test]
    fn the_orders_are_povrays() {
        assert_eq!(term_count(2), 10);
        assert_eq!(term_count(3), 20);
        assert_eq!(term_count(4), 35);
        assert_eq!(POWERS[0], [4, 0, 0]);
        assert_eq!(POWERS[3], [3, 0, 0]);
        assert_eq!(POWERS[25], [0, 2, 0]);
        assert_eq!(POWERS[32], [0, 0, 2]);
        assert_eq!(POWERS[34], [0, 0, 0]);
        assert_eq!(powers(2)[..10][9], [0, 0, 0]);
        assert_eq!(powers(3)[0], [3, 0, 0]);
    }

    #[test]
    fn a_sphere_as_a_quadric_is_hit_at_known_t() {
        let c = unit_sphere();
        let o = DVec3::new(0.0, 0.0, -5.0);
        let got = all(&c, o, DVec3::Z * 2.0, [f64::NEG_INFINITY, f64::INFINITY]);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(
            (got[0] - 2.0).abs() < 1e-12 && (got[1] - 3.0).abs() < 1e-12,
            "{got:?}"
        );
        let n = normal(&c, o + DVec3::Z * 4.0).normalize();
        assert!((n - DVec3::NEG_Z).length() < 1e-12);
        assert!(contains(&c, DVec3::splat(0.5)) && !contains(&c, DVec3::splat(0.6)));
        // From inside, with the range limited: only the way out.
        let got = all(&c, DVec3::ZERO, DVec3::X, [0.0, 10.0]);
        assert_eq!(got.len(), 1);
        assert!((got[0] - 1.0).abs() < 1e-12);
        // A ray that misses.
        assert!(all(&c, DVec3::new(0.0, 1.5, -5.0), DVec3::Z, [-1e9, 1e9]).is_empty());
    }

    #[test]
    fn a_plane_is_met_once_and_a_parallel_ray_never() {
        // y − 1 = 0.
        let c = from_terms(&[(1.0, [0, 1, 0]), (-1.0, [0, 0, 0])]).unwrap();
        assert_eq!(half_space(DVec3::Y, 1.0), c);
        let got = all(
            &c,
            DVec3::ZERO,
            DVec3::new(3.0, 2.0, 0.0),
            [f64::NEG_INFINITY, f64::INFINITY],
        );
        assert_eq!(got, vec![0.5]);
        assert!(
            all(
                &c,
                DVec3::ZERO,
                DVec3::X,
                [f64::NEG_INFINITY, f64::INFINITY]
            )
            .is_empty()
        );
        assert_eq!(degree(&c), 1);
    }

    #[test]
    fn a_paraboloid_far_from_its_vertex_keeps_its_digits() {
        // y = x² + z²: a ray down at x = 1000 meets it at y = 10⁶.
        let c = from_terms(&[(1.0, [2, 0, 0]), (1.0, [0, 0, 2]), (-1.0, [0, 1, 0])]).unwrap();
        let o = DVec3::new(1000.0, 2e6, 0.0);
        let got = all(&c, o, DVec3::NEG_Y, [0.0, f64::INFINITY]);
        assert_eq!(got.len(), 1, "{got:?}");
        assert!((got[0] - 1e6).abs() < 1e-6, "{got:?}");
    }

    #[test]
    fn a_torus_as_a_quartic_agrees_with_the_torus() {
        // (x² + y² + z² + R² − r²)² − 4R²(x² + y²) with R = 1, r = 0.3, as in POV-Ray's
        // quartic torus, expanded.
        let r2: f64 = 0.09;
        let e = 1.0 - r2;
        let c = from_terms(&[
            (1.0, [4, 0, 0]),
            (1.0, [0, 4, 0]),
            (1.0, [0, 0, 4]),
            (2.0, [2, 2, 0]),
            (2.0, [2, 0, 2]),
            (2.0, [0, 2, 2]),
            (2.0 * e - 4.0, [2, 0, 0]),
            (2.0 * e - 4.0, [0, 2, 0]),
            (2.0 * e, [0, 0, 2]),
            (e * e, [0, 0, 0]),
        ])
        .unwrap();
        let mut next = super::super::test_stream(12345);
        let mut hit = 0;
        for _ in 0..500 {
            let o = DVec3::new(next(), next(), next()) * 3.0;
            // Aimed at the torus's box, so that most meet it and some graze it.
            let d = DVec3::new(next() * 1.3, next() * 1.3, next() * 0.3) - o;
            // The part of the line in the torus's box, as a solid passes it.
            let (lo, hi) = torus::bounds(0.3);
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            let range = [a.min(b).max_element(), a.max(b).min_element()];
            if range[0] > range[1] {
                continue;
            }
            let ours = all(&c, o, d, [-1e3, 1e3]);
            let mut reference = Crossings::new();
            torus::crossings(o, d, 0.3, range, &mut reference);
            assert_eq!(
                ours.len(),
                reference.len(),
                "{o} {d}: {ours:?} vs {reference:?}"
            );
            hit += usize::from(!ours.is_empty());
            for (a, b) in ours.iter().zip(&reference) {
                assert!((a - b.0).abs() < 1e-7, "{o} {d}: {ours:?} vs {reference:?}");
            }
            for &t in &ours {
                let p = o + d * t;
                let want = torus::normal(p, 0.3).normalize();
                assert!((normal(&c, p).normalize() - want).length() < 1e-6);
            }
        }
        assert!(hit > 250, "only {hit} of the rays met the torus");
    }

    #[test]
    fn pov_values_map_in_order_and_bad_counts_are_refused() {
        // POV-Ray's piriform: 4x⁴ − 4x³ + y² + z².
        let mut v = [0.0; 35];
        v[0] = 4.0;
        v[3] = -4.0;
        v[25] = 1.0;
        v[32] = 1.0;
        let c = from_pov(4, &v).unwrap();
        let p = DVec3::new(0.5, 0.2, 0.1);
        let want = 4.0 * 0.0625 - 4.0 * 0.125 + 0.04 + 0.01;
        assert!((value(&c, p) - want).abs() < 1e-15);
        // A quadric's ten: x² + y² + z² − 1 is terms 0, 4, 7 and 9 of degree 2.
        let mut q = [0.0; 10];
        q[0] = 1.0;
        q[4] = 1.0;
        q[7] = 1.0;
        q[9] = -1.0;
        assert_eq!(from_pov(2, &q), Some(unit_sphere()));
        assert_eq!(from_pov(4, &q), None);
        assert_eq!(from_pov(5, &[0.0; 56]), None);
    }

    #[test]
    fn the_gradient_matches_finite_differences() {
        let c = from_pov(
            3,
            &(0..20).map(|i| (i as f64 * 0.37).sin()).collect::<Vec<_>>(),
        )
        .unwrap();
        let p = DVec3::new(0.3, -0.7, 0.45);
        let h = 1e-6;
        let fd = DVec3::new(
            value(&c, p + DVec3::X * h) - value(&c, p - DVec3::X * h),
            value(&c, p + DVec3::Y * h) - value(&c, p - DVec3::Y * h),
            value(&c, p + DVec3::Z * h) - value(&c, p - DVec3::Z * h),
        ) / (2.0 * h);
        assert!(
            (normal(&c, p) - fd).length() < 1e-7,
            "{} vs {fd}",
            normal(&c, p)
        );
    }
}
