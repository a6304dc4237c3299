//! Directional lights: parallel rays from infinitely far away, like the sun.

use super::LightSample;
use crate::Rgb;
use glam::Vec3;

/// Parallel light travelling along `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit vector the light travels along (from the light towards the scene).
    pub direction: Vec3,
    /// Its intensity; no falloff.
    pub intensity: Rgb,
}

impl DirectionalLight {
    /// See [`super::Light::illuminate`].
    pub fn illuminate(&self) -> LightSample {
        LightSample {
            to_light: -self.direction,
            distance: f32::INFINITY,
            intensity: self.intensity,
        }
    }
}
