//! A disc: radius 1 in the plane `z = 0`, facing `+z`, with an optional hole of radius
//! `hole < 1` about its centre, in its own space. It bounds nothing, so nothing is inside it.

use super::{Crossings, Frame, cap_frame};
use glam::DVec3;

/// The crossing of the line `o + t·d` with the disc, if it passes within the ring.
pub fn crossings(o: DVec3, d: DVec3, hole: f64, out: &mut Crossings) {
    if d.z == 0.0 {
        return;
    }
    let t = -o.z / d.z;
    let (x, y) = (o.x + t * d.x, o.y + t * d.y);
    let r2 = x * x + y * y;
    if r2 <= 1.0 && r2 >= hole * hole {
        out.push((t, 0));
    }
}

/// `(x, y)` mapped from `[-1, 1]` to `[0, 1]`.
pub fn frame(p: DVec3) -> Frame {
    cap_frame(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_through_the_ring_hits_and_through_the_hole_passes() {
        let mut out = Crossings::new();
        crossings(DVec3::new(0.7, 0.0, 2.0), DVec3::NEG_Z, 0.5, &mut out);
        assert_eq!(out.as_slice(), &[(2.0, 0)]);
        out.clear();
        crossings(DVec3::new(0.3, 0.0, 2.0), DVec3::NEG_Z, 0.5, &mut out);
        crossings(DVec3::new(1.3, 0.0, 2.0), DVec3::NEG_Z, 0.5, &mut out);
        crossings(DVec3::new(0.7, 0.0, 2.0), DVec3::X, 0.5, &mut out);
        assert!(out.is_empty());
    }
}
