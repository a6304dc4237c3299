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
        let distance = offset.length();
        if distance.is_nan() || distance <= 0.0 {
            return None;
        }
        let att = match self.falloff {
            Falloff::None => 1.0,
            Falloff::Quadratic => 1.0 / (distance * distance),
        };
        Some(LightSample {
            to_light: offset / distance,
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
}
