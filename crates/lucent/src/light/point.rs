//! Point lights.

use super::LightSample;
use crate::Rgb;
use glam::Vec3;

/// How a point light's intensity falls off with distance `d`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Falloff {
    /// No falloff (`att = 1`): the classic Whitted model, and the default.
    #[default]
    None,
    /// The physical inverse square law, `att = 1 / d²`.
    Quadratic,
}

/// Light from a point, equal in every direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Where the light is.
    pub position: Vec3,
    /// Its intensity `I_j` (at distance 1 under quadratic falloff).
    pub intensity: Rgb,
    /// How it falls off with distance.
    pub falloff: Falloff,
}

impl PointLight {
    /// See [`super::Light::illuminate`].
    pub fn illuminate(&self, p: Vec3) -> Option<LightSample> {
        let offset = self.position - p;
        // Brought to a largest component of 1 first: a light 1e20 away is still in a direction
        // though the square of its distance overflows.
        let largest = offset.abs().max_element();
        if !largest.is_finite() || largest <= 0.0 {
            return None;
        }
        let to_light = (offset / largest).normalize();
        let distance = largest * (offset / largest).length();
        let att = match self.falloff {
            Falloff::None => 1.0,
            Falloff::Quadratic => 1.0 / (distance * distance),
        };
        Some(LightSample {
            to_light,
            distance,
            intensity: self.intensity * att,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_falloff_quarters_at_double_distance() {
        let l = PointLight {
            position: Vec3::ZERO,
            intensity: Rgb::gray(8.0),
            falloff: Falloff::Quadratic,
        };
        let s = l.illuminate(Vec3::new(0.0, 2.0, 0.0)).unwrap();
        assert_eq!(s.intensity, Rgb::gray(2.0));
        assert_eq!(s.to_light, -Vec3::Y);
        assert_eq!(s.distance, 2.0);
        let classic = PointLight {
            falloff: Falloff::None,
            ..l
        };
        assert_eq!(
            classic
                .illuminate(Vec3::new(0.0, 2.0, 0.0))
                .unwrap()
                .intensity,
            Rgb::gray(8.0)
        );
    }

    #[test]
    fn a_light_whose_squared_distance_overflows_still_has_a_direction() {
        let l = PointLight {
            position: Vec3::new(0.0, 3e19, -4e19),
            intensity: Rgb::WHITE,
            falloff: Falloff::None,
        };
        let s = l.illuminate(Vec3::ZERO).unwrap();
        assert!((s.to_light - Vec3::new(0.0, 0.6, -0.8)).length() < 1e-6);
        assert!((s.distance / 5e19 - 1.0).abs() < 1e-6);
        // A distance that itself overflows keeps the direction too.
        let far = PointLight {
            position: Vec3::new(-3e38, 3e38, 0.0),
            ..l
        };
        let s = far.illuminate(Vec3::ZERO).unwrap();
        assert!((s.to_light - Vec3::new(-1.0, 1.0, 0.0).normalize()).length() < 1e-6);
        assert_eq!(s.distance, f32::INFINITY);
    }
}
