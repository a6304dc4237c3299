//! `[[material]]` tables.

use super::{Finite, TextureDesc};
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// The kinds of material. `whitted` takes the classic coefficients; the others are
/// physically based descriptions (the names and parameters of Mitsuba 3's BSDFs), which the
/// Whitted integrator renders with the nearest classic coefficients (`docs/scene-format.md`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialKind {
    /// `ka`, `kd`, `ks`, `shininess`, `kr`, `kt`, `ior`.
    #[default]
    Whitted,
    /// Lambertian: `reflectance`.
    Diffuse,
    /// A smooth metal: `eta` and `k`, or `metal`; `specular`.
    Conductor,
    /// A rough metal: as `conductor`, plus `roughness` (or `roughness_u`, `roughness_v`) and
    /// `distribution`.
    RoughConductor,
    /// Smooth glass: `ior`, `ext_ior`, `specular`, `transmittance`.
    Dielectric,
    /// Rough glass: as `dielectric`, plus the roughness keys.
    RoughDielectric,
    /// A thin sheet of glass: `ior`, `ext_ior`, `specular`, `transmittance`.
    ThinDielectric,
    /// A diffuse base under a dielectric coat: `reflectance`, `ior`, `ext_ior`, `specular`,
    /// `nonlinear`; with `roughness` (and `distribution`) the coat is rough.
    Plastic,
    /// `plastic` with a rough coat (`roughness` defaults to 0.1).
    RoughPlastic,
    /// Two other materials' surfaces blended: `materials = ["a", "b"]`, `weight` (of `b`).
    Blend,
    /// The Disney principled BSDF (Mitsuba's `principled`): `base_color`, `roughness`,
    /// `anisotropic`, `metallic`, `spec_trans`, `spec_tint`, `sheen`, `sheen_tint`,
    /// `flatness`, `clearcoat`, `clearcoat_gloss`, and `ior` or `specular` (a number).
    Principled,
    /// The thin-sheet Disney BSDF (Mitsuba's `principledthin`): `base_color`, `roughness`,
    /// `anisotropic`, `spec_trans`, `diff_trans`, `spec_tint`, `sheen`, `sheen_tint`,
    /// `flatness`, `ior`.
    PrincipledThin,
    /// glTF 2.0's metallic-roughness material: `base_color`, `metallic`, `roughness`, `ior`,
    /// `specular`, `specular_color`, `transmission`, `volume`, `clearcoat`,
    /// `clearcoat_roughness`, `clearcoat_normal_map`, `clearcoat_normal_scale`, `sheen_color`,
    /// `sheen_roughness`, `anisotropy`, `anisotropy_rotation`, `anisotropy_direction`,
    /// `iridescence`, `iridescence_ior`, `iridescence_thickness`, `diffuse_transmission`,
    /// `diffuse_transmission_color`.
    Pbr,
    /// Nothing at all: rays cross it unchanged (the boundary of a medium of the same index as
    /// its surroundings; Mitsuba's `null`). The same as `opacity = 0`.
    Null,
}

impl MaterialKind {
    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            MaterialKind::Whitted => "whitted",
            MaterialKind::Diffuse => "diffuse",
            MaterialKind::Conductor => "conductor",
            MaterialKind::RoughConductor => "roughconductor",
            MaterialKind::Dielectric => "dielectric",
            MaterialKind::RoughDielectric => "roughdielectric",
            MaterialKind::ThinDielectric => "thindielectric",
            MaterialKind::Plastic => "plastic",
            MaterialKind::RoughPlastic => "roughplastic",
            MaterialKind::Blend => "blend",
            MaterialKind::Principled => "principled",
            MaterialKind::PrincipledThin => "principledthin",
            MaterialKind::Pbr => "pbr",
            MaterialKind::Null => "null",
        }
    }

    /// Whether the kind has microfacets (takes the roughness keys).
    pub fn is_rough(self) -> bool {
        matches!(
            self,
            MaterialKind::RoughConductor
                | MaterialKind::RoughDielectric
                | MaterialKind::RoughPlastic
        )
    }
}

/// One `[[material]]`; which keys apply depends on `type` (default `"whitted"`); the others
/// are refused in build. A missing coefficient is 0, a missing `ior` is 1 (`whitted`) or 1.5.
/// Every colour or number of the physically based kinds may be a texture
/// ([`TextureDesc`]).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    /// The name objects refer to it by; unique.
    pub name: Spanned<String>,
    /// The kind of material (default `whitted`).
    #[serde(default, rename = "type", skip_serializing_if = "Option::is_none")]
    pub kind: Option<Spanned<MaterialKind>>,
    /// Ambient coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ka: Option<super::Color>,
    /// A texture multiplying `ka` (POV-Ray's ambient follows the pigment).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ka_map: Option<TextureDesc>,
    /// A bump pattern bending the normal (POV-Ray's `normal`; no TOML form yet).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bump: Option<BumpDesc>,
    /// Diffuse coefficient: a colour or a texture.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kd: Option<TextureDesc>,
    /// Specular coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ks: Option<super::Color>,
    /// Phong exponent, ≥ 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shininess: Option<Spanned<Finite>>,
    /// The highlight: `"phong"` (default) or `"blinn"` (POV-Ray's `specular`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub highlight: Option<Spanned<String>>,
    /// The exponent of `N·L` in the diffuse term (POV-Ray's `brilliance`; default 1), > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brilliance: Option<Spanned<Finite>>,
    /// Mirror reflection coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kr: Option<super::Color>,
    /// Transmission coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kt: Option<super::Color>,
    /// Index of refraction of the inside, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ior: Option<Spanned<Finite>>,
    /// Index of refraction of the outside, > 0 (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ext_ior: Option<Spanned<Finite>>,
    /// Diffuse albedo (`diffuse`, `plastic`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reflectance: Option<TextureDesc>,
    /// Tint of the specular reflection (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub specular: Option<TextureDesc>,
    /// Tint of the specular transmission (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmittance: Option<TextureDesc>,
    /// A conductor's index of refraction per channel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eta: Option<TextureDesc>,
    /// A conductor's extinction coefficient per channel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k: Option<TextureDesc>,
    /// A conductor by name (`"Au"`, `"Ag"`, `"Cu"`, `"Al"`, … the names Mitsuba knows),
    /// instead of `eta` and `k`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metal: Option<Spanned<String>>,
    /// Microfacet roughness `α` of the rough kinds, isotropic, in (0, 1].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<Spanned<TextureDesc>>,
    /// Anisotropic roughness along the surface's tangent (`∂p/∂u`), with `roughness_v`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness_u: Option<Spanned<TextureDesc>>,
    /// Anisotropic roughness along the bitangent, with `roughness_u`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness_v: Option<Spanned<TextureDesc>>,
    /// The microfacet distribution: `"ggx"` (the default) or `"beckmann"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distribution: Option<Spanned<String>>,
    /// A plastic's base sums its internal bounces (darker, more saturated; Mitsuba's
    /// `nonlinear`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nonlinear: Option<bool>,
    /// Radiance emitted by the surface: an area light on every object of this material (a
    /// texture makes it glow where the texture says, found by the rays that hit it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission: Option<TextureDesc>,
    /// Coverage in `[0, 1]`: where below 1 the surface is cut away (alpha).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opacity: Option<Spanned<TextureDesc>>,
    /// A tangent-space normal map (an image, linear by default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_map: Option<Spanned<TextureDesc>>,
    /// Multiplies the normal map's x and y (glTF's `scale`; default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_scale: Option<Spanned<Finite>>,
    /// A height texture whose gradient bends the shading normal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bump_map: Option<Spanned<TextureDesc>>,
    /// Multiplies the height (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bump_scale: Option<Spanned<Finite>>,
    /// `blend`: the two materials blended (their surfaces; this material's own keys stay).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub materials: Option<Spanned<Vec<String>>>,
    /// `blend`: the share of the second material, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weight: Option<Spanned<TextureDesc>>,
    /// The base colour (`principled`, `principledthin`, `pbr`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_color: Option<TextureDesc>,
    /// Metalness in `[0, 1]` (`principled`, `pbr`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metallic: Option<Spanned<TextureDesc>>,
    /// Anisotropy of the Disney specular lobes, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anisotropic: Option<Spanned<TextureDesc>>,
    /// Disney's specular transmission, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spec_trans: Option<Spanned<TextureDesc>>,
    /// Disney's specular tint, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spec_tint: Option<Spanned<TextureDesc>>,
    /// Disney's sheen, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sheen: Option<Spanned<TextureDesc>>,
    /// Disney's sheen tint, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sheen_tint: Option<Spanned<TextureDesc>>,
    /// Disney's flatness (fake subsurface), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flatness: Option<Spanned<TextureDesc>>,
    /// The clearcoat's weight (`principled`, `pbr`), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearcoat: Option<Spanned<TextureDesc>>,
    /// Disney's clearcoat gloss, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearcoat_gloss: Option<Spanned<TextureDesc>>,
    /// Disney's diffuse transmission of a thin sheet, in `[0, 2]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diff_trans: Option<Spanned<TextureDesc>>,
    /// glTF's specular colour (`KHR_materials_specular`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub specular_color: Option<TextureDesc>,
    /// glTF's transmission (`KHR_materials_transmission`), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmission: Option<Spanned<TextureDesc>>,
    /// glTF: the transmitted light refracts (a volume, `KHR_materials_volume`) rather than
    /// passing a thin wall unbent (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub volume: Option<bool>,
    /// glTF's clearcoat roughness (perceptual), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearcoat_roughness: Option<Spanned<TextureDesc>>,
    /// glTF's clearcoat normal map.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearcoat_normal_map: Option<Spanned<TextureDesc>>,
    /// The strength of `clearcoat_normal_map` (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearcoat_normal_scale: Option<Spanned<Finite>>,
    /// glTF's sheen colour (`KHR_materials_sheen`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sheen_color: Option<TextureDesc>,
    /// glTF's sheen roughness (perceptual), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sheen_roughness: Option<Spanned<TextureDesc>>,
    /// glTF's anisotropy strength (`KHR_materials_anisotropy`), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anisotropy: Option<Spanned<TextureDesc>>,
    /// glTF's anisotropy direction, degrees from the tangent towards the bitangent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anisotropy_rotation: Option<Spanned<Finite>>,
    /// glTF's anisotropy direction map: red and green (linear) give the direction
    /// `2·(r, g) − 1` in the tangent frame, turned by `anisotropy_rotation`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anisotropy_direction: Option<Spanned<TextureDesc>>,
    /// glTF's diffuse transmission (`KHR_materials_diffuse_transmission`), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse_transmission: Option<Spanned<TextureDesc>>,
    /// The colour of the diffusely transmitted light (default white).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse_transmission_color: Option<TextureDesc>,
    /// glTF's thin-film weight (`KHR_materials_iridescence`), in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iridescence: Option<Spanned<TextureDesc>>,
    /// The thin film's index of refraction (default 1.3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iridescence_ior: Option<Spanned<Finite>>,
    /// The thin film's thickness in nanometres, in `[0, 65535]` (default 400).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iridescence_thickness: Option<Spanned<TextureDesc>>,
    /// Whether the back side scatters light like the front (default true; Mitsuba's BSDFs
    /// are one-sided unless wrapped in `twosided`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub two_sided: Option<bool>,
    /// The material whose surface the back side wears (Mitsuba's `twosided` with two BSDFs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub back: Option<Spanned<String>>,
    /// Whether mesh vertex colours multiply the diffuse colour (default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vertex_colors: Option<bool>,
    /// Whether the back side is not there at all: rays meeting it from behind pass through
    /// (default false; glTF's single-sided materials).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cull_back: Option<bool>,
    /// Whether the `emission` leaves the back as well as the front (default false; glTF's
    /// unlit two-sided materials). Such a surface is not sampled as a light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emits_back: Option<bool>,
}

impl MaterialDesc {
    /// A `whitted` material with only a name, every coefficient missing.
    pub fn named(name: &str) -> Self {
        Self {
            name: Spanned::new(0..0, name.to_string()),
            kind: None,
            ka: None,
            ka_map: None,
            bump: None,
            kd: None,
            ks: None,
            shininess: None,
            highlight: None,
            brilliance: None,
            kr: None,
            kt: None,
            ior: None,
            ext_ior: None,
            reflectance: None,
            specular: None,
            transmittance: None,
            eta: None,
            k: None,
            metal: None,
            roughness: None,
            roughness_u: None,
            roughness_v: None,
            distribution: None,
            nonlinear: None,
            emission: None,
            opacity: None,
            normal_map: None,
            normal_scale: None,
            bump_map: None,
            bump_scale: None,
            materials: None,
            weight: None,
            base_color: None,
            metallic: None,
            anisotropic: None,
            spec_trans: None,
            spec_tint: None,
            sheen: None,
            sheen_tint: None,
            flatness: None,
            clearcoat: None,
            clearcoat_gloss: None,
            diff_trans: None,
            specular_color: None,
            transmission: None,
            volume: None,
            clearcoat_roughness: None,
            clearcoat_normal_map: None,
            clearcoat_normal_scale: None,
            sheen_color: None,
            sheen_roughness: None,
            anisotropy: None,
            anisotropy_rotation: None,
            anisotropy_direction: None,
            diffuse_transmission: None,
            diffuse_transmission_color: None,
            iridescence: None,
            iridescence_ior: None,
            iridescence_thickness: None,
            two_sided: None,
            back: None,
            vertex_colors: None,
            cull_back: None,
            emits_back: None,
        }
    }

    /// A material of `kind` named `name`, every key missing.
    pub fn of_kind(name: &str, kind: MaterialKind) -> Self {
        Self {
            kind: Some(Spanned::new(0..0, kind)),
            ..Self::named(name)
        }
    }

    /// The kind (`whitted` when not given).
    pub fn kind(&self) -> MaterialKind {
        self.kind
            .as_ref()
            .map_or(MaterialKind::Whitted, |k| *k.get_ref())
    }

    /// Every texture it holds, mutably (for rebasing image paths).
    pub fn textures_mut(&mut self) -> impl Iterator<Item = &mut TextureDesc> {
        let plain = [
            &mut self.kd,
            &mut self.reflectance,
            &mut self.specular,
            &mut self.transmittance,
            &mut self.eta,
            &mut self.k,
            &mut self.emission,
            &mut self.base_color,
            &mut self.specular_color,
            &mut self.sheen_color,
            &mut self.diffuse_transmission_color,
        ];
        let spanned = [
            &mut self.roughness,
            &mut self.roughness_u,
            &mut self.roughness_v,
            &mut self.opacity,
            &mut self.normal_map,
            &mut self.bump_map,
            &mut self.weight,
            &mut self.metallic,
            &mut self.anisotropic,
            &mut self.spec_trans,
            &mut self.spec_tint,
            &mut self.sheen,
            &mut self.sheen_tint,
            &mut self.flatness,
            &mut self.clearcoat,
            &mut self.clearcoat_gloss,
            &mut self.diff_trans,
            &mut self.transmission,
            &mut self.clearcoat_roughness,
            &mut self.clearcoat_normal_map,
            &mut self.sheen_roughness,
            &mut self.anisotropy,
            &mut self.anisotropy_direction,
            &mut self.diffuse_transmission,
            &mut self.iridescence,
            &mut self.iridescence_thickness,
        ];
        plain
            .into_iter()
            .flatten()
            .chain(spanned.into_iter().flatten().map(Spanned::get_mut))
    }
}

/// A bump pattern, which only the POV-Ray reader makes: written to TOML or read from it, it is
/// an error naming what is missing.
#[derive(Clone, Debug, PartialEq)]
pub struct BumpDesc(pub Box<lucent::texture::bump::Bump>);

impl Serialize for BumpDesc {
    fn serialize<S: serde::Serializer>(&self, _: S) -> Result<S::Ok, S::Error> {
        Err(serde::ser::Error::custom(
            "a POV-Ray `normal` (bump pattern) has no TOML form yet",
        ))
    }
}

impl<'de> Deserialize<'de> for BumpDesc {
    fn deserialize<D: serde::Deserializer<'de>>(_: D) -> Result<Self, D::Error> {
        Err(serde::de::Error::custom(
            "`bump` has no TOML form yet: bump patterns come from POV-Ray's `normal`",
        ))
    }
}
