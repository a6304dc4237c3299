//! An ellipsoid: the unit sphere in its own space, made any ellipsoid by its placement (a
//! sphere that is scaled unevenly, as Mitsuba's and POV-Ray's spheres may be). Its texture
//! coordinates are Mitsuba's sphere's: `u` the turn about z from `+x` towards `+y`, `v` the
//! angle from the pole `+z` over π.

use super::{Crossings, Frame, cylinder, poly};
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// The crossings of the line `o + t·d` with the unit sphere.
pub fn crossings(o: DVec3, d: DVec3, out: &mut Crossings) {
    let (a, b, c) = (d.length_squared(), 2.0 * o.dot(d), o.length_squared() - 1.0);
    if let Some((t0, t1)) = poly::quadratic(a, b, c) {
        out.push((t0, 0));
        out.push((t1, 0));
    }
}

/// Mitsuba's sphere coordinates and their derivatives at `p` (on the unit sphere).
pub fn frame(p: DVec3) -> Frame {
    let (rho, out) = cylinder::from_axis(p);
    Frame {
        uv: DVec2::new(cylinder::turn(p), p.z.clamp(-1.0, 1.0).acos() / PI),
        dpdu: DVec3::new(-p.y, p.x, 0.0) * TAU,
        dpdv: (out * p.z - DVec3::Z * rho) * PI,
    }
}

/// Whether `p` lies inside.
pub fn contains(p: DVec3) -> bool {
    p.length_squared() < 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_through_the_centre_crosses_at_one_each_side() {
        let mut out = Crossings::new();
        crossings(DVec3::new(0.0, 0.0, -3.0), DVec3::Z * 2.0, &mut out);
        assert_eq!(out.as_slice(), &[(1.0, 0), (2.0, 0)]);
    }

    #[test]
    fn the_coordinates_are_mitsubas_and_the_tangents_their_derivatives() {
        let p = DVec3::new(0.3, 0.5, -0.81).normalize();
        let f = frame(p);
        let h = 1e-6;
        for (d, du, dv) in [(f.dpdu, h, 0.0), (f.dpdv, 0.0, h)] {
            let moved = frame((p + d * h).normalize());
            assert!(
                (moved.uv.x - f.uv.x - du).abs() < 1e-9,
                "{:?}",
                moved.uv - f.uv
            );
            assert!(
                (moved.uv.y - f.uv.y - dv).abs() < 1e-9,
                "{:?}",
                moved.uv - f.uv
            );
        }
        // u = ¼ along +y on the equator, v = 0 at the pole +z.
        assert!((frame(DVec3::Y).uv - DVec2::new(0.25, 0.5)).length() < 1e-12);
        assert!(frame(DVec3::Z).uv.y.abs() < 1e-12);
    }
}
