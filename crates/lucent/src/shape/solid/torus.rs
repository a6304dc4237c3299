//! A torus: the circle of radius 1 about the z axis in the plane `z = 0`, swept by a tube of
//! radius `r` (the minor radius over the major), in its own space. Its surface is
//! `(|p|² + 1 − r²)² = 4·(x² + y²)`, a quartic along a ray.

use super::{Crossings, Frame, cylinder, poly};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// The crossings of the line `o + t·d` with the torus for `t` in `[t0, t1]` (the part of the
/// line in its box). The quartic is set up from the point at `t0` with a unit direction, so
/// that a ray from far away does not lose its digits to the distance, and solved by
/// [`poly::roots_in`]; a ray that only touches the surface does not cross it.
pub fn crossings(o: DVec3, d: DVec3, r: f64, [t0, t1]: [f64; 2], out: &mut Crossings) {
    let length = d.length();
    let usable = length > 0.0 && t0 <= t1;
    if !usable {
        return;
    }
    let u = d / length;
    let o = o + d * t0;
    let b = 2.0 * o.dot(u);
    let e = o.length_squared() + 1.0 - r * r;
    let alpha = u.x * u.x + u.y * u.y;
    let beta = 2.0 * (o.x * u.x + o.y * u.y);
    let gamma = o.x * o.x + o.y * o.y;
    let c = [
        e * e - 4.0 * gamma,
        2.0 * b * e - 4.0 * beta,
        b * b + 2.0 * e - 4.0 * alpha,
        2.0 * b,
        1.0,
    ];
    for s in poly::roots_in(&c, 0.0, (t1 - t0) * length) {
        out.push((t0 + s / length, 0));
    }
}

/// The outward normal at `p`: the gradient of `(|p|² + 1 − r²)² − 4·(x² + y²)`, halved.
pub fn normal(p: DVec3, r: f64) -> DVec3 {
    let g = p.length_squared() + 1.0 - r * r;
    p * g - DVec3::new(p.x, p.y, 0.0) * 2.0
}

/// `u` the turn about the z axis from `+x`, `v` the turn about the tube from its outer
/// equator towards `+z`.
pub fn frame(p: DVec3) -> Frame {
    let (rho, out) = cylinder::from_axis(p);
    let v = p.z.atan2(rho - 1.0) / TAU;
    Frame {
        uv: DVec2::new(cylinder::turn(p), if v < 0.0 { v + 1.0 } else { v }),
        dpdu: DVec3::new(-p.y, p.x, 0.0) * TAU,
        dpdv: (DVec3::Z * (rho - 1.0) - out * p.z) * TAU,
    }
}

/// Whether `p` lies inside the tube.
pub fn contains(p: DVec3, r: f64) -> bool {
    let g = p.length_squared() + 1.0 - r * r;
    g * g < 4.0 * (p.x * p.x + p.y * p.y)
}

/// The box about the torus in its own space.
pub fn bounds(r: f64) -> (DVec3, DVec3) {
    let h = DVec3::new(1.0 + r, 1.0 + r, r);
    (-h, h)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all(o: DVec3, d: DVec3, r: f64) -> Vec<f64> {
        let mut out = Crossings::new();
        crossings(o, d, r, [0.0, 100.0], &mut out);
        out.iter().map(|c| c.0).collect()
    }

    #[test]
    fn a_ray_through_the_middle_crosses_the_tube_four_times() {
        // Along x in the torus's plane: the tube spans |x| in [1 − r, 1 + r].
        let t = all(DVec3::new(-5.0, 0.0, 0.0), DVec3::X, 0.25);
        let want = [5.0 - 1.25, 5.0 - 0.75, 5.0 + 0.75, 5.0 + 1.25];
        assert_eq!(t.len(), 4, "{t:?}");
        for (g, w) in t.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{t:?}");
        }
    }

    #[test]
    fn a_ray_down_the_hole_misses() {
        assert!(all(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z, 0.25).is_empty());
    }

    #[test]
    fn a_ray_down_through_the_tube_crosses_twice_at_its_radius() {
        let t = all(DVec3::new(1.0, 0.0, 5.0), DVec3::NEG_Z, 0.25);
        assert_eq!(t.len(), 2, "{t:?}");
        assert!((t[0] - 4.75).abs() < 1e-12 && (t[1] - 5.25).abs() < 1e-12);
        let n = normal(DVec3::new(1.0, 0.0, 0.25), 0.25).normalize();
        assert!((n - DVec3::Z).length() < 1e-12, "{n}");
    }

    #[test]
    fn the_tangents_lie_in_the_surface() {
        let r = 0.4f64;
        let (phi, theta) = (0.7f64, 2.1f64);
        let p = DVec3::new(
            (1.0 + r * theta.cos()) * phi.cos(),
            (1.0 + r * theta.cos()) * phi.sin(),
            r * theta.sin(),
        );
        let f = frame(p);
        let n = normal(p, r);
        assert!(f.dpdu.dot(n).abs() < 1e-12 && f.dpdv.dot(n).abs() < 1e-12);
        assert!((f.uv.x - phi / TAU).abs() < 1e-12 && (f.uv.y - theta / TAU).abs() < 1e-12);
        // ∂p/∂v is the tube's tangent scaled by a whole turn: length 2π·r.
        assert!((f.dpdv.length() - TAU * r).abs() < 1e-12);
    }
}
