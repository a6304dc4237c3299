//! The textured parameters of the principled BSDFs ([`crate::bsdf::Principled`],
//! [`crate::bsdf::PrincipledThin`]), evaluated at a hit.

use crate::bsdf::{Principled, PrincipledThin};
use crate::texture::{ImageTexture, TexCoords, Texture};

/// The principled BSDF's parameters as textures (Mitsuba's `principled`; every one may be
/// textured but `eta`).
#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledMaps {
    /// The base colour.
    pub base_color: Texture,
    /// Perceptual roughness.
    pub roughness: Texture,
    /// Anisotropy.
    pub anisotropic: Texture,
    /// Metalness.
    pub metallic: Texture,
    /// Specular transmission.
    pub spec_trans: Texture,
    /// Specular tint.
    pub spec_tint: Texture,
    /// Sheen.
    pub sheen: Texture,
    /// Sheen tint.
    pub sheen_tint: Texture,
    /// Flatness (fake subsurface).
    pub flatness: Texture,
    /// Clearcoat.
    pub clearcoat: Texture,
    /// Clearcoat gloss.
    pub clearcoat_gloss: Texture,
    /// Index of refraction.
    pub eta: f32,
}

impl Default for PrincipledMaps {
    fn default() -> Self {
        let d = Principled::default();
        Self {
            base_color: Texture::Solid(d.base_color),
            roughness: Texture::from(d.roughness),
            anisotropic: Texture::from(0.0),
            metallic: Texture::from(0.0),
            spec_trans: Texture::from(0.0),
            spec_tint: Texture::from(0.0),
            sheen: Texture::from(0.0),
            sheen_tint: Texture::from(0.0),
            flatness: Texture::from(0.0),
            clearcoat: Texture::from(0.0),
            clearcoat_gloss: Texture::from(0.0),
            eta: d.eta,
        }
    }
}

impl PrincipledMaps {
    /// Every texture, for visiting.
    pub fn textures(&self) -> [&Texture; 11] {
        [
            &self.base_color,
            &self.roughness,
            &self.anisotropic,
            &self.metallic,
            &self.spec_trans,
            &self.spec_tint,
            &self.sheen,
            &self.sheen_tint,
            &self.flatness,
            &self.clearcoat,
            &self.clearcoat_gloss,
        ]
    }

    /// The parameters at `at`.
    pub fn at(&self, at: &TexCoords, images: &[ImageTexture]) -> Principled {
        let n = |t: &Texture| t.eval_float(at, images).clamp(0.0, 1.0);
        Principled {
            base_color: self.base_color.eval(at, images),
            roughness: n(&self.roughness),
            anisotropic: n(&self.anisotropic),
            metallic: n(&self.metallic),
            spec_trans: n(&self.spec_trans),
            spec_tint: n(&self.spec_tint),
            sheen: n(&self.sheen),
            sheen_tint: n(&self.sheen_tint),
            flatness: n(&self.flatness),
            clearcoat: n(&self.clearcoat),
            clearcoat_gloss: n(&self.clearcoat_gloss),
            eta: self.eta,
        }
    }
}

/// The thin principled BSDF's parameters as textures (Mitsuba's `principledthin`).
#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledThinMaps {
    /// The base colour.
    pub base_color: Texture,
    /// Perceptual roughness.
    pub roughness: Texture,
    /// Anisotropy.
    pub anisotropic: Texture,
    /// Specular transmission.
    pub spec_trans: Texture,
    /// Diffuse transmission, 0 to 2.
    pub diff_trans: Texture,
    /// Specular tint.
    pub spec_tint: Texture,
    /// Sheen.
    pub sheen: Texture,
    /// Sheen tint.
    pub sheen_tint: Texture,
    /// Flatness.
    pub flatness: Texture,
    /// The sheet's index of refraction.
    pub eta: Texture,
}

impl Default for PrincipledThinMaps {
    fn default() -> Self {
        let d = PrincipledThin::default();
        Self {
            base_color: Texture::Solid(d.base_color),
            roughness: Texture::from(d.roughness),
            anisotropic: Texture::from(0.0),
            spec_trans: Texture::from(0.0),
            diff_trans: Texture::from(0.0),
            spec_tint: Texture::from(0.0),
            sheen: Texture::from(0.0),
            sheen_tint: Texture::from(0.0),
            flatness: Texture::from(0.0),
            eta: Texture::from(d.eta),
        }
    }
}

impl PrincipledThinMaps {
    /// Every texture, for visiting.
    pub fn textures(&self) -> [&Texture; 10] {
        [
            &self.base_color,
            &self.roughness,
            &self.anisotropic,
            &self.spec_trans,
            &self.diff_trans,
            &self.spec_tint,
            &self.sheen,
            &self.sheen_tint,
            &self.flatness,
            &self.eta,
        ]
    }

    /// The parameters at `at`.
    pub fn at(&self, at: &TexCoords, images: &[ImageTexture]) -> PrincipledThin {
        let n = |t: &Texture| t.eval_float(at, images).clamp(0.0, 1.0);
        PrincipledThin {
            base_color: self.base_color.eval(at, images),
            roughness: n(&self.roughness),
            anisotropic: n(&self.anisotropic),
            spec_trans: n(&self.spec_trans),
            diff_trans: self.diff_trans.eval_float(at, images).clamp(0.0, 2.0),
            spec_tint: n(&self.spec_tint),
            sheen: n(&self.sheen),
            sheen_tint: n(&self.sheen_tint),
            flatness: n(&self.flatness),
            eta: self.eta.eval_float(at, images),
        }
    }
}
