//! A box: the cube `[-1, 1]³` in its own space, its edges along the axes (any box is this
//! cube placed by a transform). Its faces are parts `2·axis` (the low side) and `2·axis + 1`
//! (the high side).

use super::{Crossings, Frame};
use glam::{DVec2, DVec3};

/// The crossings of the line `o + t·d` with the cube's faces: the slab test, entry and exit.
pub fn crossings(o: DVec3, d: DVec3, out: &mut Crossings) {
    let (mut near, mut far) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut near_part, mut far_part) = (0u8, 0u8);
    for axis in 0..3 {
        if d[axis] == 0.0 {
            if o[axis].abs() > 1.0 {
                return;
            }
            continue;
        }
        let (t0, t1) = ((-1.0 - o[axis]) / d[axis], (1.0 - o[axis]) / d[axis]);
        // Entering through the low face when the ray goes up the axis.
        let (lo, hi, lo_part, hi_part) = if t0 < t1 {
            (t0, t1, 2 * axis as u8, 2 * axis as u8 + 1)
        } else {
            (t1, t0, 2 * axis as u8 + 1, 2 * axis as u8)
        };
        if lo > near {
            (near, near_part) = (lo, lo_part);
        }
        if hi < far {
            (far, far_part) = (hi, hi_part);
        }
    }
    if near < far {
        out.push((near, near_part));
        out.push((far, far_part));
    }
}

/// The outward normal of face `part`.
pub fn normal(part: u8) -> DVec3 {
    let mut n = DVec3::ZERO;
    n[usize::from(part / 2)] = if part % 2 == 1 { 1.0 } else { -1.0 };
    n
}

/// Texture coordinates on face `part`: the face's other two axes, in order, mapped from
/// `[-1, 1]` to `[0, 1]`.
pub fn frame(p: DVec3, part: u8) -> Frame {
    let axis = usize::from(part / 2);
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    let (a, b) = (a.min(b), a.max(b));
    let mut dpdu = DVec3::ZERO;
    let mut dpdv = DVec3::ZERO;
    dpdu[a] = 2.0;
    dpdv[b] = 2.0;
    Frame {
        uv: DVec2::new((p[a] + 1.0) / 2.0, (p[b] + 1.0) / 2.0),
        dpdu,
        dpdv,
    }
}

/// Whether `p` lies inside.
pub fn contains(p: DVec3) -> bool {
    p.abs().max_element() < 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_down_the_x_axis_enters_and_leaves_at_the_faces() {
        let mut out = Crossings::new();
        crossings(DVec3::new(-5.0, 0.2, 0.3), DVec3::X, &mut out);
        assert_eq!(out.as_slice(), &[(4.0, 0), (6.0, 1)]);
        assert_eq!(normal(0), DVec3::NEG_X);
        assert_eq!(normal(5), DVec3::Z);
    }

    #[test]
    fn a_ray_beside_the_box_or_along_a_face_plane_outside_misses() {
        let mut out = Crossings::new();
        crossings(DVec3::new(-5.0, 1.5, 0.0), DVec3::X, &mut out);
        crossings(
            DVec3::new(-5.0, -5.0, 0.0),
            DVec3::new(1.0, 0.2, 0.0),
            &mut out,
        );
        assert!(out.is_empty(), "{out:?}");
    }

    #[test]
    fn a_diagonal_ray_leaves_through_the_face_it_meets_last() {
        let mut out = Crossings::new();
        crossings(DVec3::ZERO, DVec3::new(0.5, 1.0, 0.25), &mut out);
        assert_eq!(out.as_slice(), &[(-1.0, 2), (1.0, 3)]);
        assert!(contains(DVec3::new(0.9, -0.9, 0.0)) && !contains(DVec3::new(1.1, 0.0, 0.0)));
    }
}
