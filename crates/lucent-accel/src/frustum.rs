//! Beams: the frustum of a bundle of rays that share an origin, and a conservative test of
//! a box against it.
//!
//! A beam is the convex cone spanned by four corner directions from a common origin — the rays
//! through a screen tile of a pinhole camera (Heckbert & Hanrahan 1984, "Beam tracing polygonal
//! objects"). Its four side planes pass through the origin; a box lies outside the beam when it
//! lies wholly outside one of them, which the box's *p-vertex* (the corner farthest along the
//! plane's inward normal) decides with one dot product per plane. The test is conservative: it
//! may keep a box no ray of the beam enters (near the cone's edges, where a box is outside the
//! cone but not outside any single plane), never the other way round.
//!
//! Rounding: the rays a caller traces are computed with their own rounding, and the slab test
//! and the primitive tests accept a little beyond the exact box (see [`crate::aabb`]), so the
//! planes are widened by an angle of [`ANGULAR_SLACK`] — about a thousandth of an 8-pixel
//! tile at 1024 pixels across, and some hundred times any rounding involved.

use crate::Aabb;
use glam::Vec3;

/// How far (in radians, roughly) a box may lie outside a side plane and still count as touched.
pub const ANGULAR_SLACK: f32 = 1e-4;

/// The radius of the ball around a shadow beam's light that its cone holds, relative to the
/// scene's coordinates there (see [`Frustum::from_point_over`]).
pub const LIGHT_SLACK: f32 = 1e-5;

/// The cone of rays `origin + t·d`, `t > 0`, for `d` in the convex hull of four directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    origin: Vec3,
    /// Unit inward normals of the four side planes (each through `origin`).
    normals: [Vec3; 4],
    /// The corner directions, of unit length.
    corners: [Vec3; 4],
}

impl Frustum {
    /// The beam from `origin` spanned by `corners`, given in order around the cone (either
    /// way round); `None` when they do not span a proper convex cone narrower than a
    /// half-space (parallel or opposite corners, a non-convex quadrilateral, non-finite input).
    pub fn new(origin: Vec3, corners: [Vec3; 4]) -> Option<Self> {
        if !origin.is_finite() {
            return None;
        }
        let mut unit = [Vec3::ZERO; 4];
        for (u, c) in unit.iter_mut().zip(corners) {
            *u = c.try_normalize()?;
        }
        let centre = (unit[0] + unit[1] + unit[2] + unit[3]).try_normalize()?;
        let mut normals = [Vec3::ZERO; 4];
        for i in 0..4 {
            let n = unit[i].cross(unit[(i + 1) % 4]).try_normalize()?;
            normals[i] = if n.dot(centre) < 0.0 { -n } else { n };
        }
        // Every corner on the inner side of every plane (up to rounding), and the centre
        // strictly inside: otherwise the four planes do not bound the hull of the corners.
        let convex = normals.iter().all(|n| {
            n.dot(centre) > ANGULAR_SLACK && unit.iter().all(|d| n.dot(*d) > -ANGULAR_SLACK)
        });
        convex.then_some(Self {
            origin,
            normals,
            corners: unit,
        })
    }

    /// A beam from `point` (a point light) over every point of `targets` (a box of shadow
    /// rays' origins, away from `point`), holding each segment between `point` and a point of
    /// the box — the shadow rays towards the light, whichever end they start from. `None`
    /// when the box is empty, not finite, or not wholly on one side of a plane through `point`.
    ///
    /// A shadow ray's origin and direction are rounded, so its line passes the light a little
    /// to the side; near the apex the angular slack covers nearly nothing. So the apex is moved
    /// back from `point`, along the beam's axis, by a twentieth of the nearest target's depth,
    /// and the cone is widened to hold a ball around `point` of [`LIGHT_SLACK`] times the
    /// scene's scale there (some hundred times a shadow ray's rounding).
    pub fn from_point_over(point: Vec3, targets: &Aabb) -> Option<Self> {
        if targets.is_empty() || !targets.min.is_finite() || !targets.max.is_finite() {
            return None;
        }
        if !point.is_finite() {
            return None;
        }
        let axis = (targets.center() - point).try_normalize()?;
        let u = axis.any_orthonormal_vector();
        let v = axis.cross(u);
        let corners = box_corners(targets);
        let near = corners
            .iter()
            .map(|c| (*c - point).dot(axis))
            .fold(f32::INFINITY, f32::min);
        let reach = corners
            .iter()
            .map(|c| (*c - point).abs().max_element())
            .fold(point.abs().max_element(), f32::max);
        if near.is_nan() || near <= reach * LIGHT_SLACK * 4.0 {
            return None;
        }
        let back = near / 20.0;
        let apex = point - axis * back;
        // The light's ball, as slopes from the apex: its radius over the apex's distance.
        let ball = 2.0 * reach * LIGHT_SLACK / back;
        let (mut lo, mut hi) = (glam::Vec2::splat(-ball), glam::Vec2::splat(ball));
        for c in corners {
            let d = c - apex;
            let slope = glam::Vec2::new(d.dot(u), d.dot(v)) / d.dot(axis);
            lo = lo.min(slope);
            hi = hi.max(slope);
        }
        let dir = |x: f32, y: f32| axis + x * u + y * v;
        Self::new(
            apex,
            [
                dir(lo.x, lo.y),
                dir(hi.x, lo.y),
                dir(hi.x, hi.y),
                dir(lo.x, hi.y),
            ],
        )
    }

    /// The unit inward normals of the four side planes, through [`Frustum::origin`].
    pub(crate) fn normals(&self) -> [Vec3; 4] {
        self.normals
    }

    /// The common origin of the beam's rays.
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// The corner directions, of unit length, in the order given.
    pub fn corners(&self) -> [Vec3; 4] {
        self.corners
    }

    /// False only when no ray of the beam can enter `b` (an empty box is never entered; a box
    /// with a NaN bound is kept, being no business of this test).
    #[inline]
    pub fn touches(&self, b: &Aabb) -> bool {
        if b.min.cmpgt(b.max).any() {
            return false;
        }
        self.normals.iter().all(|n| {
            let p = Vec3::select(n.cmpge(Vec3::ZERO), b.max, b.min) - self.origin;
            // Outside only when surely below the plane; NaN (a NaN bound, or ∞ − ∞) is
            // unordered, and the box is kept.
            let outside = n
                .dot(p)
                .partial_cmp(&(-ANGULAR_SLACK * (p.x.abs() + p.y.abs() + p.z.abs())));
            outside != Some(std::cmp::Ordering::Less)
        })
    }

    /// True unless no ray of the beam can reach the infinite plane through `point` with
    /// normal `normal` at some `t > 0`: the ray must head towards the plane's side it is not on,
    /// and `normal · d` is linear in `d`, so the corners decide.
    pub fn may_reach_plane(&self, point: Vec3, normal: Vec3) -> bool {
        let side = normal.dot(point - self.origin);
        if side == 0.0 || !side.is_finite() {
            return true;
        }
        let n = normal.normalize_or_zero() * side.signum();
        // A corner heading surely away (`n · d ≤ −slack`) is no witness; NaN keeps the plane.
        self.corners.iter().any(|d| {
            !matches!(
                n.dot(*d).partial_cmp(&-ANGULAR_SLACK),
                Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
            )
        })
    }
}

/// The eight corners of `b`.
fn box_corners(b: &Aabb) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        let pick = |bit: usize, lo: f32, hi: f32| if i >> bit & 1 == 0 { lo } else { hi };
        Vec3::new(
            pick(0, b.min.x, b.max.x),
            pick(1, b.min.y, b.max.y),
            pick(2, b.min.z, b.max.z),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square beam down −z, a half-angle of about 0.1 rad.
    fn beam() -> Frustum {
        let c = |x: f32, y: f32| Vec3::new(x, y, -1.0);
        Frustum::new(
            Vec3::ZERO,
            [c(-0.1, -0.1), c(0.1, -0.1), c(0.1, 0.1), c(-0.1, 0.1)],
        )
        .unwrap()
    }

    fn cube(centre: Vec3, half: f32) -> Aabb {
        Aabb::new(centre - half, centre + half)
    }

    #[test]
    fn boxes_in_front_are_touched_and_those_beside_or_behind_are_not() {
        let f = beam();
        assert!(f.touches(&cube(Vec3::new(0.0, 0.0, -5.0), 0.1)));
        assert!(
            f.touches(&cube(Vec3::new(0.55, 0.0, -5.0), 0.1)),
            "straddles a side"
        );
        assert!(!f.touches(&cube(Vec3::new(1.0, 0.0, -5.0), 0.1)));
        assert!(
            !f.touches(&cube(Vec3::new(0.0, 0.0, 5.0), 0.1)),
            "behind the origin"
        );
        assert!(f.touches(&cube(Vec3::ZERO, 0.1)), "holds the origin");
        assert!(!f.touches(&Aabb::EMPTY));
    }

    #[test]
    fn either_winding_gives_the_same_beam() {
        let f = beam();
        let mut c = f.corners();
        c.reverse();
        let g = Frustum::new(Vec3::ZERO, c).unwrap();
        for x in [-0.8, -0.45, 0.0, 0.45, 0.8] {
            let b = cube(Vec3::new(x, 0.0, -5.0), 0.1);
            assert_eq!(f.touches(&b), g.touches(&b));
        }
    }

    #[test]
    fn degenerate_corners_give_no_beam() {
        let d = Vec3::new(0.0, 0.0, -1.0);
        assert!(Frustum::new(Vec3::ZERO, [d; 4]).is_none());
        let bow_tie = [
            Vec3::new(-0.1, -0.1, -1.0),
            Vec3::new(0.1, 0.1, -1.0),
            Vec3::new(0.1, -0.1, -1.0),
            Vec3::new(-0.1, 0.1, -1.0),
        ];
        assert!(Frustum::new(Vec3::ZERO, bow_tie).is_none());
    }

    #[test]
    fn a_shadow_beam_holds_its_targets_and_the_light_but_not_what_lies_beside() {
        let light = Vec3::new(0.0, 10.0, 0.0);
        let targets = Aabb::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.1, 1.0));
        let f = Frustum::from_point_over(light, &targets).unwrap();
        assert!(f.touches(&targets));
        assert!(f.touches(&cube(light, 1e-3)), "the light itself");
        assert!(f.touches(&cube(Vec3::new(0.0, 5.0, 0.0), 0.01)), "between");
        assert!(!f.touches(&cube(Vec3::new(4.0, 5.0, 0.0), 0.5)), "beside");
        assert!(
            !f.touches(&cube(Vec3::new(0.0, 12.0, 0.0), 0.05)),
            "behind the light"
        );
        // A light inside the box, or touching it: no beam.
        assert!(Frustum::from_point_over(Vec3::new(0.0, 0.05, 0.0), &targets).is_none());
        assert!(Frustum::from_point_over(light, &Aabb::EMPTY).is_none());
    }

    #[test]
    fn planes_ahead_are_reached_and_planes_behind_are_not() {
        let f = beam();
        assert!(f.may_reach_plane(Vec3::new(0.0, 0.0, -3.0), Vec3::Z));
        assert!(!f.may_reach_plane(Vec3::new(0.0, 0.0, 3.0), Vec3::Z));
        // A floor below: the beam looks level, its lower rays go down.
        assert!(f.may_reach_plane(Vec3::new(0.0, -1.0, 0.0), Vec3::Y));
        assert!(
            f.may_reach_plane(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y),
            "upper rays rise"
        );
        // A ceiling far above a beam that looks down: missed.
        let down = Frustum::new(
            Vec3::ZERO,
            [
                Vec3::new(-0.1, -1.0, -1.0),
                Vec3::new(0.1, -1.0, -1.0),
                Vec3::new(0.1, -0.8, -1.0),
                Vec3::new(-0.1, -0.8, -1.0),
            ],
        )
        .unwrap();
        assert!(!down.may_reach_plane(Vec3::new(0.0, 5.0, 0.0), Vec3::Y));
    }
}
