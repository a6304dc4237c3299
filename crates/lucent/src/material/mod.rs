//! Materials: one description that every integrator reads.
//!
//! The classic coefficients of the Whitted model (see [`crate::integrator::whitted`]):
//! `I = ka·Ia + Σ_j S_j·I_j·att_j·(kd·max(N·L, 0) + ks·max(R·V, 0)^shininess) + kr·Ir + kt·It`.

use crate::Rgb;
use crate::texture::Texture;

/// A surface's response to light, per RGB channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Ambient coefficient, multiplies the scene's ambient light `Ia`.
    pub ka: Rgb,
    /// Diffuse coefficient (a texture): Lambert's `kd·max(N·L, 0)`.
    pub kd: Texture,
    /// Specular coefficient of the Phong highlight `ks·max(R·V, 0)^shininess`.
    pub ks: Rgb,
    /// Phong exponent; larger is a smaller, sharper highlight.
    pub shininess: f32,
    /// Mirror reflection coefficient: the weight of the reflected ray's colour `Ir`.
    pub kr: Rgb,
    /// Transmission coefficient: the weight of the refracted ray's colour `It`.
    pub kt: Rgb,
    /// Index of refraction of the material's inside (the outside is taken as vacuum, 1).
    pub ior: f32,
    /// Radiance the surface emits from its front side (an area light); added to what it
    /// reflects.
    pub ke: Rgb,
}

impl Default for Material {
    /// All coefficients 0 (black, opaque), index of refraction 1.
    fn default() -> Self {
        Self {
            ka: Rgb::BLACK,
            kd: Texture::Solid(Rgb::BLACK),
            ks: Rgb::BLACK,
            shininess: 0.0,
            kr: Rgb::BLACK,
            kt: Rgb::BLACK,
            ior: 1.0,
            ke: Rgb::BLACK,
        }
    }
}

impl Material {
    /// A matte material of diffuse colour `kd`.
    pub fn diffuse(kd: Rgb) -> Self {
        Self {
            kd: Texture::Solid(kd),
            ..Self::default()
        }
    }
}
