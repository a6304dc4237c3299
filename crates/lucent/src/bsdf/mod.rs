//! Scattering functions (BSDFs) for a path tracer: evaluate, sample and pdf, as Mitsuba 3 defines
//! them.
//!
//! # The contract
//! - **Local frame.** Every direction is in the local shading frame ([`Frame`]): `z` is the
//!   shading normal as the shape gives it (not turned towards the ray).
//! - **Directions point away from the surface and are unit vectors.** `wo` points towards the
//!   viewer (where the path came from), `wi` towards the light (the sampled next direction).
//!   `wo.z < 0` means the path arrives from the back, which for a dielectric is its inside.
//! - **Sides.** Reflection-only BSDFs (Lambert, the conductors, plastic, and Classic when
//!   `kt = 0`) are one-sided, as in Mitsuba: zero unless `wo.z > 0` and `wi.z > 0`. An integrator
//!   that wants a two-sided material flips the frame before calling. Transmitting BSDFs
//!   ([`Bsdf::transmits`]) must receive the unflipped frame: the sign of `wo.z` tells them which
//!   medium the path is in.
//! - **Cosines.** [`Bsdf::eval`] returns `f(wo, wi)·|cos θi|`, the cosine **included**, and
//!   [`BsdfSample::weight`] is `f·|cos θi| / pdf`, the factor a path's throughput is multiplied
//!   by.
//! - **Densities** are per unit solid angle of `wi`. A Dirac lobe (mirror, smooth refraction) has
//!   no density: its samples carry `delta = true` and, in `pdf`, the discrete probability of
//!   having chosen that lobe; `eval` and `pdf` ignore Dirac lobes entirely (they are zero there).
//! - **Consistency.** For a non-delta sample `s`, `s.weight == eval(wo, s.wi) / pdf(wo, s.wi)`
//!   and `s.pdf == pdf(wo, s.wi)`, up to rounding (the tests in `bsdf/tests/` hold every
//!   variant to this, and χ²-test every sampling routine against its `pdf`).
//! - **Failure.** `sample` returns `None` when nothing is scattered (the wrong side, a grazing
//!   `wo`, a sampled direction below the horizon, black coefficients). No method returns NaN or
//!   infinity, whatever the angles or parameters.
//! - **Transport.** Refraction compresses solid angle, so radiance crossing into a medium of
//!   relative index `η` is scaled by `1/η²`; importance is not ([`Transport`]). Only
//!   transmission depends on the mode.
//!
//! Each variant cites the Mitsuba 3 plugin it reproduces; a scene converted from Mitsuba maps
//! `int_ior/ext_ior` to `eta`, `specular_reflectance` to `specular`, `specular_transmittance`
//! to `transmittance`, `diffuse_reflectance` to `diffuse` or `albedo`, and `distribution`,
//! `alpha` (or `alpha_u`, `alpha_v`) to a [`Microfacet`].
//!
//! # Adding a variant
//! 1. Write `bsdf/name.rs`: a plain struct of the variant's parameters with `eval`, `pdf` and
//!    `sample` in the local frame, the formulas above the code, analytic tests at the bottom.
//! 2. Add the variant to [`Bsdf`] and its arm to `Bsdf::model`; the compiler lists the other
//!    `match`es to extend.
//! 3. Add it to the tables in `bsdf/tests/`: the χ² cases (`mod.rs`, if it has a non-delta
//!    lobe), and in `weights_and_energy.rs` the weight/pdf consistency list, the energy list and,
//!    if it reflects, the reciprocity list.

use glam::{Vec2, Vec3};

use crate::Rgb;

pub mod frame;
pub mod fresnel;
pub(crate) mod ggx;
pub mod microfacet;

mod classic;
mod conductor;
mod dielectric;
pub mod gltf_pbr;
mod gltf_translucent;
pub(crate) mod lambert;
pub(crate) mod plastic;
pub mod principled;
pub mod principled_thin;
pub(crate) mod rough_conductor;
pub(crate) mod rough_dielectric;
pub mod rough_plastic;
pub mod sheen;
mod thin_dielectric;
pub mod thin_film;

#[cfg(test)]
mod chi2;
#[cfg(test)]
mod tests;

pub use frame::{Frame, FrameOf};
pub use gltf_pbr::GltfPbr;
pub use microfacet::{Distribution, Microfacet};
pub use principled::Principled;
pub use principled_thin::PrincipledThin;
pub use rough_plastic::RoughCoat;
pub use sheen::{Sheen, SheenAlbedo};

use classic::Classic;
use conductor::Conductor;
use dielectric::Dielectric;
use gltf_translucent::GltfTranslucent;
use lambert::Lambert;
use plastic::Plastic;
use rough_conductor::RoughConductor;
use rough_dielectric::RoughDielectric;
use rough_plastic::RoughPlastic;
use thin_dielectric::ThinDielectric;

/// Which quantity a path carries: radiance (camera paths) or importance (light paths, for a
/// later photon mapper). Refraction scales radiance by 1/η² but not importance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transport {
    /// Radiance, traced from the camera: refraction into a denser medium concentrates it by
    /// `η²` per unit solid angle, so the transmitted value is scaled by `1/η'²` (η' the ratio
    /// of the index being entered over the index being left).
    Radiance,
    /// Importance (or light flux), traced from the lights: refraction does not scale it.
    Importance,
}

/// One direction drawn by [`Bsdf::sample`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// The sampled direction, a unit vector in the local frame, pointing away from the surface.
    pub wi: Vec3,
    /// `f(wo, wi)·|cos θi| / pdf`: the factor the path's throughput is multiplied by. For a
    /// Dirac lobe, its coefficient (and Fresnel factor) divided by the lobe's probability.
    pub weight: Rgb,
    /// Solid-angle density of having drawn `wi` (over all non-delta lobes, lobe choice
    /// included) — or, when `delta` is true, the discrete probability of the Dirac lobe chosen.
    pub pdf: f32,
    /// True when `wi` came from a Dirac lobe (mirror, smooth refraction): a light cannot be
    /// sampled towards it, so it takes no part in multiple importance sampling.
    pub delta: bool,
}

impl BsdfSample {
    /// The sample of a non-delta direction `wi` drawn from a mixture of lobes that can each
    /// produce it: weighted by the mixture's whole value `f·|cos θi|` over its whole density
    /// (one-sample MIS); `None` where the density vanishes.
    pub(crate) fn of_mixture(wi: Vec3, value: Rgb, pdf: f32) -> Option<Self> {
        (pdf > 0.0).then(|| Self {
            wi,
            weight: value * (1.0 / pdf),
            pdf,
            delta: false,
        })
    }
}

/// A surface's scattering function: one of a closed set of models, each in its own file.
///
/// Colours are per-channel coefficients in `[0, 1]` unless said otherwise; indices of
/// refraction are relative (`η_inside / η_outside`, the inside being `z < 0`); rough variants
/// take a [`Microfacet`] distribution (GGX or Beckmann, roughness `α` along the frame's `x` and
/// `y`; `α = roughness²` in the Disney convention). Variants that need tables computed when the
/// scene is built borrow them (`'a`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bsdf<'a> {
    /// Ideal diffuse reflection, `f = albedo/π` (Mitsuba `diffuse`).
    Lambert {
        /// Hemispherical reflectance.
        albedo: Rgb,
    },
    /// A smooth metal: a mirror weighted by the exact Fresnel reflectance of the complex index
    /// `η + i·k`, per channel (Mitsuba `conductor`).
    Conductor {
        /// Real part of the metal's index, relative to the outside, per channel.
        eta: Rgb,
        /// Imaginary part (extinction coefficient), per channel.
        k: Rgb,
        /// A factor on the reflection; 1 for physical realism.
        specular: Rgb,
    },
    /// A rough metal: microfacets with the conductor's Fresnel, visible-normal sampling
    /// (Mitsuba `roughconductor`, `sample_visible = true`).
    RoughConductor {
        /// Real part of the metal's index, per channel.
        eta: Rgb,
        /// Extinction coefficient, per channel.
        k: Rgb,
        /// A factor on the reflection; 1 for physical realism.
        specular: Rgb,
        /// The facets' distribution and roughness.
        microfacet: Microfacet,
    },
    /// Smooth glass: mirror reflection with probability `F`, refraction with `1 − F`, exact
    /// unpolarised Fresnel and total internal reflection (Mitsuba `dielectric`).
    Dielectric {
        /// `η_inside / η_outside`, e.g. 1.5 for glass in air.
        eta: f32,
        /// A factor on the reflection; 1 for physical realism.
        specular: Rgb,
        /// A factor on the transmission; 1 for physical realism.
        transmittance: Rgb,
    },
    /// Rough glass: microfacet reflection and refraction of Walter et al. 2007 with
    /// visible-normal sampling (Mitsuba `roughdielectric`, `sample_visible = true`).
    RoughDielectric {
        /// `η_inside / η_outside`.
        eta: f32,
        /// A factor on the reflection.
        specular: Rgb,
        /// A factor on the transmission.
        transmittance: Rgb,
        /// The facets' distribution and roughness.
        microfacet: Microfacet,
    },
    /// A thin sheet of glass: both faces reflect, the rest passes straight through, unbent
    /// (Mitsuba `thindielectric`).
    ThinDielectric {
        /// `η_sheet / η_outside`.
        eta: f32,
        /// A factor on the reflection.
        specular: Rgb,
        /// A factor on the transmission.
        transmittance: Rgb,
    },
    /// A diffuse base under a smooth dielectric coat (Mitsuba `plastic`).
    Plastic {
        /// Reflectance of the diffuse base.
        diffuse: Rgb,
        /// Index of the coat, `η_coat / η_outside`.
        eta: f32,
        /// A factor on the coat's reflection; 1 for physical realism.
        specular: Rgb,
        /// Sum the base's internal bounces (`ρ/(1 − ρ F_dr)`) instead of Mitsuba's default,
        /// colour-preserving `ρ/(1 − F_dr)`.
        nonlinear: bool,
    },
    /// A diffuse base under a rough dielectric coat, with the coat's tabulated rough
    /// transmittance (Mitsuba `roughplastic`).
    RoughPlastic {
        /// Reflectance of the diffuse base.
        diffuse: Rgb,
        /// A factor on the coat's reflection; 1 for physical realism.
        specular: Rgb,
        /// As for [`Bsdf::Plastic`].
        nonlinear: bool,
        /// The coat: index, microfacets and tables.
        coat: &'a RoughCoat,
    },
    /// The Disney principled BSDF, as Mitsuba's `principled` computes it.
    Principled(Principled),
    /// glTF 2.0's metallic-roughness BRDF (with its specular, ior and transmission layers).
    Gltf(GltfPbr),
    /// glTF's diffuse transmission (`KHR_materials_diffuse_transmission`): a Lambertian lobe
    /// through the surface of `base_color`, under the specular layer of the other parameters
    /// (see `bsdf/gltf_translucent.rs`); the same from both sides.
    GltfTranslucent(GltfPbr),
    /// A sheen layer (glTF's `KHR_materials_sheen`).
    Sheen(Sheen),
    /// The thin-sheet Disney BSDF, as Mitsuba's `principledthin` computes it.
    PrincipledThin(PrincipledThin),
    /// The Whitted material's coefficients as lobes for a path tracer: Lambert `kd`, a
    /// normalised Phong lobe `ks` of exponent `shininess`, a mirror `kr` and a refraction `kt`
    /// through index `eta` (reflecting on total internal reflection). The coefficients are used
    /// as given, without Fresnel; materials scale them to sum to at most 1 before they get here
    /// (`Material::classic_bsdf`).
    Classic {
        /// Diffuse coefficient.
        kd: Rgb,
        /// Phong coefficient: the lobe `ks·(n+2)/(2π)·cosⁿα` about the mirror direction.
        ks: Rgb,
        /// Phong exponent `n ≥ 0`.
        shininess: f32,
        /// Mirror coefficient (a Dirac lobe).
        kr: Rgb,
        /// Transmission coefficient (a Dirac lobe); non-zero makes the material two-sided.
        kt: Rgb,
        /// `η_inside / η_outside` for the refraction lobe.
        eta: f32,
    },
}

/// A variant's parameters as the type that implements it (one per file).
enum Model<'a> {
    Lambert(Lambert),
    Conductor(Conductor),
    RoughConductor(RoughConductor),
    Dielectric(Dielectric),
    RoughDielectric(RoughDielectric),
    ThinDielectric(ThinDielectric),
    Plastic(Plastic),
    RoughPlastic(RoughPlastic<'a>),
    Principled(Principled),
    PrincipledThin(PrincipledThin),
    Gltf(GltfPbr),
    GltfTranslucent(GltfTranslucent),
    Sheen(Sheen),
    Classic(Classic),
}

impl<'a> Bsdf<'a> {
    /// The implementing type of this variant, with its parameters. Inlined into each
    /// dispatch, so that the two matches fuse and only the variant at hand is built (out of
    /// line, every call built its model on the stack and copied it out).
    #[inline(always)]
    fn model(&self) -> Model<'a> {
        match *self {
            Bsdf::Lambert { albedo } => Model::Lambert(Lambert { albedo }),
            Bsdf::Conductor { eta, k, specular } => {
                Model::Conductor(Conductor { eta, k, specular })
            }
            Bsdf::RoughConductor {
                eta,
                k,
                specular,
                microfacet,
            } => Model::RoughConductor(RoughConductor::new(eta, k, specular, microfacet)),
            Bsdf::Dielectric {
                eta,
                specular,
                transmittance,
            } => Model::Dielectric(Dielectric::new(eta, specular, transmittance)),
            Bsdf::RoughDielectric {
                eta,
                specular,
                transmittance,
                microfacet,
            } => Model::RoughDielectric(RoughDielectric::new(
                eta,
                specular,
                transmittance,
                microfacet,
            )),
            Bsdf::ThinDielectric {
                eta,
                specular,
                transmittance,
            } => Model::ThinDielectric(ThinDielectric::new(eta, specular, transmittance)),
            Bsdf::Plastic {
                diffuse,
                eta,
                specular,
                nonlinear,
            } => Model::Plastic(Plastic::new(diffuse, eta, specular, nonlinear)),
            Bsdf::RoughPlastic {
                diffuse,
                specular,
                nonlinear,
                coat,
            } => Model::RoughPlastic(RoughPlastic::new(diffuse, specular, nonlinear, coat)),
            Bsdf::Principled(p) => Model::Principled(p),
            Bsdf::PrincipledThin(p) => Model::PrincipledThin(p),
            Bsdf::Gltf(p) => Model::Gltf(p),
            Bsdf::GltfTranslucent(p) => Model::GltfTranslucent(GltfTranslucent(p)),
            Bsdf::Sheen(p) => Model::Sheen(p),
            Bsdf::Classic {
                kd,
                ks,
                shininess,
                kr,
                kt,
                eta,
            } => Model::Classic(Classic::new(kd, ks, shininess, kr, kt, eta)),
        }
    }

    /// `f(wo, wi)·|cos θi|` — the BSDF times the cosine of `wi` (cosine INCLUDED) — summed over
    /// the non-delta lobes; zero for Dirac lobes and on the wrong side of a one-sided BSDF.
    /// Both directions are unit vectors in the local frame pointing away from the surface.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: Transport) -> Rgb {
        let f = match self.model() {
            Model::Lambert(b) => b.eval(wo, wi),
            Model::Conductor(_) | Model::Dielectric(_) | Model::ThinDielectric(_) => Rgb::BLACK,
            Model::RoughConductor(b) => b.eval(wo, wi),
            Model::RoughDielectric(b) => b.eval(wo, wi, mode),
            Model::Plastic(b) => b.eval(wo, wi),
            Model::RoughPlastic(b) => b.eval(wo, wi),
            Model::Principled(b) => b.eval(wo, wi, mode),
            Model::PrincipledThin(b) => b.eval(wo, wi),
            Model::Gltf(b) => b.eval(wo, wi, mode),
            Model::GltfTranslucent(b) => b.eval(wo, wi),
            Model::Sheen(b) => b.eval(wo, wi),
            Model::Classic(b) => b.eval(wo, wi),
        };
        debug_assert!(f.is_finite(), "{self:?}.eval({wo}, {wi}) = {f:?}");
        // The variants guard their divisions; this keeps a missed corner from poisoning an image.
        if f.is_finite() { f } else { Rgb::BLACK }
    }

    /// Solid-angle density with which `sample` picks wi (over its non-delta lobes, including
    /// lobe-selection probabilities); 0 for delta-only BSDFs, and 0 where `eval` is zero
    /// because of sides.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let p = match self.model() {
            Model::Lambert(b) => b.pdf(wo, wi),
            Model::Conductor(_) | Model::Dielectric(_) | Model::ThinDielectric(_) => 0.0,
            Model::RoughConductor(b) => b.pdf(wo, wi),
            Model::RoughDielectric(b) => b.pdf(wo, wi),
            Model::Plastic(b) => b.pdf(wo, wi),
            Model::RoughPlastic(b) => b.pdf(wo, wi),
            Model::Principled(b) => b.pdf(wo, wi),
            Model::PrincipledThin(b) => b.pdf(wo, wi),
            Model::Gltf(b) => b.pdf(wo, wi),
            Model::GltfTranslucent(b) => b.pdf(wo, wi),
            Model::Sheen(b) => b.pdf(wo, wi),
            Model::Classic(b) => b.pdf(wo, wi),
        };
        debug_assert!(p.is_finite() && p >= 0.0, "{self:?}.pdf({wo}, {wi}) = {p}");
        if p.is_finite() && p > 0.0 { p } else { 0.0 }
    }

    /// Draw wi given two uniform inputs in [0,1): `u_lobe` picks a lobe (and is free to reuse),
    /// `u` the direction. None when nothing is scattered.
    ///
    /// The same inputs always give the same sample (no hidden randomness).
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: Transport) -> Option<BsdfSample> {
        let s = match self.model() {
            Model::Lambert(b) => b.sample(wo, u),
            Model::Conductor(b) => b.sample(wo),
            Model::RoughConductor(b) => b.sample(wo, u),
            Model::Dielectric(b) => b.sample(wo, u_lobe, mode),
            Model::RoughDielectric(b) => b.sample(wo, u_lobe, u, mode),
            Model::ThinDielectric(b) => b.sample(wo, u_lobe),
            Model::Plastic(b) => b.sample(wo, u_lobe, u),
            Model::RoughPlastic(b) => b.sample(wo, u_lobe, u),
            Model::Principled(b) => b.sample(wo, u_lobe, u, mode),
            Model::PrincipledThin(b) => b.sample(wo, u_lobe, u),
            Model::Gltf(b) => b.sample(wo, u_lobe, u, mode),
            Model::GltfTranslucent(b) => b.sample(wo, u),
            Model::Sheen(b) => b.sample(wo, u),
            Model::Classic(b) => b.sample(wo, u_lobe, u, mode),
        }?;
        debug_assert!(
            s.weight.is_finite() && s.pdf.is_finite() && s.wi.is_finite(),
            "{self:?}.sample({wo}, {u_lobe}, {u}) = {s:?}"
        );
        // A sample that carries nothing ends the path just as `None` does; say so in one place.
        let useful = s.pdf > 0.0
            && s.pdf.is_finite()
            && s.weight.is_finite()
            && !s.weight.is_black()
            && s.wi.is_finite();
        useful.then_some(s)
    }

    /// True when every lobe is a Dirac delta (light sampling is useless there).
    pub fn is_delta(&self) -> bool {
        match self.model() {
            Model::Lambert(_)
            | Model::RoughConductor(_)
            | Model::RoughPlastic(_)
            | Model::Principled(_)
            | Model::PrincipledThin(_)
            | Model::Gltf(_)
            | Model::GltfTranslucent(_)
            | Model::Sheen(_) => false,
            Model::Conductor(_) | Model::Dielectric(_) | Model::ThinDielectric(_) => true,
            Model::RoughDielectric(b) => b.is_delta(),
            Model::Plastic(b) => b.is_delta(),
            Model::Classic(b) => b.is_delta(),
        }
    }

    /// The probability that [`Bsdf::sample`] from `wo` picks a Dirac lobe: 1 for mirrors and
    /// smooth glass, 0 for BSDFs without one, between for mixtures (a smooth plastic's coat,
    /// a Whitted material's `kr` and `kt` beside its `kd`).
    pub fn delta_share(&self, wo: Vec3) -> f32 {
        match self.model() {
            Model::Lambert(_)
            | Model::RoughConductor(_)
            | Model::RoughPlastic(_)
            | Model::Principled(_)
            | Model::PrincipledThin(_)
            | Model::Gltf(_)
            | Model::GltfTranslucent(_)
            | Model::Sheen(_) => 0.0,
            Model::Conductor(_) | Model::Dielectric(_) | Model::ThinDielectric(_) => 1.0,
            Model::RoughDielectric(b) => f32::from(u8::from(b.is_delta())),
            Model::Plastic(b) => b.delta_share(wo),
            Model::Classic(b) => {
                if b.is_delta() {
                    1.0
                } else {
                    b.delta_share()
                }
            }
        }
    }

    /// True when it can transmit (light can arrive from the other side).
    pub fn transmits(&self) -> bool {
        match self {
            Bsdf::Dielectric { .. }
            | Bsdf::RoughDielectric { .. }
            | Bsdf::ThinDielectric { .. } => true,
            Bsdf::Classic { kt, .. } => !kt.is_black(),
            // The principled BSDF's inside is seen only through its transmission; the thin one
            // is the same from both sides by itself.
            Bsdf::Principled(p) => p.spec_trans > 0.0 && p.metallic < 1.0,
            Bsdf::PrincipledThin(_) | Bsdf::GltfTranslucent(_) => true,
            Bsdf::Gltf(p) => p.transmits(),
            _ => false,
        }
    }
}

/// The mirror image of `w` about the local normal `z`: `(−x, −y, z)`, the same as
/// `optics::reflect(−w, Z)`.
#[inline]
fn mirror(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}
