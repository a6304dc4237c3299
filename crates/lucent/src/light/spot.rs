//! Spot lights: point lights that shine into a cone.

use super::LightSample;
use super::image_light::Cone;
use super::point::PointLight;
use glam::Vec3;

/// A point light limited to a cone about `direction`, full inside `cos_start`, fading
/// smoothly (smoothstep in the cosine) to nothing at `cos_cutoff`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    /// Position, intensity and falloff with distance.
    pub point: PointLight,
    /// Unit direction of the cone's axis.
    pub direction: Vec3,
    /// Cosine of the cone's half-angle: no light outside.
    pub cos_cutoff: f32,
    /// Cosine of the half-angle where the fade to the edge starts (`≥ cos_cutoff`).
    pub cos_start: f32,
}

impl SpotLight {
    /// The light reaching `p`, if it lies inside the cone.
    pub fn illuminate(&self, p: Vec3) -> Option<LightSample> {
        let mut s = self.point.illuminate(p)?;
        let edge = self.cone().edge((-s.to_light).dot(self.direction));
        if edge == 0.0 {
            return None;
        }
        if edge < 1.0 {
            s.intensity = s.intensity * edge;
        }
        Some(s)
    }

    /// Its cone's edge.
    pub fn cone(&self) -> Cone {
        Cone {
            cos_cutoff: self.cos_cutoff,
            cos_start: self.cos_start,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rgb;
    use crate::light::Falloff;

    #[test]
    fn full_inside_faded_at_the_edge_dark_outside() {
        let spot = SpotLight {
            point: PointLight {
                position: Vec3::ZERO,
                intensity: Rgb::WHITE,
                falloff: Falloff::None,
            },
            direction: -Vec3::Y,
            cos_cutoff: 30f32.to_radians().cos(),
            cos_start: 20f32.to_radians().cos(),
        };
        let at = |deg: f32| {
            let d = Vec3::new(deg.to_radians().sin(), -deg.to_radians().cos(), 0.0);
            spot.illuminate(d * 2.0).map_or(0.0, |s| s.intensity.r)
        };
        assert_eq!(at(0.0), 1.0);
        assert_eq!(at(19.0), 1.0);
        let mid = at(25.0);
        assert!(mid > 0.0 && mid < 1.0, "{mid}");
        assert_eq!(at(31.0), 0.0);
        assert_eq!(at(90.0), 0.0);
    }
}
