//! Materials: one description that every integrator reads.
//!
//! A material holds the physically based [`Surface`] that the path tracer and the photon
//! mapper sample, and the classic coefficients of the Whitted model (see
//! [`crate::integrator::whitted`]):
//! `I = ka·Ia + Σ_j S_j·I_j·att_j·(kd·max(N·L, 0) + ks·max(R·V, 0)^shininess) + kr·Ir + kt·It`.
//! A `whitted` material's surface is [`Surface::Classic`] (its coefficients read as lobes,
//! [`crate::bsdf::Bsdf::Classic`]); a physically based one carries the classic coefficients
//! nearest to it, derived here ([`Material::physically_based`], `material/classic.rs`).
//!
//! Every parameter a format can texture is a [`Texture`]; a surface is a tree whose leaves are
//! scattering models and whose inner nodes blend two surfaces, pick one per side, or perturb
//! the shading normal of the surface below (normal and bump maps). At a hit the tree is
//! resolved into a [`Scattering`]: the leaves' BSDFs with their textures evaluated, each with
//! its weight and shading frame.

mod classic;
mod gltf;
pub mod metals;
mod principled;
mod scattering;
mod shading;

pub use classic::Approximation;
pub use gltf::GltfMaps;
pub use principled::{PrincipledMaps, PrincipledThinMaps};
pub(crate) use scattering::unleaked;
pub use scattering::{Part, Scattering, ScatteringSample, Side, Terminator};
pub use shading::{Geometry, facing, facing_lanes};

use std::sync::Arc;

use crate::Rgb;
use crate::bsdf::{Bsdf, Distribution, Microfacet, RoughCoat};
use crate::texture::{ImageTexture, TexCoords, Texture};

/// A rough surface's microfacets: the distribution, and the roughness `α` along the shading
/// frame's tangent and bitangent (textures of numbers; the same texture twice when isotropic).
#[derive(Clone, Debug, PartialEq)]
pub struct Roughness {
    /// GGX or Beckmann.
    pub distribution: Distribution,
    /// `α` along the tangent.
    pub alpha_u: Texture,
    /// `α` along the bitangent.
    pub alpha_v: Texture,
}

impl Roughness {
    /// Isotropic roughness `alpha` of `distribution`.
    pub fn isotropic(distribution: Distribution, alpha: f32) -> Self {
        Self {
            distribution,
            alpha_u: Texture::from(alpha),
            alpha_v: Texture::from(alpha),
        }
    }

    /// The microfacets at `at`.
    pub(crate) fn at(&self, at: &TexCoords, images: &[ImageTexture]) -> Microfacet {
        let u = self.alpha_u.eval_float(at, images);
        let v = if self.alpha_v == self.alpha_u {
            u
        } else {
            self.alpha_v.eval_float(at, images)
        };
        Microfacet::new(self.distribution, u, v)
    }

    /// The mean roughness over the surface, for the Whitted integrator's Phong exponent.
    fn mean_alpha(&self, images: &[ImageTexture]) -> f32 {
        0.5 * (self.alpha_u.mean(images).mean() + self.alpha_v.mean(images).mean())
    }
}

/// The physically based description of a surface, read by the path tracer and the photon
/// mapper: a scattering model with its parameters, or a node combining surfaces.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Surface {
    /// The material's classic coefficients as lobes: Lambert `kd`, normalised Phong
    /// `ks`/`shininess`, mirror `kr`, refraction `kt` with `ior`.
    #[default]
    Classic,
    /// Lambertian (Mitsuba `diffuse`).
    Diffuse {
        /// Hemispherical reflectance.
        reflectance: Texture,
    },
    /// A metal of complex index `eta + i·k`, smooth or rough (Mitsuba `conductor`,
    /// `roughconductor`).
    Conductor {
        /// Real part of the index of refraction, per channel.
        eta: Texture,
        /// Extinction coefficient, per channel.
        k: Texture,
        /// Tint of the reflection.
        specular: Texture,
        /// `None` for a smooth mirror.
        roughness: Option<Roughness>,
    },
    /// Glass: relative index `eta` (inside over outside), smooth or rough (Mitsuba
    /// `dielectric`, `roughdielectric`).
    Dielectric {
        /// Index of the inside relative to the outside.
        eta: f32,
        /// Tint of the reflection.
        specular: Texture,
        /// Tint of the transmission.
        transmittance: Texture,
        /// `None` for smooth glass.
        roughness: Option<Roughness>,
    },
    /// A thin sheet of glass (Mitsuba `thindielectric`).
    ThinDielectric {
        /// Index of the sheet relative to the outside.
        eta: f32,
        /// Tint of the reflection.
        specular: Texture,
        /// Tint of the transmission.
        transmittance: Texture,
    },
    /// A diffuse base under a dielectric coat, smooth or rough (Mitsuba `plastic`,
    /// `roughplastic`).
    Plastic {
        /// Reflectance of the base.
        diffuse: Texture,
        /// Index of the coat relative to the outside.
        eta: f32,
        /// Tint of the coat's reflection.
        specular: Texture,
        /// Sum the base's internal bounces (Mitsuba's `nonlinear`).
        nonlinear: bool,
        /// The rough coat with its tables; `None` for a smooth coat.
        coat: Option<Arc<RoughCoat>>,
    },
    /// The Disney principled BSDF (Mitsuba `principled`).
    Principled(Box<PrincipledMaps>),
    /// The thin-sheet Disney BSDF (Mitsuba `principledthin`).
    PrincipledThin(Box<PrincipledThinMaps>),
    /// glTF 2.0's metallic-roughness material with its extensions' layers.
    Gltf(Box<GltfMaps>),
    /// `first·(1 − weight) + second·weight` (Mitsuba `blendbsdf`).
    Blend {
        /// The share of `second`, a number in `[0, 1]`.
        weight: Texture,
        /// Where `weight` is 0.
        first: Box<Surface>,
        /// Where `weight` is 1.
        second: Box<Surface>,
    },
    /// One surface for the front, another for the back (Mitsuba `twosided` with two BSDFs).
    TwoSided {
        /// Seen from the side the shading normal points to.
        front: Box<Surface>,
        /// Seen from the other side, as if it were the front.
        back: Box<Surface>,
    },
    /// `inner` with its shading normal read from a tangent-space normal map (Mitsuba
    /// `normalmap`; glTF's `normalTexture`).
    NormalMap {
        /// The map: `2·texel − 1` is the normal in the frame (tangent, bitangent, normal).
        normals: Texture,
        /// glTF's `scale`: multiplies the map's x and y (1 for Mitsuba).
        strength: f32,
        /// The surface it applies to.
        inner: Box<Surface>,
    },
    /// `inner` with its shading normal bent by the gradient of a height texture (Mitsuba
    /// `bumpmap`).
    BumpMap {
        /// The height, a number-valued texture.
        height: Texture,
        /// Multiplies the height.
        scale: f32,
        /// The surface it applies to.
        inner: Box<Surface>,
    },
}

impl Surface {
    /// A plastic of coat index `eta`, rough when `roughness` is given (its coat's tables are
    /// integrated now: a few tens of milliseconds; share one [`RoughCoat`] between materials
    /// with [`Surface::plastic_with`]).
    pub fn plastic(
        diffuse: Texture,
        eta: f32,
        specular: Texture,
        nonlinear: bool,
        roughness: Option<(Distribution, f32)>,
    ) -> Self {
        let coat = roughness
            .map(|(d, alpha)| Arc::new(RoughCoat::new(Microfacet::isotropic(d, alpha), eta)));
        Self::plastic_with(diffuse, eta, specular, nonlinear, coat)
    }

    /// A plastic whose rough coat, if any, is `coat`.
    pub fn plastic_with(
        diffuse: Texture,
        eta: f32,
        specular: Texture,
        nonlinear: bool,
        coat: Option<Arc<RoughCoat>>,
    ) -> Self {
        Surface::Plastic {
            diffuse,
            eta,
            specular,
            nonlinear,
            coat,
        }
    }

    /// Whether any texture of the tree reads texture coordinates (asked at every hit: the
    /// common leaves are answered without visiting the tree).
    #[inline]
    pub fn uses_uv(&self) -> bool {
        match self {
            Surface::Classic => false,
            Surface::Diffuse { reflectance } => reflectance.uses_uv(),
            Surface::Plastic {
                diffuse, specular, ..
            } => diffuse.uses_uv() || specular.uses_uv(),
            Surface::NormalMap { .. } | Surface::BumpMap { .. } => true,
            _ => {
                let mut any = false;
                self.visit_textures(&mut |t| any |= t.uses_uv());
                any || self.perturbs_normal()
            }
        }
    }

    /// Whether the tree's shading frame must follow the surface's tangents (anisotropic or
    /// possibly anisotropic lobes, normal and bump maps): an isotropic BSDF works in any frame
    /// around the normal, so hits on such surfaces skip working the tangents out.
    #[inline]
    pub fn needs_tangents(&self) -> bool {
        match self {
            Surface::Classic
            | Surface::Diffuse { .. }
            | Surface::Plastic { .. }
            | Surface::ThinDielectric { .. } => false,
            Surface::Conductor { roughness, .. } | Surface::Dielectric { roughness, .. } => {
                roughness.is_some()
            }
            _ => true,
        }
    }

    /// Whether the tree holds a normal or bump map.
    pub fn perturbs_normal(&self) -> bool {
        match self {
            Surface::NormalMap { .. } | Surface::BumpMap { .. } => true,
            Surface::Blend { first, second, .. } => {
                first.perturbs_normal() || second.perturbs_normal()
            }
            Surface::TwoSided { front, back } => front.perturbs_normal() || back.perturbs_normal(),
            _ => false,
        }
    }

    /// Whether any leaf can transmit light (glass): such surfaces take no side flipping.
    pub fn transmits(&self) -> bool {
        match self {
            Surface::Dielectric { .. }
            | Surface::ThinDielectric { .. }
            | Surface::PrincipledThin(_) => true,
            Surface::Principled(p) => p.spec_trans.mean(&[]).max_channel() > 0.0,
            Surface::Gltf(p) => {
                p.transmission.mean(&[]).max_channel() > 0.0
                    || p.diffuse_transmission.mean(&[]).max_channel() > 0.0
            }
            Surface::Blend { first, second, .. } => first.transmits() || second.transmits(),
            Surface::TwoSided { front, back } => front.transmits() || back.transmits(),
            Surface::NormalMap { inner, .. } | Surface::BumpMap { inner, .. } => inner.transmits(),
            _ => false,
        }
    }

    /// Calls `f` on every texture of the tree.
    pub fn visit_textures(&self, f: &mut impl FnMut(&Texture)) {
        let rough = |r: &Option<Roughness>, f: &mut dyn FnMut(&Texture)| {
            if let Some(r) = r {
                f(&r.alpha_u);
                f(&r.alpha_v);
            }
        };
        match self {
            Surface::Classic => {}
            Surface::Diffuse { reflectance } => f(reflectance),
            Surface::Conductor {
                eta,
                k,
                specular,
                roughness,
            } => {
                f(eta);
                f(k);
                f(specular);
                rough(roughness, f);
            }
            Surface::Dielectric {
                specular,
                transmittance,
                roughness,
                ..
            } => {
                f(specular);
                f(transmittance);
                rough(roughness, f);
            }
            Surface::ThinDielectric {
                specular,
                transmittance,
                ..
            } => {
                f(specular);
                f(transmittance);
            }
            Surface::Plastic {
                diffuse, specular, ..
            } => {
                f(diffuse);
                f(specular);
            }
            Surface::Principled(p) => p.textures().into_iter().for_each(f),
            Surface::PrincipledThin(p) => p.textures().into_iter().for_each(f),
            Surface::Gltf(p) => p.textures().into_iter().for_each(f),
            Surface::Blend {
                weight,
                first,
                second,
            } => {
                f(weight);
                first.visit_textures(f);
                second.visit_textures(f);
            }
            Surface::TwoSided { front, back } => {
                front.visit_textures(f);
                back.visit_textures(f);
            }
            Surface::NormalMap { normals, inner, .. } => {
                f(normals);
                inner.visit_textures(f);
            }
            Surface::BumpMap { height, inner, .. } => {
                f(height);
                inner.visit_textures(f);
            }
        }
    }
}

/// A surface's response to light, per RGB channel.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Ambient coefficient, multiplies the scene's ambient light `Ia`.
    pub ka: Rgb,
    /// A texture multiplying `ka` (POV-Ray's ambient term follows the pigment's pattern).
    pub ka_map: Option<Texture>,
    /// Diffuse coefficient (a texture): Lambert's `kd·max(N·L, 0)`.
    pub kd: Texture,
    /// Specular coefficient of the Phong highlight `ks·max(R·V, 0)^shininess`.
    pub ks: Rgb,
    /// Phong exponent; larger is a smaller, sharper highlight.
    pub shininess: f32,
    /// The highlight is Blinn's `ks·max(N·H, 0)^shininess` (H halfway between L and V, POV-Ray's
    /// `specular`) instead of Phong's.
    pub blinn: bool,
    /// The exponent of `N·L` in the diffuse term (POV-Ray's `brilliance`; 1 is Lambert's).
    pub brilliance: f32,
    /// Mirror reflection coefficient: the weight of the reflected ray's colour `Ir`.
    pub kr: Rgb,
    /// Transmission coefficient: the weight of the refracted ray's colour `It`.
    pub kt: Rgb,
    /// Index of refraction of the material's inside (the outside is taken as vacuum, 1).
    pub ior: f32,
    /// A solid pattern bending the shading normal of the classic terms (POV-Ray's `normal`):
    /// lighting, reflection and refraction all see the bent normal.
    pub bump: Option<Box<crate::texture::bump::Bump>>,
    /// Radiance the surface emits from its front side (an area light); added to what it
    /// reflects.
    pub ke: Rgb,
    /// A texture multiplying `ke` (glTF's `emissiveTexture`); such a surface is not sampled as
    /// a light (its emission is found by the rays that hit it).
    pub emission_map: Option<Texture>,
    /// Coverage in `[0, 1]`: where it is below 1 the surface is partly cut away (glTF's alpha,
    /// Mitsuba's `mask`); `None` for an opaque surface.
    pub opacity: Option<Texture>,
    /// The physically based description the path tracer samples.
    pub surface: Surface,
    /// Whether the back of the surface scatters light as its front does (the path tracer;
    /// Whitted lights both sides). One-sided reflecting surfaces are black from behind.
    pub two_sided: bool,
    /// Whether a mesh's vertex colours multiply the diffuse colour (`kd`, and the base of
    /// diffuse and plastic surfaces). Mitsuba's scenes ask for them explicitly instead.
    pub vertex_colors: bool,
    /// Whether the surface's back is not there: every ray that meets it from behind passes
    /// through, as glTF culls the back faces of single-sided materials.
    pub cull_back: bool,
    /// Whether the surface emits from its back as from its front (glTF's unlit two-sided
    /// materials). Such a surface is never sampled as a light (the build gives it an
    /// `emission_map`): its light is found by the rays that hit it, from either side.
    pub emits_back: bool,
}

impl Default for Material {
    /// All coefficients 0 (black, opaque), index of refraction 1.
    fn default() -> Self {
        Self {
            ka: Rgb::BLACK,
            ka_map: None,
            kd: Texture::Solid(Rgb::BLACK),
            ks: Rgb::BLACK,
            shininess: 0.0,
            blinn: false,
            brilliance: 1.0,
            kr: Rgb::BLACK,
            kt: Rgb::BLACK,
            ior: 1.0,
            bump: None,
            ke: Rgb::BLACK,
            emission_map: None,
            opacity: None,
            surface: Surface::Classic,
            two_sided: true,
            vertex_colors: true,
            cull_back: false,
            emits_back: false,
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
        Self::physically_based(
            Surface::Diffuse {
                reflectance: Texture::Solid(albedo),
            },
            &[],
        )
        .0
    }

    /// A material of the physically based `surface`, with the classic coefficients nearest to
    /// it for the Whitted integrator, and what they approximate (`images` are the scene's, for
    /// the means of textures).
    pub fn physically_based(
        surface: Surface,
        images: &[ImageTexture],
    ) -> (Self, Option<Approximation>) {
        let (c, approx) = classic::nearest(&surface, images);
        let m = Self {
            ka: c.ka,
            ka_map: None,
            kd: c.kd,
            ks: c.ks,
            shininess: c.shininess,
            blinn: false,
            brilliance: 1.0,
            kr: c.kr,
            kt: c.kt,
            ior: c.ior,
            surface,
            ..Self::default()
        };
        (m, approx)
    }

    /// The emitted radiance at `at` (zero where not emitting).
    pub fn emission(&self, at: &TexCoords, images: &[ImageTexture]) -> Rgb {
        match &self.emission_map {
            Some(t) => self.ke * t.eval(at, images),
            None => self.ke,
        }
    }

    /// Whether the surface emits light somewhere.
    pub fn emits(&self) -> bool {
        !self.ke.is_black()
    }

    /// Whether a ray along `dir` meeting geometric normal `ng` sees the surface's emission: on
    /// its front, or on either side when it [`emits_back`](Material::emits_back).
    #[inline]
    pub fn emits_towards(&self, ng: glam::Vec3, dir: glam::Vec3) -> bool {
        self.emits() && (self.emits_back || ng.dot(dir) < 0.0)
    }

    /// Whether looking the surface's textures up needs texture coordinates.
    #[inline(always)]
    pub fn uses_uv(&self) -> bool {
        self.kd.uses_uv()
            || self.surface.uses_uv()
            || self.emission_map.as_ref().is_some_and(Texture::uses_uv)
            || self.opacity.as_ref().is_some_and(Texture::uses_uv)
    }

    /// Whether a hit on the material needs the surface's tangents (`∂p/∂u`, `∂p/∂v`, a mesh's
    /// tangent frame): for its textures' footprints or its shading frame.
    #[inline(always)]
    pub fn needs_tangents(&self) -> bool {
        self.uses_uv() || self.surface.needs_tangents()
    }

    /// The coverage at `at` (1 for an opaque material).
    pub fn opacity(&self, at: &TexCoords, images: &[ImageTexture]) -> f32 {
        self.opacity
            .as_ref()
            .map_or(1.0, |t| t.eval_float(at, images).clamp(0.0, 1.0))
    }

    /// The classic lobes for the path tracer at a point whose diffuse colour (`kd` evaluated
    /// there) is `kd`.
    pub(crate) fn classic_bsdf(&self, kd: Rgb) -> Bsdf<'static> {
        // Whitted's coefficients often add up to more than 1 (the default scene's glass:
        // ks 0.7 + kr 0.1 + kt 0.88): harmless for one bounce, but a path tracer multiplies
        // them at every bounce, and light trapped in glass would grow without bound. Scaled
        // down together to sum to at most 1, they keep their balance.
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
        let Bsdf::Classic { kd, ks, kr, kt, .. } = glass.classic_bsdf(Rgb::BLACK) else {
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
            matte.classic_bsdf(Rgb::gray(0.6)),
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
