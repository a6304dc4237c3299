//! A superellipsoid (Barr's, as POV-Ray's): `(|x|^(2/e) + |y|^(2/e))^(e/n) + |z|^(2/n) = 1` in
//! its own space, inside the cube `[-1, 1]³`. `e` shapes its cross-sections in x and y, `n`
//! along z: both 1 make the unit sphere, both near 0 the cube, 2 an octahedron.
//!
//! Its function along a ray is no polynomial, so the crossings are found by sampling: the
//! ray's run through the cube in [`STEPS`] even steps, each sign change refined by regula falsi
//! to `f64` precision. Two crossings closer than a step (a ray grazing an edge) can be missed
//! together, never one alone, so the crossings still alternate.

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
    let step = (t1 - t0) / STEPS as f64;
    let mut a = (t0, f(t0));
    for i in 1..=STEPS {
        let t = if i == STEPS { t1 } else { t0 + step * i as f64 };
        let b = (t, f(t));
        // A sample exactly on the surface counts as inside, so that it is crossed once.
        if (a.1 <= 0.0) != (b.1 <= 0.0) && !out.is_full() {
            out.push((refine(&f, a, b), 0));
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
