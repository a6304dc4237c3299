//! Light sources: points and directions ([`Light`]), and for the path tracer also area lights
//! and the environment, sampled together through [`Emitters`].
//!
//! A light answers, for a point being shaded, where it is (direction and distance) and how
//! much it delivers there ([`LightSample`]); and, for photon mapping, where its light starts
//! and which way it goes ([`Photon`], [`Emitters::sample_photon`] in [`emission`]). To add a
//! kind: a file with its struct and `illuminate`, a variant here, a photon in [`emission`],
//! and its scene-file keys.

pub mod area;
pub mod directional;
pub mod emission;
pub mod emitters;
pub mod environment;
pub mod image_light;
pub mod photometric;
pub mod point;
pub mod spot;

pub use area::{AreaLights, EmitterSample};
pub use emission::{Photon, bounding_sphere};
pub use emitters::Emitters;
pub use environment::EnvironmentLight;
pub use image_light::{Cone, ImageLight, IntensityImage, IntensityImageError, Mapping};

pub use directional::DirectionalLight;
pub use photometric::{Goniometry, PhotometricLight, Profile, ProfileError};
pub use point::{Falloff, PointLight};
pub use spot::SpotLight;

use crate::Rgb;
use glam::Vec3;

/// A light source.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// Light from one point.
    Point(PointLight),
    /// Light from one point, into a cone.
    Spot(SpotLight),
    /// Parallel light from infinitely far away.
    Directional(DirectionalLight),
    /// Light from one point, as strong in each direction as a measured table says.
    Photometric(PhotometricLight),
    /// Light from one point, as strong in each direction as an image says: goniometric
    /// lights, projectors and spot lights with a texture.
    Image(ImageLight),
}

/// A light as seen from a shaded point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit vector from the shaded point towards the light (`L`).
    pub to_light: Vec3,
    /// Distance to the light along `to_light`; infinite for a directional light.
    pub distance: f32,
    /// Intensity arriving at the point, attenuation included (`I_j · att_j`).
    pub intensity: Rgb,
}

impl Light {
    /// Where a light at a point is; `None` for a light at infinity.
    pub fn position(&self) -> Option<Vec3> {
        match self {
            Light::Point(p) => Some(p.position),
            Light::Spot(s) => Some(s.point.position),
            Light::Photometric(l) => Some(l.point.position),
            Light::Image(l) => Some(l.point.position),
            Light::Directional(_) => None,
        }
    }

    /// The light as seen from `p`, or `None` when `p` is exactly at a point light.
    #[inline]
    pub fn illuminate(&self, p: Vec3) -> Option<LightSample> {
        match self {
            Light::Point(l) => l.illuminate(p),
            Light::Spot(l) => l.illuminate(p),
            Light::Directional(l) => Some(l.illuminate()),
            Light::Photometric(l) => l.illuminate(p),
            Light::Image(l) => l.illuminate(p),
        }
    }
}
