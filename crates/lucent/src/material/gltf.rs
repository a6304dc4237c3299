//! glTF 2.0's material as lucent holds it: the metallic-roughness parameters and the layers of
//! its `KHR_materials_*` extensions, each a texture (factor times texture, as the reader makes
//! them), evaluated at a hit into up to three parts of a [`super::Scattering`]:
//!
//! - the base, [`GltfPbr`] (metallic-roughness with `specular`, `ior`, `transmission`,
//!   `anisotropy`, and the thin film of `iridescence` in its Fresnel terms);
//! - the sheen ([`Sheen`]) on top of it, the base keeping `1 − max(sheen)·E(μ)`;
//! - the clearcoat on top of both, a GGX mirror of roughness `clearcoat_roughness²` in the
//!   coat's own normal, weighted by `clearcoat·F(μ)` (Schlick, f0 0.04), the layers below
//!   keeping the rest: the specification's `fresnel_coat`, its Fresnel taken at the viewer's
//!   angle to the coat's normal.

use std::sync::Arc;

use glam::Vec2;

use crate::Rgb;
use crate::bsdf::{GltfPbr, Microfacet, Sheen, SheenAlbedo};
use crate::texture::{ImageTexture, TexCoords, Texture};

/// glTF's material parameters as textures.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfMaps {
    /// `baseColorFactor` times `baseColorTexture`.
    pub base_color: Texture,
    /// `metallicFactor` times the blue channel of `metallicRoughnessTexture`.
    pub metallic: Texture,
    /// `roughnessFactor` times its green channel (perceptual: `α = roughness²`).
    pub roughness: Texture,
    /// `KHR_materials_ior` (default 1.5).
    pub ior: f32,
    /// `KHR_materials_specular`: the factor (times the texture's alpha).
    pub specular: Texture,
    /// `KHR_materials_specular`: the colour.
    pub specular_color: Texture,
    /// `KHR_materials_transmission`.
    pub transmission: Texture,
    /// Whether transmitted light refracts (`KHR_materials_volume` with a thickness).
    pub volume: bool,
    /// `KHR_materials_clearcoat`: its weight.
    pub clearcoat: Texture,
    /// Its perceptual roughness.
    pub clearcoat_roughness: Texture,
    /// Its own normal map and scale, if any.
    pub clearcoat_normals: Option<(Texture, f32)>,
    /// `KHR_materials_sheen`: the colour (black: no sheen).
    pub sheen_color: Texture,
    /// Its perceptual roughness.
    pub sheen_roughness: Texture,
    /// The sheen's albedo table, present when there is sheen.
    pub sheen_albedo: Option<Arc<SheenAlbedo>>,
    /// `KHR_materials_anisotropy`: its strength.
    pub anisotropy: Texture,
    /// Its direction, radians from the tangent towards the bitangent.
    pub anisotropy_rotation: f32,
    /// `KHR_materials_iridescence`: the thin film's weight (`iridescenceFactor` times the red
    /// channel of `iridescenceTexture`; 0: no film).
    pub iridescence: Texture,
    /// The film's index of refraction (`iridescenceIor`, default 1.3).
    pub iridescence_ior: f32,
    /// The film's thickness in nanometres: `iridescenceThicknessMaximum` (default 400), or its
    /// mix with the minimum by the green channel of `iridescenceThicknessTexture`.
    pub iridescence_thickness: Texture,
}

impl Default for GltfMaps {
    /// glTF's defaults: white base, metallic 1, roughness 1, ior 1.5, no layers.
    fn default() -> Self {
        Self {
            base_color: Texture::from(1.0),
            metallic: Texture::from(1.0),
            roughness: Texture::from(1.0),
            ior: 1.5,
            specular: Texture::from(1.0),
            specular_color: Texture::from(1.0),
            transmission: Texture::from(0.0),
            volume: false,
            clearcoat: Texture::from(0.0),
            clearcoat_roughness: Texture::from(0.0),
            clearcoat_normals: None,
            sheen_color: Texture::from(0.0),
            sheen_roughness: Texture::from(0.0),
            sheen_albedo: None,
            anisotropy: Texture::from(0.0),
            anisotropy_rotation: 0.0,
            iridescence: Texture::from(0.0),
            iridescence_ior: 1.3,
            iridescence_thickness: Texture::from(400.0),
        }
    }
}

/// The layers at a hit.
pub(super) struct GltfLayers {
    /// The base BRDF.
    pub base: GltfPbr,
    /// The sheen, if any, with its albedo at the viewer's angle still to be looked up.
    pub sheen: Option<Sheen>,
    /// The clearcoat's weight and microfacets.
    pub clearcoat: Option<(f32, Microfacet)>,
}

impl GltfMaps {
    /// Every texture, for visiting.
    pub fn textures(&self) -> Vec<&Texture> {
        let mut v = vec![
            &self.base_color,
            &self.metallic,
            &self.roughness,
            &self.specular,
            &self.specular_color,
            &self.transmission,
            &self.clearcoat,
            &self.clearcoat_roughness,
            &self.sheen_color,
            &self.sheen_roughness,
            &self.anisotropy,
            &self.iridescence,
            &self.iridescence_thickness,
        ];
        if let Some((t, _)) = &self.clearcoat_normals {
            v.push(t);
        }
        v
    }

    /// The layers at `at`; `color` multiplies the base colour (vertex colours).
    pub(super) fn at(&self, at: &TexCoords, images: &[ImageTexture], color: Rgb) -> GltfLayers {
        let n = |t: &Texture| t.eval_float(at, images).clamp(0.0, 1.0);
        let roughness = n(&self.roughness);
        let alpha = roughness * roughness;
        let strength = n(&self.anisotropy);
        let alpha_t = alpha + (1.0 - alpha) * strength * strength;
        let iridescence = n(&self.iridescence);
        // Whole nanometres (see `GltfPbr::film_thickness`); not looked up without a film.
        let film_thickness = if iridescence > 0.0 {
            let d = self.iridescence_thickness.eval_float(at, images);
            d.clamp(0.0, f32::from(u16::MAX)).round() as u16
        } else {
            0
        };
        let base = GltfPbr {
            base_color: self.base_color.eval(at, images) * color,
            metallic: n(&self.metallic),
            alpha: Vec2::new(alpha_t, alpha),
            ior: self.ior,
            specular: n(&self.specular),
            specular_color: self.specular_color.eval(at, images),
            transmission: n(&self.transmission),
            iridescence,
            film_ior: self.iridescence_ior,
            film_thickness,
            volume: self.volume,
        };
        let sheen_color = self.sheen_color.eval(at, images);
        let sheen = (!sheen_color.is_black()).then(|| Sheen {
            color: sheen_color,
            roughness: n(&self.sheen_roughness),
        });
        let cc = n(&self.clearcoat);
        let clearcoat = (cc > 0.0).then(|| {
            let r = n(&self.clearcoat_roughness);
            (cc, Microfacet::ggx(r * r))
        });
        GltfLayers {
            base,
            sheen,
            clearcoat,
        }
    }
}
