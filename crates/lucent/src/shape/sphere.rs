//! Spheres: the ray's parametric equation put into `|p − c|² = r²`, a quadratic in t.

use glam::Vec3;
use lucent_accel::{Aabb, Ray};

/// A sphere given by its centre and radius (radius > 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius, positive.
    pub radius: f32,
}

/// How a sphere's texture coordinates lie on it: `u` is the longitude about the pole `z`,
/// measured from `x` towards `y` (`u = φ/2π`, wrapped to `[0, 1)`), and `v = θ/π` the angle
/// from the pole. The three are unit vectors, `x` and `y` perpendicular to `z` and to each
/// other (either handedness).
///
/// lucent's own spheres ([`SphereMap::LAT_LONG`]) have the pole `+y` and `u = ½` facing `−z`,
/// the lat-long convention of environment maps ([`crate::texture::image::latlong_uv`]);
/// Mitsuba's have the pole along their `to_world`'s z and `u = 0` along its x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereMap {
    /// Where `u = 0` on the equator.
    pub x: Vec3,
    /// Where `u = ¼`.
    pub y: Vec3,
    /// The pole, `v = 0`.
    pub z: Vec3,
}

impl Default for SphereMap {
    fn default() -> Self {
        Self::LAT_LONG
    }
}

impl SphereMap {
    /// lucent's lat-long layout: `u = ½ + atan2(n_x, −n_z)/2π`, `v = acos(n_y)/π`.
    pub const LAT_LONG: SphereMap = SphereMap {
        x: Vec3::Z,
        y: Vec3::NEG_X,
        z: Vec3::Y,
    };

    /// The texture coordinates of the point of unit normal `n`.
    pub fn uv(&self, n: Vec3) -> glam::Vec2 {
        let phi = n.dot(self.y).atan2(n.dot(self.x));
        let u = phi / std::f32::consts::TAU;
        let u = if u < 0.0 { u + 1.0 } else { u };
        let v = n.dot(self.z).clamp(-1.0, 1.0).acos() / std::f32::consts::PI;
        glam::Vec2::new(u, v)
    }

    /// `∂p/∂u` and `∂p/∂v` at the point of unit normal `n` on a sphere of `radius`: with
    /// `n = sin θ (cos φ x + sin φ y) + cos θ z`, `∂p/∂u = 2πr·sin θ·(−sin φ x + cos φ y)` and
    /// `∂p/∂v = πr·(cos θ (cos φ x + sin φ y) − sin θ z)`, worked out from `n`'s components
    /// without trigonometry. At the poles, where longitude is undefined, any tangent pair
    /// perpendicular to `n` stands in.
    pub fn tangents(&self, n: Vec3, radius: f32) -> (Vec3, Vec3) {
        let (a, b, c) = (n.dot(self.x), n.dot(self.y), n.dot(self.z));
        let s = (a * a + b * b).sqrt();
        if s < 1e-6 {
            let (t, u) = n.any_orthonormal_pair();
            return (
                t * (std::f32::consts::TAU * radius),
                u * (std::f32::consts::PI * radius),
            );
        }
        let dpdu = (self.y * a - self.x * b) * (std::f32::consts::TAU * radius);
        let dpdv =
            ((self.x * a + self.y * b) * (c / s) - self.z * s) * (std::f32::consts::PI * radius);
        (dpdu, dpdv)
    }
}

/// The real roots of the ray–sphere quadratic, smallest first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Roots {
    /// No real root: the ray's line misses the sphere.
    Miss,
    /// One double root: the line grazes the sphere.
    Graze(f32),
    /// Two roots: the line pierces the sphere, entering at the first and leaving at the second.
    Pierce(f32, f32),
}

impl Sphere {
    /// The roots of `a·t² + 2·b'·t + c = 0` with `a = d·d`, `b' = d·f`, `c = f·f − r²`, `f = o − center`.
    ///
    /// Two measures keep them accurate (Haines et al., "Precision Improvements for Ray/Sphere
    /// Intersection", Ray Tracing Gems 2019): the discriminant is computed as
    /// `a·(r² − |f − (b'/a)·d|²)`, the squared distance from the centre to the line, instead of
    /// the cancelling `b'² − a·c`; and the root of larger magnitude comes from
    /// `q = −b' − sign(b')·√disc` with the other as `c/q`, which never subtracts nearly equal numbers.
    pub fn roots(&self, ray: &Ray) -> Roots {
        let f = ray.origin - self.center;
        let a = ray.dir.length_squared();
        let b = ray.dir.dot(f);
        let c = f.length_squared() - self.radius * self.radius;
        let to_line = f - (b / a) * ray.dir;
        let disc = a * (self.radius * self.radius - to_line.length_squared());
        if disc.is_nan() || disc < 0.0 {
            return Roots::Miss; // also when the inputs are NaN
        }
        if disc == 0.0 {
            return Roots::Graze(-b / a);
        }
        let q = -(b + b.signum() * disc.sqrt());
        let (t0, t1) = (c / q, q / a);
        Roots::Pierce(t0.min(t1), t0.max(t1))
    }

    /// The nearest root in `(0, t_max)`: the entry point from outside, the exit from inside.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let in_range = |t: f32| t > 0.0 && t < t_max;
        match self.roots(ray) {
            Roots::Miss => None,
            Roots::Graze(t) => in_range(t).then_some(t),
            Roots::Pierce(t0, t1) => [t0, t1].into_iter().find(|&t| in_range(t)),
        }
    }

    /// How many times the ray crosses the surface in `(0, t_max)` (0, 1 or 2); a graze counts once.
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> u32 {
        let in_range = |t: f32| u32::from(t > 0.0 && t < t_max);
        match self.roots(ray) {
            Roots::Miss => 0,
            Roots::Graze(t) => in_range(t),
            Roots::Pierce(t0, t1) => in_range(t0) + in_range(t1),
        }
    }

    /// The outward unit normal at `p`: the line from the centre through the point.
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        // A point that rounds onto the centre (a tiny sphere far out, where a scene file's
        // check does not reach: a moved one) still gets a unit normal.
        (p - self.center).normalize_or(Vec3::Z)
    }

    /// `p` moved radially onto the surface, which removes most of the rounding error of `o + t·d`.
    pub fn project_to_surface(&self, p: Vec3) -> Vec3 {
        let d = p - self.center;
        let length = d.length();
        if length.is_nan() || length == 0.0 {
            return p;
        }
        self.center + d * (self.radius / length)
    }

    /// The bounding box.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            self.center - Vec3::splat(self.radius),
            self.center + Vec3::splat(self.radius),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_that_rounds_onto_the_centre_keeps_finite_geometry() {
        // 1e-8 is far below the spacing of floats at 5e19: every hit rounds to the centre.
        let s = Sphere {
            center: Vec3::new(0.1, 0.2, -5e19),
            radius: 1e-8,
        };
        let p = s.project_to_surface(s.center);
        assert_eq!(p, s.center);
        assert_eq!(s.normal_at(p), Vec3::Z);
    }

    #[test]
    fn the_lat_long_map_is_the_environments() {
        for n in [Vec3::new(0.3, 0.5, -0.81), Vec3::new(-0.7, -0.2, 0.68)] {
            let n = n.normalize();
            let want = crate::texture::image::latlong_uv(n);
            assert!((SphereMap::LAT_LONG.uv(n) - want).length() < 1e-5, "{n}");
        }
    }

    #[test]
    fn the_tangents_are_the_derivatives_of_the_map() {
        // Moving along ∂p/∂u by a small step moves u by that step, and v not; likewise for v.
        let s = Sphere {
            center: Vec3::new(1.0, 2.0, 3.0),
            radius: 2.0,
        };
        let mitsuba = SphereMap {
            x: Vec3::X,
            y: Vec3::Y,
            z: Vec3::Z,
        };
        for map in [SphereMap::LAT_LONG, mitsuba] {
            for n in [
                Vec3::new(0.3, 0.5, -0.81),
                Vec3::new(-0.7, -0.2, 0.68),
                Vec3::new(0.1, 0.9, 0.42),
            ] {
                let n = n.normalize();
                let (dpdu, dpdv) = map.tangents(n, s.radius);
                let uv = map.uv(n);
                let h = 1e-3;
                for (d, du, dv) in [(dpdu, h, 0.0), (dpdv, 0.0, h)] {
                    let q = s.center + n * s.radius + d * h;
                    let moved = map.uv(s.normal_at(q));
                    assert!(
                        ((moved.x - uv.x) - du).abs() < 2e-5,
                        "{n}: du {}",
                        moved.x - uv.x
                    );
                    assert!(
                        ((moved.y - uv.y) - dv).abs() < 2e-5,
                        "{n}: dv {}",
                        moved.y - uv.y
                    );
                }
                assert!(dpdu.dot(n).abs() < 1e-5 && dpdv.dot(n).abs() < 1e-5);
            }
            let (a, b) = map.tangents(map.z, s.radius);
            assert!(a.is_finite() && b.is_finite() && a.dot(map.z).abs() < 1e-5);
        }
        // Mitsuba's sphere: u = 0 along +x, u = ¼ along +y, v = 0 at +z.
        assert!((mitsuba.uv(Vec3::Y) - glam::Vec2::new(0.25, 0.5)).length() < 1e-6);
        assert!(mitsuba.uv(Vec3::Z).y.abs() < 1e-6);
    }

    fn unit_sphere() -> Sphere {
        Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        }
    }

    #[test]
    fn a_ray_beside_the_sphere_has_no_root() {
        let ray = Ray::new(Vec3::new(1.5, 0.0, -5.0), Vec3::Z);
        assert_eq!(unit_sphere().roots(&ray), Roots::Miss);
        assert_eq!(unit_sphere().intersect(&ray, f32::INFINITY), None);
    }

    #[test]
    fn a_tangent_ray_grazes_at_one_root() {
        let ray = Ray::new(Vec3::new(1.0, 0.0, -5.0), Vec3::Z);
        assert_eq!(unit_sphere().roots(&ray), Roots::Graze(5.0));
        assert_eq!(unit_sphere().intersect(&ray, f32::INFINITY), Some(5.0));
    }

    #[test]
    fn a_central_ray_pierces_at_two_roots_and_hits_the_nearer() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        assert_eq!(unit_sphere().roots(&ray), Roots::Pierce(4.0, 6.0));
        assert_eq!(unit_sphere().intersect(&ray, f32::INFINITY), Some(4.0));
    }

    #[test]
    fn an_off_centre_ray_hits_at_the_known_distance() {
        // Offset 0.6 from the axis: the chord's half-length is 0.8, so t = 5 − 0.8.
        let ray = Ray::new(Vec3::new(0.6, 0.0, -5.0), Vec3::Z);
        let t = unit_sphere().intersect(&ray, f32::INFINITY).unwrap();
        assert!((t - 4.2).abs() < 1e-6, "t = {t}");
    }

    #[test]
    fn a_ray_from_inside_hits_the_far_side() {
        let ray = Ray::new(Vec3::new(0.0, 0.5, 0.0), Vec3::Y);
        assert_eq!(unit_sphere().intersect(&ray, f32::INFINITY), Some(0.5));
    }

    #[test]
    fn a_sphere_behind_the_ray_is_missed() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::Z);
        assert_eq!(unit_sphere().intersect(&ray, f32::INFINITY), None);
    }

    #[test]
    fn unnormalised_directions_measure_t_in_their_own_units() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), 2.0 * Vec3::Z);
        assert_eq!(unit_sphere().intersect(&ray, f32::INFINITY), Some(2.0));
    }

    #[test]
    fn a_small_far_sphere_keeps_its_precision() {
        // The naive b² − ac loses every digit here; the stable form keeps t to f32 precision.
        let s = Sphere {
            center: Vec3::new(0.0, 0.0, 10_000.0),
            radius: 0.01,
        };
        let ray = Ray::new(Vec3::ZERO, Vec3::Z);
        let t = s.intersect(&ray, f32::INFINITY).unwrap();
        assert!((t - 9_999.99).abs() < 2e-3, "t = {t}");
    }

    #[test]
    fn crossings_count_surfaces_inside_the_segment() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        assert_eq!(unit_sphere().crossings(&ray, 10.0), 2);
        assert_eq!(unit_sphere().crossings(&ray, 5.0), 1);
        assert_eq!(unit_sphere().crossings(&ray, 3.0), 0);
    }

    #[test]
    fn the_normal_points_outward() {
        let n = unit_sphere().normal_at(Vec3::new(0.0, 0.0, -1.0));
        assert_eq!(n, Vec3::new(0.0, 0.0, -1.0));
    }
}
