//! A cylinder: radius 1 about the z axis, from `z = 0` to `z = 1`, in its own space (any
//! cylinder is this one placed by a transform). Part 0 is the side, 1 the cap at `z = 0`, 2 the
//! cap at `z = 1`; an open cylinder has no caps.

use super::{Crossings, Frame, cap_frame, poly};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// The crossings of the line `o + t·d` with the side (where `x² + y² = 1` for `0 ≤ z ≤ 1`)
/// and, unless `open`, with the caps.
pub fn crossings(o: DVec3, d: DVec3, open: bool, out: &mut Crossings) {
    let a = d.x * d.x + d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.y * d.y);
    let c = o.x * o.x + o.y * o.y - 1.0;
    if a > 0.0
        && let Some((t0, t1)) = poly::quadratic(a, b, c)
    {
        for t in [t0, t1] {
            let z = o.z + t * d.z;
            if (0.0..=1.0).contains(&z) {
                out.push((t, 0));
            }
        }
    }
    if !open {
        caps(o, d, [1.0, 1.0], out);
    }
}

/// The crossings with the caps of radii `radii` at `z = 0` (part 1) and `z = 1` (part 2).
pub fn caps(o: DVec3, d: DVec3, radii: [f64; 2], out: &mut Crossings) {
    if d.z == 0.0 {
        return;
    }
    for (part, (z, r)) in [(1u8, (0.0, radii[0])), (2, (1.0, radii[1]))] {
        let t = (z - o.z) / d.z;
        let (x, y) = (o.x + t * d.x, o.y + t * d.y);
        if x * x + y * y <= r * r {
            out.push((t, part));
        }
    }
}

/// The outward normal at `p` on `part`.
pub fn normal(p: DVec3, part: u8) -> DVec3 {
    match part {
        0 => DVec3::new(p.x, p.y, 0.0),
        1 => DVec3::NEG_Z,
        _ => DVec3::Z,
    }
}

/// On the side, `u` the turn about the axis from `+x` towards `+y` and `v = z`; on a cap, the
/// cap's `(x, y)` mapped from `[-1, 1]` to `[0, 1]`.
pub fn frame(p: DVec3, part: u8) -> Frame {
    match part {
        0 => Frame {
            uv: DVec2::new(turn(p), p.z),
            dpdu: DVec3::new(-p.y, p.x, 0.0) * TAU,
            dpdv: DVec3::Z,
        },
        _ => cap_frame(p),
    }
}

/// The angle about the z axis from `+x` towards `+y`, as a fraction of a turn in `[0, 1)`.
pub fn turn(p: DVec3) -> f64 {
    let u = p.y.atan2(p.x) / TAU;
    if u < 0.0 { u + 1.0 } else { u }
}

/// The distance of `p` from the z axis, and the unit direction from the axis towards it in
/// the plane z = 0 (`+x` on the axis itself).
pub fn from_axis(p: DVec3) -> (f64, DVec3) {
    let rho = (p.x * p.x + p.y * p.y).sqrt();
    if rho > 0.0 {
        (rho, DVec3::new(p.x / rho, p.y / rho, 0.0))
    } else {
        (rho, DVec3::X)
    }
}

/// Whether `p` lies inside the closed cylinder.
pub fn contains(p: DVec3) -> bool {
    p.x * p.x + p.y * p.y < 1.0 && p.z > 0.0 && p.z < 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_across_the_axis_meets_the_side_at_known_t() {
        let mut out = Crossings::new();
        crossings(DVec3::new(-3.0, 0.6, 0.5), DVec3::X, false, &mut out);
        // x² = 1 − 0.36: x = ±0.8.
        assert_eq!(out.len(), 2);
        assert!((out[0].0 - 2.2).abs() < 1e-14 && (out[1].0 - 3.8).abs() < 1e-14);
        let p = DVec3::new(-0.8, 0.6, 0.5);
        assert!((normal(p, 0).normalize() - DVec3::new(-0.8, 0.6, 0.0)).length() < 1e-15);
    }

    #[test]
    fn a_ray_down_the_axis_meets_the_caps_unless_open() {
        let mut out = Crossings::new();
        crossings(DVec3::new(0.2, 0.0, -1.0), DVec3::Z, false, &mut out);
        assert_eq!(out.as_slice(), &[(1.0, 1), (2.0, 2)]);
        out.clear();
        crossings(DVec3::new(0.2, 0.0, -1.0), DVec3::Z, true, &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn a_ray_above_the_cylinder_misses_its_infinite_side() {
        let mut out = Crossings::new();
        crossings(DVec3::new(-3.0, 0.0, 1.5), DVec3::X, false, &mut out);
        assert!(out.is_empty());
    }
}
