//! Instances: one mesh placed in the world by an affine transform, stored once however many
//! times it is placed.
//!
//! A ray meets an instance in the mesh's own (object) space: its origin and direction are
//! carried there by the inverse transform, the direction left unnormalised, so that the ray
//! parameter `t` is the same in both spaces and hits compare directly with world-space ones.

use glam::{Affine3A, Mat3, Vec3};
use lucent_accel::{Aabb, Ray};

/// The largest ratio of a placement's greatest to its least scale (its condition number, as
/// bounded by Frobenius norms): the normal matrix scaled to a largest entry of 1 then shortens
/// no unit normal below 1e-30, so `normal_to_world` stays in normal single precision.
const MAX_CONDITION: f64 = 1e30;

/// An invertible affine map from object space to world space, with what queries need of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    to_world: Affine3A,
    to_object: Affine3A,
    /// The inverse transpose of the linear part: it carries normals to world space.
    normal_to_world: Mat3,
}

/// The inverse transpose of a placement's linear part, scaled so that its largest entry is 1: a
/// normal is normalised after the map, so a uniform factor is free, and this one keeps a huge or
/// tiny placement's normals in range.
fn normal_matrix(inverse_transpose: Mat3) -> Mat3 {
    let largest = [
        inverse_transpose.x_axis,
        inverse_transpose.y_axis,
        inverse_transpose.z_axis,
    ]
    .iter()
    .map(|c| c.abs().max_element())
    .fold(0.0, f32::max);
    inverse_transpose * largest.recip()
}

impl Transform {
    /// The transform `to_world`, or `None` when it cannot be inverted in single precision: a
    /// determinant that is zero or not finite, an inverse that overflows, or a placement so far
    /// from uniform (its smallest scale below 1e-30 of its largest) that a normal would
    /// underflow on its way to the world.
    pub fn new(to_world: Affine3A) -> Option<Self> {
        let det = to_world.matrix3.determinant();
        if !(det.is_finite() && det != 0.0 && to_world.translation.is_finite()) {
            return None;
        }
        let to_object = to_world.inverse();
        let normal_to_world = normal_matrix(Mat3::from(to_world.matrix3).inverse().transpose());
        // The ratio of the extreme scales bounds how short a mapped normal gets (the normal
        // matrix's singular values are the reciprocals of the placement's): the product of the
        // Frobenius norms of the map and its inverse bounds that ratio from above.
        let linear = Mat3::from(to_world.matrix3).as_dmat3();
        let frobenius = |m: glam::DMat3| {
            (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared())
                .sqrt()
        };
        let conditioned = frobenius(linear) * frobenius(linear.inverse()) <= MAX_CONDITION;
        (to_object.is_finite() && normal_to_world.is_finite() && conditioned).then_some(Self {
            to_world,
            to_object,
            normal_to_world,
        })
    }

    /// The transform `to_world` for an object that a motion carries, where [`Transform::new`]
    /// is too slow to call for every sample: the same maps, the normals' from the inverse
    /// already at hand, and the conditioning not checked again (the placement was, at rest and
    /// at time 0; a motion only turns, moves and scales by finite positive factors). `None`
    /// when something is not finite.
    pub fn moved(to_world: Affine3A) -> Option<Self> {
        let to_object = to_world.inverse();
        let normal_to_world = normal_matrix(Mat3::from(to_object.matrix3).transpose());
        let finite = to_world.is_finite() && to_object.is_finite() && normal_to_world.is_finite();
        finite.then_some(Self {
            to_world,
            to_object,
            normal_to_world,
        })
    }

    /// The object-to-world map.
    pub fn to_world(&self) -> Affine3A {
        self.to_world
    }

    /// `ray` in object space, with the same parameter `t`.
    #[inline]
    pub fn ray_to_object(&self, ray: &Ray) -> Ray {
        Ray::new(
            self.to_object.transform_point3(ray.origin),
            self.to_object.transform_vector3(ray.dir),
        )
    }

    /// A point from object to world space.
    #[inline]
    pub fn point_to_world(&self, p: Vec3) -> Vec3 {
        self.to_world.transform_point3(p)
    }

    /// A direction (a tangent, a difference of points) from object to world space.
    #[inline]
    pub fn vector_to_world(&self, v: Vec3) -> Vec3 {
        self.to_world.transform_vector3(v)
    }

    /// `1`, or `−1` where the transform mirrors (its linear part's determinant is negative).
    #[inline]
    pub fn handedness(&self) -> f32 {
        if self.to_world.matrix3.determinant() < 0.0 {
            -1.0
        } else {
            1.0
        }
    }

    /// A unit normal from object to world space (unit again). It keeps its side of the surface
    /// even under a mirroring transform, where the winding's normal would flip.
    #[inline]
    pub fn normal_to_world(&self, n: Vec3) -> Vec3 {
        let m = self.normal_to_world * n;
        let length2 = m.length_squared();
        if (1e-30..1e30).contains(&length2) {
            return m * length2.sqrt().recip();
        }
        // Brought to a largest component of 1 first: a thin placement's normal can be short
        // enough (about 1e-30) that its squared length would underflow.
        (m * m.abs().max_element().recip()).normalize()
    }

    /// A bound on the world-space error of `point_to_world(p)` when `p` carries the per-axis
    /// error bound `error`: the error carried through the linear part, plus the rounding of
    /// the transform itself.
    pub fn error_to_world(&self, p: Vec3, error: Vec3) -> Vec3 {
        let m = self.to_world.matrix3;
        let abs_m = glam::Mat3A::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
        let carried = Vec3::from(abs_m * glam::Vec3A::from(error));
        let own = Vec3::from(abs_m * glam::Vec3A::from(p.abs()))
            + Vec3::from(self.to_world.translation.abs());
        carried + super::gamma(4) * own
    }

    /// The world box around an object-space box (the box of its eight transformed corners).
    pub fn bounds_to_world(&self, b: Aabb) -> Aabb {
        if b.is_empty() {
            return b;
        }
        Aabb::from_points((0..8).map(|k| {
            let pick = |bit: usize, axis: usize| {
                if k & bit == 0 {
                    b.min[axis]
                } else {
                    b.max[axis]
                }
            };
            self.point_to_world(Vec3::new(pick(1, 0), pick(2, 1), pick(4, 2)))
        }))
    }
}

/// Mesh `mesh` of the scene, placed by `transform` (`None`: as it is).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Index of the mesh in the scene.
    pub mesh: u32,
    /// Object to world; `None` for the identity, which skips the ray transform.
    pub transform: Option<Transform>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn rays_keep_their_parameter_in_object_space() {
        let m = Affine3A::from_scale_rotation_translation(
            Vec3::new(2.0, 3.0, 0.5),
            Quat::from_rotation_y(0.7),
            Vec3::new(1.0, -2.0, 5.0),
        );
        let t = Transform::new(m).unwrap();
        let ray = Ray::new(
            Vec3::new(0.3, 0.1, -4.0),
            Vec3::new(0.2, 0.1, 1.0).normalize(),
        );
        let local = t.ray_to_object(&ray);
        for s in [0.0, 1.0, 7.5] {
            let back = t.point_to_world(local.at(s));
            assert!(
                (back - ray.at(s)).length() < 1e-4,
                "{back} vs {}",
                ray.at(s)
            );
        }
    }

    #[test]
    fn normals_stay_perpendicular_and_outward() {
        // A shear: a plain linear map would tilt the normal off the surface.
        let m = Affine3A::from_mat3(Mat3::from_cols(Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Z));
        let t = Transform::new(m).unwrap();
        let (u, v) = (
            t.to_world.transform_vector3(Vec3::X),
            t.to_world.transform_vector3(Vec3::Z),
        );
        let n = t.normal_to_world(Vec3::Y);
        assert!(n.dot(u).abs() < 1e-6 && n.dot(v).abs() < 1e-6 && n.y > 0.0);
        // A mirror in x keeps a +y normal pointing to +y.
        let mirror = Transform::new(Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0))).unwrap();
        assert_eq!(mirror.normal_to_world(Vec3::Y), Vec3::Y);
    }

    #[test]
    fn singular_transforms_are_refused() {
        assert!(Transform::new(Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0))).is_none());
        assert!(Transform::new(Affine3A::from_translation(Vec3::NAN)).is_none());
        // The determinant 1e-42 is not 0, but its reciprocal overflows.
        assert!(Transform::new(Affine3A::from_scale(Vec3::splat(1e-14))).is_none());
        // Invertible, but a normal along z would shrink to 1e-36 of the others.
        assert!(Transform::new(Affine3A::from_scale(Vec3::new(1e18, 1e18, 1e-18))).is_none());
    }

    #[test]
    fn normals_stay_unit_under_huge_and_tiny_placements() {
        // The last: an x normal divided by 3e22 has a square below the smallest float.
        for scale in [
            Vec3::splat(1e12),
            Vec3::splat(1e-12),
            Vec3::new(1e20, 1.0, 1e-6),
            Vec3::new(-3e12, 2e12, 1e12),
            Vec3::new(3e22, 1.0, 1e-7),
        ] {
            let t = Transform::new(Affine3A::from_scale(scale)).expect("invertible");
            for n in [Vec3::new(0.48, 0.6, 0.64), Vec3::X, Vec3::Y, Vec3::Z] {
                let world = t.normal_to_world(n);
                assert!((world.length() - 1.0).abs() < 1e-5, "{scale}, {n}: {world}");
                // The inverse transpose of a scale divides by it, component by component.
                let expected = (n.as_dvec3() / scale.as_dvec3()).normalize().as_vec3();
                assert!(
                    (world - expected).length() < 1e-5,
                    "{scale}: {world} vs {expected}"
                );
            }
        }
    }
}
