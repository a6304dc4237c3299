//! Infinite planes: the ray put into `n · (p − p0) = 0` gives t as a ratio.

use glam::Vec3;
use lucent_accel::Ray;

/// The infinite plane through `point` with unit normal `normal`.
///
/// Unbounded, so it lives outside the accelerators (which need finite boxes) and is tested
/// against every ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// A point on the plane; the origin of its surface coordinates.
    pub point: Vec3,
    /// Unit normal; the plane's front side.
    pub normal: Vec3,
    /// Unit tangents spanning the plane, so that `(tangent, bitangent, normal)` is right-handed.
    pub tangent: Vec3,
    /// See `tangent`.
    pub bitangent: Vec3,
}

impl Plane {
    /// The plane through `point` with normal direction `normal` (any non-zero length).
    pub fn new(point: Vec3, normal: Vec3) -> Self {
        let normal = normal.normalize();
        let (tangent, bitangent) = normal.any_orthonormal_pair();
        Self {
            point,
            normal,
            tangent,
            bitangent,
        }
    }

    /// `t = n · (p0 − o) / (n · d)` if it lies in `(0, t_max)`; a parallel ray (`n · d = 0`) misses.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let denom = self.normal.dot(ray.dir);
        if denom == 0.0 {
            return None;
        }
        let t = self.normal.dot(self.point - ray.origin) / denom;
        (t > 0.0 && t < t_max).then_some(t)
    }

    /// Coordinates of `p` in the plane's own frame, measured from `point`: exact zero across the
    /// plane, so that textures such as a checkerboard do not flicker on rounding noise.
    pub fn surface_coords(&self, p: Vec3) -> Vec3 {
        let d = p - self.point;
        Vec3::new(d.dot(self.tangent), d.dot(self.bitangent), 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn floor() -> Plane {
        Plane::new(Vec3::ZERO, Vec3::Y)
    }

    #[test]
    fn a_parallel_ray_misses() {
        let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X);
        assert_eq!(floor().intersect(&ray, f32::INFINITY), None);
        // Even when it lies in the plane itself.
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(floor().intersect(&ray, f32::INFINITY), None);
    }

    #[test]
    fn a_ray_down_hits_at_its_height() {
        let ray = Ray::new(Vec3::new(3.0, 2.0, -1.0), -Vec3::Y);
        assert_eq!(floor().intersect(&ray, f32::INFINITY), Some(2.0));
    }

    #[test]
    fn both_sides_are_hit_and_behind_is_missed() {
        let from_below = Ray::new(Vec3::new(0.0, -2.0, 0.0), Vec3::Y);
        assert_eq!(floor().intersect(&from_below, f32::INFINITY), Some(2.0));
        let away = Ray::new(Vec3::new(0.0, 2.0, 0.0), Vec3::Y);
        assert_eq!(floor().intersect(&away, f32::INFINITY), None);
    }

    #[test]
    fn an_oblique_ray_hits_at_the_known_distance() {
        let ray = Ray::new(
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0).normalize(),
        );
        let t = floor().intersect(&ray, f32::INFINITY).unwrap();
        assert!((t - 2f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn surface_coords_lie_in_the_plane() {
        let p = Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y);
        let c = p.surface_coords(Vec3::new(2.0, -1.0, 3.0));
        assert_eq!(c.z, 0.0);
        assert!((c.truncate().length() - 13f32.sqrt()).abs() < 1e-5);
    }
}
