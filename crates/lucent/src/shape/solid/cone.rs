//! A cone, possibly truncated: about the z axis from `z = 0` (radius `r0`) to `z = 1` (radius
//! `r1`), in its own space. Part 0 is the side, 1 the cap at `z = 0`, 2 the cap at `z = 1`;
//! an open cone has no caps.

use super::{Crossings, Frame, cap_frame, cylinder, poly};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// The crossings of the line `o + t·d` with the side (`x² + y² = (r0 + (r1 − r0)·z)²` for
/// `0 ≤ z ≤ 1`) and, unless `open`, with the caps.
pub fn crossings(o: DVec3, d: DVec3, [r0, r1]: [f64; 2], open: bool, out: &mut Crossings) {
    let k = r1 - r0;
    let r_o = r0 + k * o.z;
    let a = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
    let b = 2.0 * (o.x * d.x + o.y * d.y - k * d.z * r_o);
    let c = o.x * o.x + o.y * o.y - r_o * r_o;
    if let Some((t0, t1)) = poly::quadratic(a, b, c) {
        for t in [t0, t1] {
            // Within the height, the other nappe of the double cone is never reached.
            let z = o.z + t * d.z;
            if (0.0..=1.0).contains(&z) {
                out.push((t, 0));
            }
        }
    }
    if !open {
        cylinder::caps(o, d, [r0, r1], out);
    }
}

/// The outward normal at `p` on `part`.
pub fn normal(p: DVec3, [r0, r1]: [f64; 2], part: u8) -> DVec3 {
    let k = r1 - r0;
    match part {
        0 => DVec3::new(p.x, p.y, -k * (r0 + k * p.z)),
        1 => DVec3::NEG_Z,
        _ => DVec3::Z,
    }
}

/// On the side, `u` the turn about the axis and `v = z` (as on a cylinder); on a cap, the
/// cap's `(x, y)` mapped from `[-1, 1]` to `[0, 1]`.
pub fn frame(p: DVec3, [r0, r1]: [f64; 2], part: u8) -> Frame {
    if part != 0 {
        return cap_frame(p);
    }
    let k = r1 - r0;
    // On the axis (the apex) the slant has no direction.
    let (r, out) = cylinder::from_axis(p);
    let out = if r > 0.0 { out } else { DVec3::ZERO };
    Frame {
        uv: DVec2::new(cylinder::turn(p), p.z),
        dpdu: DVec3::new(-p.y, p.x, 0.0) * TAU,
        dpdv: out * k + DVec3::Z,
    }
}

/// Whether `p` lies inside the closed cone.
pub fn contains(p: DVec3, [r0, r1]: [f64; 2]) -> bool {
    let r = r0 + (r1 - r0) * p.z;
    p.z > 0.0 && p.z < 1.0 && p.x * p.x + p.y * p.y < r * r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_across_a_pointed_cone_meets_it_at_its_radius_there() {
        // Radius 1 at z = 0 to 0 at z = 1: at z = 0.5 the radius is 0.5.
        let mut out = Crossings::new();
        crossings(
            DVec3::new(-3.0, 0.0, 0.5),
            DVec3::X,
            [1.0, 0.0],
            false,
            &mut out,
        );
        assert_eq!(out.len(), 2, "{out:?}");
        assert!((out[0].0 - 2.5).abs() < 1e-14 && (out[1].0 - 3.5).abs() < 1e-14);
        // The side leans outward-up: the normal at (0.5, 0, 0.5) is (1, 0, 1)/√2.
        let n = normal(DVec3::new(0.5, 0.0, 0.5), [1.0, 0.0], 0).normalize();
        assert!(
            (n - DVec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-15,
            "{n}"
        );
    }

    #[test]
    fn the_other_nappe_is_not_hit() {
        // Above the apex of the pointed cone, where the double cone opens again.
        let mut out = Crossings::new();
        crossings(
            DVec3::new(-3.0, 0.0, 1.5),
            DVec3::X,
            [1.0, 0.0],
            true,
            &mut out,
        );
        assert!(out.is_empty(), "{out:?}");
    }

    #[test]
    fn with_equal_radii_it_is_the_cylinder() {
        let (o, d) = (DVec3::new(-2.0, 0.3, -0.5), DVec3::new(1.0, 0.1, 0.7));
        let (mut a, mut b) = (Crossings::new(), Crossings::new());
        crossings(o, d, [1.0, 1.0], false, &mut a);
        cylinder::crossings(o, d, false, &mut b);
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            assert!((x.0 - y.0).abs() < 1e-14 && x.1 == y.1);
        }
    }

    #[test]
    fn the_tangents_follow_the_slanted_side() {
        let (radii, p) = ([1.0, 0.5], DVec3::new(0.0, 0.75, 0.5));
        let f = frame(p, radii, 0);
        let n = normal(p, radii, 0);
        assert!(f.dpdu.dot(n).abs() < 1e-12 && f.dpdv.dot(n).abs() < 1e-12);
        assert!((f.dpdv - DVec3::new(0.0, -0.5, 1.0)).length() < 1e-15);
    }
}
