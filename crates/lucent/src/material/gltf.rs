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
    /// `anisotropyTexture`'s direction, if any: its red and green channels (linear, in
    /// `[0, 1]`) map to a vector `2·(r, g) − 1` in the tangent frame, turned by
    /// `anisotropy_rotation`.
    pub anisotropy_direction: Option<Texture>,
    /// `KHR_materials_diffuse_transmission`: the share of the diffuse light that passes
    /// through the surface (0: none).
    pub diffuse_transmission: Texture,
    /// The colour of the light diffusely transmitted.
    pub diffuse_transmission_color: Texture,
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
            anisotropy_direction: None,
            diffuse_transmission: Texture::from(0.0),
            diffuse_transmission_color: Texture::from(1.0),
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
    /// The diffuse transmission's share of the base (`(1 − metallic)(1 − transmission)` times
    /// its factor) and its BSDF (`Bsdf::GltfTranslucent`), if any.
    pub translucent: Option<(f32, GltfPbr)>,
    /// The anisotropy's direction, radians from the tangent towards the bitangent.
    pub rotation: f32,
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
            &self.diffuse_transmission,
            &self.diffuse_transmission_color,
        ];
        if let Some((t, _)) = &self.clearcoat_normals {
            v.push(t);
        }
        if let Some(t) = &self.anisotropy_direction {
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
        let mut base = GltfPbr {
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
            diffuse_transmission: 0,
        };
        let dt = n(&self.diffuse_transmission);
        let translucent = (dt > 0.0).then(|| {
            // The share in 255ths, as the base keeps it, so that the two add up exactly.
            let q = (dt * 255.0).round().max(1.0) as u8;
            base.diffuse_transmission = q;
            let share = (1.0 - base.metallic) * (1.0 - base.transmission) * f32::from(q) / 255.0;
            let color = self.diffuse_transmission_color.eval(at, images);
            (
                share,
                GltfPbr {
                    base_color: color.clamp(0.0, 1.0),
                    ..base
                },
            )
        });
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
        let rotation = match &self.anisotropy_direction {
            Some(t) if strength > 0.0 => {
                let c = t.eval(at, images);
                let (x, y) = (2.0 * c.r - 1.0, 2.0 * c.g - 1.0);
                // A texel of no direction (its centre) leaves the tangent's.
                let turn = if x * x + y * y > 1e-8 {
                    y.atan2(x)
                } else {
                    0.0
                };
                self.anisotropy_rotation + turn
            }
            _ => self.anisotropy_rotation,
        };
        GltfLayers {
            base,
            sheen,
            clearcoat,
            translucent,
            rotation,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use std::f32::consts::FRAC_PI_2;

    fn layers(maps: &GltfMaps) -> GltfLayers {
        maps.at(&TexCoords::at(Vec3::ZERO, Vec2::ZERO), &[], Rgb::WHITE)
    }

    #[test]
    fn the_direction_map_turns_the_anisotropy() {
        let turned = |direction: Rgb| GltfMaps {
            anisotropy: Texture::from(0.5),
            anisotropy_rotation: 0.3,
            anisotropy_direction: Some(Texture::Solid(direction)),
            ..GltfMaps::default()
        };
        // (r, g) = (0.5, 1) is the bitangent: a quarter turn more than the rotation.
        let r = layers(&turned(Rgb::new(0.5, 1.0, 0.0))).rotation;
        assert!((r - (0.3 + FRAC_PI_2)).abs() < 1e-5, "{r}");
        // (1, 0.5) is the tangent, and the map's centre no direction: the rotation alone.
        assert!((layers(&turned(Rgb::new(1.0, 0.5, 0.0))).rotation - 0.3).abs() < 1e-6);
        assert_eq!(layers(&turned(Rgb::new(0.5, 0.5, 0.5))).rotation, 0.3);
        // Without anisotropy the map is not looked at.
        let flat = GltfMaps {
            anisotropy: Texture::from(0.0),
            ..turned(Rgb::new(0.5, 1.0, 0.0))
        };
        assert_eq!(layers(&flat).rotation, 0.3);
    }

    #[test]
    fn diffuse_transmission_takes_its_share_from_the_base() {
        let maps = GltfMaps {
            base_color: Texture::Solid(Rgb::new(0.2, 0.8, 0.2)),
            metallic: Texture::from(0.25),
            transmission: Texture::from(0.5),
            diffuse_transmission: Texture::from(0.6),
            diffuse_transmission_color: Texture::Solid(Rgb::new(1.0, 0.5, 0.0)),
            ..GltfMaps::default()
        };
        let l = layers(&maps);
        let (share, translucent) = l.translucent.expect("a translucent part");
        let q = l.base.diffuse_transmission;
        assert_eq!(q, 153, "0.6 in 255ths");
        assert!((share - 0.75 * 0.5 * 153.0 / 255.0).abs() < 1e-6, "{share}");
        assert_eq!(translucent.base_color, Rgb::new(1.0, 0.5, 0.0));
        assert_eq!(translucent.diffuse_transmission, q);
        // None without the extension.
        assert!(layers(&GltfMaps::default()).translucent.is_none());
    }
}
