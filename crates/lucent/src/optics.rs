//! Mirror reflection and Snell's law, on unit vectors.

use glam::Vec3;

/// The mirror direction of `i` (travelling towards the surface) about the normal `n`:
/// `R = I − 2(N·I)N`. Works with `n` on either side.
#[inline]
pub fn reflect(i: Vec3, n: Vec3) -> Vec3 {
    i - 2.0 * n.dot(i) * n
}

/// The refracted direction of unit `i` through a surface with unit normal `n` facing the
/// incident side (`n · i ≤ 0`), where `mu = μ_incident / μ_transmitted`; `None` on total
/// internal reflection.
///
/// Snell's law `sin θi / sin θt = μt / μi` in vector form, with `c = −N·I = cos θi`:
/// `T = μ·I + N·(μ·c − √(1 − μ²(1 − c²)))`. The square root's argument is `cos² θt`; when it is
/// negative, no transmitted ray exists and all the light is reflected.
#[inline]
pub fn refract(i: Vec3, n: Vec3, mu: f32) -> Option<Vec3> {
    let c = -n.dot(i);
    let k = 1.0 - mu * mu * (1.0 - c * c);
    (k >= 0.0).then(|| mu * i + n * (mu * c - k.sqrt()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit direction going down into the surface `y = 0` at `deg` degrees from the normal.
    fn incident(deg: f32) -> Vec3 {
        let a = deg.to_radians();
        Vec3::new(a.sin(), -a.cos(), 0.0)
    }

    /// The angle between `t` and the inward normal −y, in degrees.
    fn angle_from_inward_normal(t: Vec3) -> f32 {
        t.normalize().dot(-Vec3::Y).acos().to_degrees()
    }

    #[test]
    fn reflection_mirrors_about_the_normal() {
        let r = reflect(incident(30.0), Vec3::Y);
        assert!((r - Vec3::new(0.5, 3f32.sqrt() / 2.0, 0.0)).length() < 1e-6);
        // The other side of the normal gives the same mirror.
        assert!((reflect(incident(30.0), -Vec3::Y) - r).length() < 1e-6);
    }

    #[test]
    fn air_to_glass_obeys_snell() {
        for deg in [0.0f32, 10.0, 30.0, 45.0, 60.0, 89.0] {
            let t = refract(incident(deg), Vec3::Y, 1.0 / 1.5).expect("no TIR entering glass");
            assert!((t.length() - 1.0).abs() < 1e-5, "T stays a unit vector");
            let expected = (deg.to_radians().sin() / 1.5).asin().to_degrees();
            let got = angle_from_inward_normal(t);
            assert!(
                (got - expected).abs() < 1e-3,
                "{deg}°: got {got}°, Snell says {expected}°"
            );
        }
    }

    #[test]
    fn glass_to_air_obeys_snell_below_the_critical_angle() {
        for deg in [0.0f32, 20.0, 40.0, 41.0] {
            let t = refract(incident(deg), Vec3::Y, 1.5).expect("below the critical angle");
            let expected = (1.5 * deg.to_radians().sin()).asin().to_degrees();
            let got = angle_from_inward_normal(t);
            assert!(
                (got - expected).abs() < 1e-2,
                "{deg}°: got {got}°, Snell says {expected}°"
            );
        }
    }

    #[test]
    fn total_internal_reflection_beyond_41_8_degrees() {
        // Critical angle of glass (1.5) to air: asin(1/1.5) = 41.81°.
        let critical = (1.0f32 / 1.5).asin().to_degrees();
        assert!((critical - 41.81).abs() < 0.01);
        assert!(refract(incident(41.7), Vec3::Y, 1.5).is_some());
        assert!(refract(incident(41.9), Vec3::Y, 1.5).is_none());
        assert!(refract(incident(70.0), Vec3::Y, 1.5).is_none());
    }

    #[test]
    fn a_round_trip_through_a_slab_restores_the_direction() {
        let i = incident(35.0);
        let inside = refract(i, Vec3::Y, 1.0 / 1.5).unwrap();
        let out = refract(inside, Vec3::Y, 1.5).unwrap();
        assert!((out - i).length() < 1e-5);
    }
}
