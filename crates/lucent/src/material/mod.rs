//! Materials: one description that every integrator reads.
//!
//! The classic coefficients of the Whitted model (see [`crate::integrator::whitted`]):
//! `I = ka·Ia + Σ_j S_j·I_j·att_j·(kd·max(N·L, 0) + ks·max(R·V, 0)^shininess) + kr·Ir + kt·It`,
//! and the physically based [`Surface`] that the path tracer samples. A scene file's material
//! sets both: a `whitted` material's surface is [`Surface::Classic`] (its coefficients read as
//! lobes, [`crate::bsdf::Bsdf::Classic`]), and a physically based one carries the classic
//! coefficients nearest to it for the Whitted integrator.

use crate::Rgb;
use crate::bsdf::Bsdf;
use crate::texture::Texture;

/// The physically based description of a surface, read by the path tracer. Diffuse colours
/// come from the material's `kd` texture (evaluated at the hit).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Surface {
    /// The classic coefficients as lobes: Lambert `kd`, normalised Phong `ks`/`shininess`,
    /// mirror `kr`, refraction `kt` with `ior`.
    #[default]
    Classic,
    /// Lambertian, albedo `kd`.
    Diffuse,
    /// A metal of complex index `eta + i·k`; `alpha` is the GGX roughness (0: smooth).
    Conductor {
        /// Real part of the index of refraction, per channel.
        eta: Rgb,
        /// Extinction coefficient, per channel.
        k: Rgb,
        /// Tint of the reflection.
        specular: Rgb,
        /// GGX roughness; 0 for a smooth mirror.
        alpha: f32,
    },
    /// Glass: relative index `eta` (inside over outside); `alpha` as for conductors.
    Dielectric {
        /// Index of the inside relative to the outside.
        eta: f32,
        /// Tint of the reflection.
        specular: Rgb,
        /// Tint of the transmission.
        transmittance: Rgb,
        /// GGX roughness; 0 for smooth glass.
        alpha: f32,
    },
    /// A diffuse base `kd` under a dielectric coat of relative index `eta`.
    Plastic {
        /// Index of the coat relative to the outside.
        eta: f32,
        /// Tint of the coat's reflection.
        specular: Rgb,
        /// GGX roughness of the coat; 0 for a smooth coat.
        alpha: f32,
    },
}

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
    /// The physically based description the path tracer samples.
    pub surface: Surface,
    /// Whether the back of the surface scatters light as its front does (the path tracer;
    /// Whitted lights both sides). One-sided reflecting surfaces are black from behind.
    pub two_sided: bool,
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
            surface: Surface::Classic,
            two_sided: true,
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

    /// A physically based Lambertian material of albedo `albedo` (its classic `kd` too).
    pub fn lambertian(albedo: Rgb) -> Self {
        Self {
            kd: Texture::Solid(albedo),
            surface: Surface::Diffuse,
            ..Self::default()
        }
    }

    /// The BSDF at a surface point whose diffuse colour (`kd` evaluated there) is `kd`.
    pub fn bsdf(&self, kd: Rgb) -> Bsdf {
        match self.surface {
            Surface::Classic => {
                // Whitted's coefficients often add up to more than 1 (the default scene's glass:
                // ks 0.7 + kr 0.1 + kt 0.88): harmless for one bounce, but a path tracer
                // multiplies them at every bounce, and light trapped in glass would grow without
                // bound. Scaled down together to sum to at most 1, they keep their balance.
                let sum = (kd + self.ks + self.kr + self.kt).max_channel();
                let s = if sum > 1.0 { 1.0 / sum } else { 1.0 };
                Bsdf::Classic {
                    kd: kd * s,
                    ks: self.ks * s,
                    shininess: self.shininess,
                    kr: self.kr * s,
                    kt: self.kt * s,
                    eta: self.ior,
                }
            }
            Surface::Diffuse => Bsdf::Lambert { albedo: kd },
            Surface::Conductor {
                eta,
                k,
                specular,
                alpha,
            } => {
                if alpha > 0.0 {
                    Bsdf::RoughConductor {
                        eta,
                        k,
                        specular,
                        alpha,
                    }
                } else {
                    Bsdf::Conductor { eta, k, specular }
                }
            }
            Surface::Dielectric {
                eta,
                specular,
                transmittance,
                alpha,
            } => {
                if alpha > 0.0 {
                    Bsdf::RoughDielectric {
                        eta,
                        specular,
                        transmittance,
                        alpha,
                    }
                } else {
                    Bsdf::Dielectric {
                        eta,
                        specular,
                        transmittance,
                    }
                }
            }
            Surface::Plastic {
                eta,
                specular,
                alpha,
            } => Bsdf::Plastic {
                diffuse: kd,
                eta,
                specular,
                alpha,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classic_lobes_that_sum_past_one_are_scaled_together() {
        let glass = Material {
            ks: Rgb::gray(0.7),
            kr: Rgb::gray(0.1),
            kt: Rgb::gray(0.88),
            ior: 1.5,
            ..Material::default()
        };
        let Bsdf::Classic { kd, ks, kr, kt, .. } = glass.bsdf(Rgb::BLACK) else {
            panic!("a whitted material is the classic BSDF");
        };
        assert!(((kd + ks + kr + kt).max_channel() - 1.0).abs() < 1e-6);
        assert!(
            (ks.r / kt.r - 0.7 / 0.88).abs() < 1e-6,
            "the balance is kept"
        );
        // Coefficients that fit are used as given.
        let matte = Material::diffuse(Rgb::gray(0.6));
        assert_eq!(
            matte.bsdf(Rgb::gray(0.6)),
            Bsdf::Classic {
                kd: Rgb::gray(0.6),
                ks: Rgb::BLACK,
                shininess: 0.0,
                kr: Rgb::BLACK,
                kt: Rgb::BLACK,
                eta: 1.0
            }
        );
    }
}
