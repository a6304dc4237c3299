//! The classic Whitted coefficients nearest to a physically based surface, for the Whitted
//! integrator (the table is in `docs/scene-format.md`):
//!
//! | surface | classic coefficients |
//! | --- | --- |
//! | diffuse | `kd` = reflectance (its texture), `ka` = its mean |
//! | smooth plastic | as diffuse, plus `kr = specular·F0` |
//! | rough plastic | as diffuse, plus a Phong highlight `ks`, `shininess` of the coat's roughness |
//! | smooth conductor | `kr = specular·F0(η, k)` |
//! | rough conductor | a Phong highlight `ks = specular·F0`, `shininess` of the roughness |
//! | dielectric, thin dielectric | `kr = specular·F0`, `kt = transmittance·(1 − F0)`, `ior = η` (smooth) |
//! | principled (thin) | `kd` = base colour × the diffuse share, a Phong highlight `ks` of the metallic and dielectric reflection, `kt` the transmission |
//! | blend | the weighted mean of both sides' coefficients |
//! | two-sided, normal and bump maps | their (front) surface's |
//!
//! `F0` is the Fresnel reflectance at normal incidence; textured parameters other than the
//! diffuse colour count by their mean. The Phong exponent matching GGX roughness `α` is
//! `2/α² − 2` (Walter et al. 2007). What cannot be drawn as written is reported as an
//! [`Approximation`].

use crate::Rgb;
use crate::material::{Roughness, Surface};
use crate::texture::{ImageTexture, Texture};

/// Why a surface is drawn by the Whitted integrator other than as written, for one warning per
/// reason.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Approximation {
    /// A rough surface is drawn with a Phong highlight (or as smooth glass).
    Rough,
    /// A blend of two surfaces is drawn with the mean of their coefficients.
    Blend,
    /// A normal or bump map is not drawn (the surface's own normal is used).
    NormalMap,
}

/// The classic coefficients.
pub(super) struct Classic {
    pub ka: Rgb,
    pub kd: Texture,
    pub ks: Rgb,
    pub shininess: f32,
    pub kr: Rgb,
    pub kt: Rgb,
    pub ior: f32,
}

impl Classic {
    fn black() -> Self {
        Self {
            ka: Rgb::BLACK,
            kd: Texture::Solid(Rgb::BLACK),
            ks: Rgb::BLACK,
            shininess: 0.0,
            kr: Rgb::BLACK,
            kt: Rgb::BLACK,
            ior: 1.0,
        }
    }

    /// A diffuse classic material of colour `kd`.
    fn diffuse(kd: &Texture, images: &[ImageTexture]) -> Self {
        Self {
            ka: kd.mean(images),
            kd: kd.clone(),
            ..Self::black()
        }
    }
}

/// Normal-incidence Fresnel reflectance of a dielectric interface with relative index `eta`.
fn dielectric_f0(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// Normal-incidence Fresnel reflectance of a conductor, per channel.
fn conductor_f0(eta: Rgb, k: Rgb) -> Rgb {
    let f = |n: f32, k: f32| ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
    Rgb::new(f(eta.r, k.r), f(eta.g, k.g), f(eta.b, k.b))
}

/// The Phong exponent whose lobe matches GGX roughness `alpha` (Walter et al. 2007).
fn phong_exponent(alpha: f32) -> f32 {
    (2.0 / (alpha * alpha) - 2.0).max(1.0)
}

/// The Phong exponent of a rough surface's mean roughness.
fn shininess(r: &Roughness, images: &[ImageTexture]) -> f32 {
    phong_exponent(r.mean_alpha(images).max(1e-4))
}

/// The classic coefficients of `surface`, and what they approximate.
pub(super) fn nearest(
    surface: &Surface,
    images: &[ImageTexture],
) -> (Classic, Option<Approximation>) {
    let mean = |t: &Texture| t.mean(images);
    match surface {
        Surface::Classic => (Classic::black(), None),
        Surface::Diffuse { reflectance } => (Classic::diffuse(reflectance, images), None),
        Surface::Plastic {
            diffuse,
            eta,
            specular,
            coat,
            ..
        } => {
            let mut c = Classic::diffuse(diffuse, images);
            let f0 = dielectric_f0(*eta);
            match coat {
                Some(coat) => {
                    c.shininess = phong_exponent(coat.microfacet().mean_alpha());
                    c.ks = mean(specular) * (f0 * (c.shininess + 2.0) / 2.0).min(1.0);
                    (c, Some(Approximation::Rough))
                }
                None => {
                    c.kr = mean(specular) * f0;
                    (c, None)
                }
            }
        }
        Surface::Conductor {
            eta,
            k,
            specular,
            roughness,
        } => {
            let f0 = conductor_f0(mean(eta), mean(k));
            let mut c = Classic::black();
            match roughness {
                Some(r) => {
                    c.shininess = shininess(r, images);
                    c.ks = mean(specular) * f0;
                    (c, Some(Approximation::Rough))
                }
                None => {
                    c.kr = mean(specular) * f0;
                    (c, None)
                }
            }
        }
        Surface::Dielectric {
            eta,
            specular,
            transmittance,
            roughness,
        } => {
            let f0 = dielectric_f0(*eta);
            let c = Classic {
                ior: *eta,
                kr: mean(specular) * f0,
                kt: mean(transmittance) * (1.0 - f0),
                ..Classic::black()
            };
            (c, roughness.as_ref().map(|_| Approximation::Rough))
        }
        Surface::ThinDielectric {
            eta,
            specular,
            transmittance,
        } => {
            // Both faces reflect; the light passes unbent, as through glass of index 1.
            let r = dielectric_f0(*eta);
            let r = 2.0 * r / (1.0 + r);
            let c = Classic {
                ior: 1.0,
                kr: mean(specular) * r,
                kt: mean(transmittance) * (1.0 - r),
                ..Classic::black()
            };
            (c, None)
        }
        Surface::Principled(p) => {
            // The diffuse part as kd, the dielectric and metallic reflection as a highlight.
            let metallic = mean(&p.metallic).mean();
            let trans = mean(&p.spec_trans).mean();
            let base = mean(&p.base_color);
            let diffuse = (1.0 - metallic) * (1.0 - trans);
            let alpha = mean(&p.roughness).mean().powi(2).max(1e-3);
            let c = Classic {
                ka: base * diffuse,
                kd: Texture::Product(
                    Box::new(p.base_color.clone()),
                    Box::new(Texture::from(diffuse)),
                ),
                ks: base * metallic + Rgb::gray((1.0 - metallic) * dielectric_f0(p.eta)),
                shininess: phong_exponent(alpha),
                kt: base.map(f32::sqrt) * ((1.0 - metallic) * trans),
                ior: if trans > 0.0 { p.eta } else { 1.0 },
                ..Classic::black()
            };
            (c, Some(Approximation::Rough))
        }
        Surface::Gltf(p) => {
            // A metal's reflection and a dielectric's diffuse colour and coat.
            let metallic = mean(&p.metallic).mean();
            let trans = mean(&p.transmission).mean();
            let base = mean(&p.base_color);
            let diffuse = (1.0 - metallic) * (1.0 - trans);
            let alpha = mean(&p.roughness).mean().powi(2).max(1e-3);
            let f0 = dielectric_f0(p.ior);
            let c = Classic {
                ka: base * diffuse,
                kd: Texture::Product(
                    Box::new(p.base_color.clone()),
                    Box::new(Texture::from(diffuse)),
                ),
                ks: base * metallic + Rgb::gray((1.0 - metallic) * f0),
                shininess: phong_exponent(alpha),
                kt: base * ((1.0 - metallic) * trans),
                ior: if trans > 0.0 && p.volume { p.ior } else { 1.0 },
                ..Classic::black()
            };
            (c, Some(Approximation::Rough))
        }
        Surface::PrincipledThin(p) => {
            let trans = mean(&p.spec_trans).mean();
            let base = mean(&p.base_color);
            let alpha = mean(&p.roughness).mean().powi(2).max(1e-3);
            let c = Classic {
                ka: base * (1.0 - trans),
                kd: Texture::Product(
                    Box::new(p.base_color.clone()),
                    Box::new(Texture::from(1.0 - trans)),
                ),
                ks: Rgb::gray(trans * dielectric_f0(mean(&p.eta).mean())),
                shininess: phong_exponent(alpha),
                kt: base * trans,
                ior: 1.0,
                ..Classic::black()
            };
            (c, Some(Approximation::Rough))
        }
        Surface::Blend {
            weight,
            first,
            second,
        } => {
            let t = mean(weight).mean().clamp(0.0, 1.0);
            let (a, _) = nearest(first, images);
            let (b, _) = nearest(second, images);
            let mix = |x: Rgb, y: Rgb| x.lerp(y, t);
            let kd = Texture::Mix {
                a: Box::new(a.kd),
                b: Box::new(b.kd),
                t: Box::new(weight.clone()),
            };
            let c = Classic {
                ka: mix(a.ka, b.ka),
                kd,
                ks: mix(a.ks, b.ks),
                shininess: a.shininess * (1.0 - t) + b.shininess * t,
                kr: mix(a.kr, b.kr),
                kt: mix(a.kt, b.kt),
                ior: if b.kt.is_black() { a.ior } else { b.ior },
            };
            (c, Some(Approximation::Blend))
        }
        Surface::TwoSided { front, .. } => nearest(front, images),
        Surface::NormalMap { inner, .. } | Surface::BumpMap { inner, .. } => {
            let (c, approx) = nearest(inner, images);
            (c, approx.or(Some(Approximation::NormalMap)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::Distribution;

    #[test]
    fn fresnel_at_normal_incidence_and_phong_exponents() {
        assert!((dielectric_f0(1.5) - 0.04).abs() < 1e-6);
        assert_eq!(phong_exponent(1.0), 1.0);
        assert!((phong_exponent(0.1) - 198.0).abs() < 1e-3);
    }

    #[test]
    fn glass_mirrors_f0_and_transmits_the_rest() {
        let glass = Surface::Dielectric {
            eta: 1.5,
            specular: Texture::from(1.0),
            transmittance: Texture::from(1.0),
            roughness: None,
        };
        let (c, approx) = nearest(&glass, &[]);
        assert!(approx.is_none() && c.ior == 1.5);
        assert!((c.kr.r - 0.04).abs() < 1e-6 && (c.kt.r - 0.96).abs() < 1e-6);
        // Gold reflects red most and blue least.
        let gold = Surface::Conductor {
            eta: Texture::Solid(Rgb::new(0.143, 0.374, 1.442)),
            k: Texture::Solid(Rgb::new(3.983, 2.385, 1.603)),
            specular: Texture::from(1.0),
            roughness: Some(Roughness::isotropic(Distribution::Ggx, 0.1)),
        };
        let (c, approx) = nearest(&gold, &[]);
        assert_eq!(approx, Some(Approximation::Rough));
        assert!(c.ks.r > 0.9 && c.ks.g > 0.6 && c.ks.b < 0.5, "{:?}", c.ks);
        assert!((c.shininess - 198.0).abs() < 0.1);
    }
}
