//! A superellipsoid (Barr's, as POV-Ray's): `(|x|^(2/e) + |y|^(2/e))^(e/n) + |z|^(2/n) = 1` in
//! its own space, inside the cube `[-1, 1]³`. `e` shapes its cross-sections in x and y, `n`
//! along z: both 1 make the unit sphere, both near 0 the cube, 2 an octahedron.
//!
//! Its function along a ray is no polynomial. With both exponents at most 2 the solid is
//! convex and so is its function along any line: a golden-section search for a point inside
//! (stopping at the first it finds) brackets the two crossings, each refined by regula falsi
//! to `f64` precision — a few tens of evaluations, a miss included. Otherwise the crossings
//! are found by sampling: the ray's run through the cube in [`STEPS`] even steps, each sign
//! change refined the same way. Either way, two crossings closer than the search's resolution
//! (a ray grazing the surface) can be missed together, never one alone, so the crossings still
//! alternate.

use super::{Crossings, Frame, ellipsoid};
use glam::DVec3;

/// Samples of the function along the ray's run through the cube.
pub const STEPS: usize = 96;

/// The inside-outside function: negative inside, 0 on the surface.
pub fn value(p: DVec3, [e, n]: [f64; 2]) -> f64 {
    let s = p.x.abs().powf(2.0 / e) + p.y.abs().powf(2.0 / e);
    s.powf(e / n) + p.z.abs().powf(2.0 / n) - 1.0
}

/// The crossings of the line `o + t·d` for `t` in `[t0, t1]` (its run through the cube).
pub fn crossings(o: DVec3, d: DVec3, shape: [f64; 2], [t0, t1]: [f64; 2], out: &mut Crossings) {
    let usable = t0 < t1;
    if !usable {
        return;
    }
    let f = |t: f64| value(o + d * t, shape);
    if shape[0] <= 2.0 && shape[1] <= 2.0 {
        convex_crossings(&f, [t0, t1], out);
        return;
    }
    sampled_crossings(&f, [t0, t1], out);
}

/// The crossings of a convex function along `[t0, t1]` (inside where it is ≤ 0): where the
/// ends differ, one; where both are outside, a golden-section search for the least value
/// stops at the first point inside, which splits the run into two runs of one crossing each.
fn convex_crossings(f: &impl Fn(f64) -> f64, [t0, t1]: [f64; 2], out: &mut Crossings) {
    let (a, b) = ((t0, f(t0)), (t1, f(t1)));
    match (a.1 <= 0.0, b.1 <= 0.0) {
        (true, true) => {}
        (true, false) | (false, true) => out.push((refine(f, a, b), 0)),
        (false, false) => {
            if let Some(m) = inside_point(f, a, b) {
                out.push((refine(f, a, m), 0));
                out.push((refine(f, m, b), 0));
            }
        }
    }
}

/// A point of `(a, b)` where the convex `f` is ≤ 0, both ends outside: golden-section search
/// for the minimum, given up when the bracket is a millionth of the run (a graze that thin is
/// taken as a miss, both its crossings together).
fn inside_point(f: &impl Fn(f64) -> f64, a: (f64, f64), b: (f64, f64)) -> Option<(f64, f64)> {
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let (mut lo, mut hi) = (a.0, b.0);
    let tolerance = (hi - lo) * 1e-6;
    let mut x1 = hi - INV_PHI * (hi - lo);
    let mut x2 = lo + INV_PHI * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    while hi - lo > tolerance {
        if f1 <= 0.0 {
            return Some((x1, f1));
        }
        if f2 <= 0.0 {
            return Some((x2, f2));
        }
        if f1 < f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - INV_PHI * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + INV_PHI * (hi - lo);
            f2 = f(x2);
        }
    }
    None
}

/// The crossings along `[t0, t1]` by [`STEPS`] even samples, each sign change refined.
fn sampled_crossings(f: &impl Fn(f64) -> f64, [t0, t1]: [f64; 2], out: &mut Crossings) {
    let step = (t1 - t0) / STEPS as f64;
    let mut a = (t0, f(t0));
    for i in 1..=STEPS {
        let t = if i == STEPS { t1 } else { t0 + step * i as f64 };
        let b = (t, f(t));
        // A sample exactly on the surface counts as inside, so that it is crossed once.
        if (a.1 <= 0.0) != (b.1 <= 0.0) && !out.is_full() {
            out.push((refine(f, a, b), 0));
        }
        a = b;
    }
}

/// The root of `f` between `a` and `b`, one inside (≤ 0) and one outside: regula falsi with
/// the Illinois rule (the end that stays has its value halved, so that both ends move), which
/// converges in a few steps where bisection needs fifty.
fn refine(f: &impl Fn(f64) -> f64, mut a: (f64, f64), mut b: (f64, f64)) -> f64 {
    let mut kept = 0i8;
    for _ in 0..60 {
        let secant = a.0 - a.1 * (b.0 - a.0) / (b.1 - a.1);
        let m = if secant > a.0 && secant < b.0 {
            secant
        } else {
            0.5 * (a.0 + b.0)
        };
        if m <= a.0 || m >= b.0 || b.0 - a.0 <= 4.0 * f64::EPSILON * m.abs().max(1e-300) {
            return m;
        }
        let v = f(m);
        if (v <= 0.0) == (a.1 <= 0.0) {
            a = (m, v);
            if kept == 1 {
                b.1 *= 0.5;
            }
            kept = 1;
        } else {
            b = (m, v);
            if kept == -1 {
                a.1 *= 0.5;
            }
            kept = -1;
        }
    }
    0.5 * (a.0 + b.0)
}

/// The outward normal at `p`: the function's gradient, from whichever terms are finite there.
pub fn normal(p: DVec3, [e, n]: [f64; 2]) -> DVec3 {
    let s = p.x.abs().powf(2.0 / e) + p.y.abs().powf(2.0 / e);
    let side = |v: f64, k: f64| v.signum() * v.abs().powf(k - 1.0);
    let across = if s > 0.0 { s.powf(e / n - 1.0) } else { 0.0 };
    let g = DVec3::new(
        across * side(p.x, 2.0 / e),
        across * side(p.y, 2.0 / e),
        side(p.z, 2.0 / n),
    );
    if g.is_finite() && g != DVec3::ZERO {
        g
    } else {
        p
    }
}

/// The ellipsoid's coordinates of the direction of `p`, their derivatives made tangent to the
/// surface at `p`.
pub fn frame(p: DVec3, shape: [f64; 2]) -> Frame {
    let n = normal(p, shape).normalize_or(DVec3::Z);
    let f = ellipsoid::frame(p.normalize_or(DVec3::Z));
    let along = |t: DVec3| (t - n * n.dot(t)) * p.length();
    Frame {
        uv: f.uv,
        dpdu: along(f.dpdu),
        dpdv: along(f.dpdv),
    }
}

/// Whether `p` lies inside.
pub fn contains(p: DVec3, shape: [f64; 2]) -> bool {
    value(p, shape) < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all(o: DVec3, d: DVec3, shape: [f64; 2]) -> Vec<f64> {
        let (lo, hi) = ((-1.0 - o) / d, (1.0 - o) / d);
        let t0 = lo.min(hi).max_element();
        let t1 = lo.max(hi).min_element();
        let mut out = Crossings::new();
        crossings(o, d, shape, [t0, t1], &mut out);
        out.iter().map(|c| c.0).collect()
    }

    #[test]
    fn with_both_exponents_1_it_is_the_unit_sphere() {
        let (o, d) = (DVec3::new(0.3, -0.2, -4.0), DVec3::new(0.05, 0.1, 1.0));
        let got = all(o, d, [1.0, 1.0]);
        let mut want = Crossings::new();
        ellipsoid::crossings(o, d, &mut want);
        assert_eq!(got.len(), 2, "{got:?}");
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w.0).abs() < 1e-12, "{got:?} vs {want:?}");
        }
        let p = DVec3::new(0.6, 0.0, 0.8);
        assert!((normal(p, [1.0, 1.0]).normalize() - p).length() < 1e-12);
    }

    #[test]
    fn small_exponents_make_nearly_the_cube() {
        // e = n = 0.1: a ray along x at (y, z) = (0.5, 0.5) meets the surface within 2% of
        // the cube's face.
        let got = all(DVec3::new(-3.0, 0.5, 0.5), DVec3::X, [0.1, 0.1]);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(
            (got[0] - 2.0).abs() < 0.02 && (got[1] - 4.0).abs() < 0.02,
            "{got:?}"
        );
        let n = normal(DVec3::new(0.999, 0.5, 0.5), [0.1, 0.1]).normalize();
        assert!(n.x > 0.99, "{n}");
    }

    #[test]
    fn the_octahedron_of_exponents_2_is_hit_on_its_face() {
        // |x| + |y| + |z| = 1: along z at (0.2, 0.3) the faces are at z = ±0.5.
        let got = all(DVec3::new(0.2, 0.3, -3.0), DVec3::Z, [2.0, 2.0]);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(
            (got[0] - 2.5).abs() < 1e-12 && (got[1] - 3.5).abs() < 1e-12,
            "{got:?}"
        );
        let n = normal(DVec3::new(0.2, 0.3, 0.5), [2.0, 2.0]).normalize();
        assert!((n - DVec3::ONE.normalize()).length() < 1e-12, "{n}");
    }

    #[test]
    fn the_convex_search_finds_what_dense_sampling_finds() {
        // Random rays through convex superellipsoids: the golden-section search and a dense
        // sampling of the same run agree on every crossing (rays grazing within a millionth of
        // the run aside).
        let mut next = super::super::test_stream(99);
        let mut met = 0;
        for _ in 0..2000 {
            let shape = [0.05 + 0.975 * (next() + 1.0), 0.05 + 0.975 * (next() + 1.0)];
            let o = DVec3::new(next(), next(), next()) * 3.0;
            let d = DVec3::new(next(), next(), next()) * 0.9 - o;
            let (lo, hi) = ((-1.0 - o) / d, (1.0 - o) / d);
            let (t0, t1) = (lo.min(hi).max_element(), lo.max(hi).min_element());
            if t0 >= t1 {
                continue;
            }
            let f = |t: f64| value(o + d * t, shape);
            let mut fast = Crossings::new();
            convex_crossings(&f, [t0, t1], &mut fast);
            // Dense sampling: 20000 steps.
            let mut slow = Vec::new();
            let n = 20_000;
            let mut a = (t0, f(t0));
            for i in 1..=n {
                let t = t0 + (t1 - t0) * i as f64 / n as f64;
                let b = (t, f(t));
                if (a.1 <= 0.0) != (b.1 <= 0.0) {
                    slow.push(refine(&f, a, b));
                }
                a = b;
            }
            assert_eq!(
                fast.len(),
                slow.len(),
                "{shape:?} {o} {d}: {fast:?} vs {slow:?}"
            );
            for (x, y) in fast.iter().zip(&slow) {
                assert!(
                    (x.0 - y).abs() < 1e-9,
                    "{shape:?} {o} {d}: {fast:?} vs {slow:?}"
                );
            }
            met += usize::from(!fast.is_empty());
        }
        assert!(met > 500, "only {met} rays met a superellipsoid");
    }

    #[test]
    fn the_tangents_lie_in_the_surface() {
        let shape = [0.5, 1.5];
        let d = DVec3::new(0.4, -0.7, 0.5).normalize();
        let got = all(-d * 3.0, d, shape);
        let p = -d * 3.0 + d * got[0];
        let f = frame(p, shape);
        let n = normal(p, shape).normalize();
        assert!(f.dpdu.dot(n).abs() < 1e-9 && f.dpdv.dot(n).abs() < 1e-9);
    }
}
