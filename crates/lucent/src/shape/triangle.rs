//! Ray–triangle intersection, two ways: the lecture notes' plane-and-barycentrics method, and
//! the watertight method of Woop, Benthin and Wald (2013), the default. The watertight test
//! lives in `lucent-accel` (beside its SIMD twin in the wide BVH) and is re-exported here.

use glam::Vec3;
use lucent_accel::Ray;

/// Which ray–triangle test to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TriangleTest {
    /// Woop, Benthin & Wald 2013: never lets a ray slip between two triangles sharing an edge.
    #[default]
    Watertight,
    /// The notes: hit the plane, project onto two axes, solve for the barycentric weights.
    Projection,
}

impl TriangleTest {
    /// Intersects with the chosen method.
    pub fn intersect(self, ray: &Ray, v: [Vec3; 3], t_max: f32) -> Option<TriangleHit> {
        match self {
            TriangleTest::Watertight => watertight(ray, v, t_max),
            TriangleTest::Projection => projection(ray, v, t_max),
        }
    }

    /// The name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TriangleTest::Watertight => "watertight",
            TriangleTest::Projection => "projection",
        }
    }
}

pub use lucent_accel::triangle::{TriangleHit, watertight};

/// The lecture notes' test.
///
/// Hit the triangle's plane (`t = n·(A − o) / n·d`, parallel when the denominator is zero), then
/// drop the axis of the normal's largest component and solve the two remaining coordinates of
/// `P − C = (A − C)·a1 + (B − C)·a2` for `a1`, `a2` by Cramer's rule; `a3 = 1 − a1 − a2`. The
/// point is inside iff all three lie in `[0, 1]` (a weight of 0: on an edge; two: on a vertex).
pub fn projection(ray: &Ray, [a, b, c]: [Vec3; 3], t_max: f32) -> Option<TriangleHit> {
    let n = (b - a).cross(c - a);
    let denom = n.dot(ray.dir);
    if denom == 0.0 {
        return None;
    }
    let t = n.dot(a - ray.origin) / denom;
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    let p = ray.at(t);
    let (i, j) = match n.abs().max_position() {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let (ac, bc, pc) = (a - c, b - c, p - c);
    let det = ac[i] * bc[j] - ac[j] * bc[i];
    if det == 0.0 {
        return None;
    }
    let a1 = (pc[i] * bc[j] - pc[j] * bc[i]) / det;
    let a2 = (ac[i] * pc[j] - ac[j] * pc[i]) / det;
    let a3 = 1.0 - a1 - a2;
    let inside = |w: f32| (0.0..=1.0).contains(&w);
    (inside(a1) && inside(a2) && inside(a3)).then_some(TriangleHit {
        t,
        bary: [a1, a2, a3],
    })
}

/// The unit normal `(B − A) × (C − A)`, counter-clockwise winding facing the viewer; `None`
/// for a degenerate triangle.
pub fn normal([a, b, c]: [Vec3; 3]) -> Option<Vec3> {
    (b - a).cross(c - a).try_normalize()
}

/// `∂p/∂u` and `∂p/∂v` of the triangle with corners `p` and texture coordinates `uv`: the
/// linear map from `uv` to points it spans, solved from two edges (pbrt's construction).
/// `None` when the coordinates are degenerate (collinear or repeated).
pub fn uv_tangents(p: [Vec3; 3], uv: [glam::Vec2; 3]) -> Option<(Vec3, Vec3)> {
    let (duv02, duv12) = (uv[0] - uv[2], uv[1] - uv[2]);
    let (dp02, dp12) = (p[0] - p[2], p[1] - p[2]);
    let det = duv02.x * duv12.y - duv02.y * duv12.x;
    if det.is_nan() || det.abs() <= 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let dpdu = (dp02 * duv12.y - dp12 * duv02.y) * inv;
    let dpdv = (dp12 * duv02.x - dp02 * duv12.x) * inv;
    (dpdu.is_finite() && dpdv.is_finite()).then_some((dpdu, dpdv))
}

/// Twice the area, in double precision (for degeneracy checks).
pub fn double_area([a, b, c]: [Vec3; 3]) -> f64 {
    (b.as_dvec3() - a.as_dvec3())
        .cross(c.as_dvec3() - a.as_dvec3())
        .length()
}

#[cfg(test)]
mod tests {
    use super::*;

    // A right triangle in the plane z = 0: A at the origin, B on x, C on y.
    const TRI: [Vec3; 3] = [Vec3::ZERO, Vec3::X, Vec3::Y];

    #[test]
    fn uv_tangents_map_texture_steps_to_points() {
        use glam::Vec2;
        // u runs along −y at twice the speed, v along +x.
        let uv = [
            Vec2::new(0.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(-2.0, 0.0),
        ];
        let (dpdu, dpdv) = uv_tangents(TRI, uv).unwrap();
        assert!((dpdu - Vec3::new(0.0, -0.5, 0.0)).length() < 1e-6, "{dpdu}");
        assert!((dpdv - Vec3::X).length() < 1e-6, "{dpdv}");
        assert!(uv_tangents(TRI, [Vec2::ZERO; 3]).is_none());
    }

    fn down_at(x: f32, y: f32) -> Ray {
        Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z)
    }

    fn both(ray: &Ray) -> [Option<TriangleHit>; 2] {
        [
            watertight(ray, TRI, f32::INFINITY),
            projection(ray, TRI, f32::INFINITY),
        ]
    }

    #[test]
    fn inside_hits_with_the_right_weights() {
        for hit in both(&down_at(0.25, 0.25)) {
            let hit = hit.expect("hit");
            assert!((hit.t - 1.0).abs() < 1e-6);
            // P = a1·A + a2·B + a3·C with A = 0, B = x, C = y: a2 = x, a3 = y.
            let [a1, a2, a3] = hit.bary;
            assert!(
                (a1 - 0.5).abs() < 1e-6 && (a2 - 0.25).abs() < 1e-6 && (a3 - 0.25).abs() < 1e-6
            );
        }
    }

    #[test]
    fn on_an_edge_one_weight_is_zero_and_it_hits() {
        for hit in both(&down_at(0.5, 0.0)) {
            let hit = hit.expect("edge hit");
            assert_eq!(hit.bary.iter().filter(|&&w| w == 0.0).count(), 1, "{hit:?}");
        }
    }

    #[test]
    fn on_a_vertex_two_weights_are_zero_and_it_hits() {
        for hit in both(&down_at(1.0, 0.0)) {
            let hit = hit.expect("vertex hit");
            assert_eq!(hit.bary.iter().filter(|&&w| w == 0.0).count(), 2, "{hit:?}");
        }
    }

    #[test]
    fn outside_misses() {
        for (x, y) in [(0.6, 0.6), (-0.1, 0.5), (0.5, -0.1), (2.0, 2.0)] {
            assert_eq!(both(&down_at(x, y)), [None, None], "at ({x}, {y})");
        }
    }

    #[test]
    fn parallel_and_behind_miss() {
        let parallel = Ray::new(Vec3::new(-1.0, 0.2, 0.0), Vec3::X);
        assert_eq!(both(&parallel), [None, None]);
        let behind = Ray::new(Vec3::new(0.2, 0.2, -1.0), -Vec3::Z);
        assert_eq!(both(&behind), [None, None]);
    }

    #[test]
    fn both_sides_are_hit() {
        let from_below = Ray::new(Vec3::new(0.2, 0.2, -1.0), Vec3::Z);
        for hit in both(&from_below) {
            assert!((hit.expect("back-face hit").t - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn t_max_cuts_off_farther_hits() {
        let ray = down_at(0.25, 0.25);
        assert_eq!(watertight(&ray, TRI, 0.5), None);
        assert_eq!(projection(&ray, TRI, 0.5), None);
    }

    #[test]
    fn degenerate_triangles_are_never_hit() {
        let line = [Vec3::ZERO, Vec3::X, 2.0 * Vec3::X];
        let ray = Ray::new(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z);
        assert_eq!(watertight(&ray, line, f32::INFINITY), None);
        assert_eq!(projection(&ray, line, f32::INFINITY), None);
        assert_eq!(normal(line), None);
    }

    #[test]
    fn normal_follows_counter_clockwise_winding() {
        assert_eq!(normal(TRI), Some(Vec3::Z));
    }
}
