//! `[[material]]` tables.

use super::{Color, Finite};
use lucent::Rgb;
use lucent::texture::Checker;
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;
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
    /// A rough metal (GGX): as `conductor`, plus `roughness`.
    RoughConductor,
    /// Smooth glass: `ior`, `ext_ior`, `specular`, `transmittance`.
    Dielectric,
    /// Rough glass (GGX): as `dielectric`, plus `roughness`.
    RoughDielectric,
    /// A diffuse base under a smooth dielectric coat: `reflectance`, `ior`, `ext_ior`,
    /// `specular`; `roughness` for a rough coat.
    Plastic,
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
            MaterialKind::Plastic => "plastic",
        }
    }
}

/// One `[[material]]`; which keys apply depends on `type` (default `"whitted"`); the others
/// are refused in build. A missing coefficient is 0, a missing `ior` is 1.
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
    pub ka: Option<Color>,
    /// Diffuse coefficient: a colour, a checkerboard or an image.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kd: Option<DiffuseDesc>,
    /// Specular coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ks: Option<Color>,
    /// Phong exponent, ≥ 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shininess: Option<Spanned<Finite>>,
    /// Mirror reflection coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kr: Option<Color>,
    /// Transmission coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kt: Option<Color>,
    /// Index of refraction of the inside, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ior: Option<Spanned<Finite>>,
    /// Index of refraction of the outside, > 0 (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ext_ior: Option<Spanned<Finite>>,
    /// Diffuse albedo (`diffuse`, `plastic`): a colour, a checkerboard or an image.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reflectance: Option<DiffuseDesc>,
    /// Tint of the specular reflection (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub specular: Option<Color>,
    /// Tint of the specular transmission (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmittance: Option<Color>,
    /// A conductor's index of refraction per channel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eta: Option<Color>,
    /// A conductor's extinction coefficient per channel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k: Option<Color>,
    /// A conductor by name: `"Au"`, `"Ag"`, `"Cu"`, `"Al"` (instead of `eta` and `k`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metal: Option<Spanned<String>>,
    /// GGX roughness α of the rough kinds, in (0, 1].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<Spanned<Finite>>,
    /// Radiance emitted by the surface: an area light on every object of this material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission: Option<Color>,
    /// Whether the back side scatters light like the front (default true; Mitsuba's BSDFs
    /// are one-sided unless wrapped in `twosided`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub two_sided: Option<bool>,
}

/// A colour over a surface, as a file gives it: a colour, `{ checker = { even, odd, size } }`,
/// or `{ image = "file.png" }` (PNG, JPEG, EXR or HDR; 8-bit images are sRGB-encoded, float
/// images linear; looked up by the surface's texture coordinates).
#[derive(Clone, Debug, PartialEq)]
pub enum DiffuseDesc {
    /// One colour.
    Solid(Rgb),
    /// A 3D checkerboard.
    Checker(Checker),
    /// An image file, relative to the scene file's folder.
    Image(String),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CheckerDesc {
    even: Color,
    odd: Color,
    size: Finite,
}

struct DiffuseVisitor;

impl<'de> Visitor<'de> for DiffuseVisitor {
    type Value = DiffuseDesc;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(
            "a colour (a number or [r, g, b]), { checker = { even, odd, size } } or { image = \"file\" }",
        )
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<DiffuseDesc, E> {
        let Color(c) = Color::deserialize(de::value::F64Deserializer::new(v))?;
        Ok(DiffuseDesc::Solid(c))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<DiffuseDesc, E> {
        self.visit_f64(v as f64)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<DiffuseDesc, E> {
        self.visit_f64(v as f64)
    }

    fn visit_seq<A: de::SeqAccess<'de>>(self, seq: A) -> Result<DiffuseDesc, A::Error> {
        let Color(c) = Color::deserialize(de::value::SeqAccessDeserializer::new(seq))?;
        Ok(DiffuseDesc::Solid(c))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<DiffuseDesc, A::Error> {
        let Some(key) = map.next_key::<String>()? else {
            return Err(de::Error::custom(
                "an empty table is not a texture; expected { checker = ... }",
            ));
        };
        if key == "image" {
            let file: String = map.next_value()?;
            if file.is_empty() {
                return Err(de::Error::custom("the image's file name is empty"));
            }
            if let Some(extra) = map.next_key::<String>()? {
                return Err(de::Error::custom(format!(
                    "a texture has one kind; unexpected `{extra}` after `image`"
                )));
            }
            return Ok(DiffuseDesc::Image(file));
        }
        if key != "checker" {
            return Err(de::Error::unknown_field(&key, &["checker", "image"]));
        }
        let c: CheckerDesc = map.next_value()?;
        if c.size.0 <= 0.0 {
            return Err(de::Error::custom(format!(
                "the checker size must be positive, got {}",
                c.size.0
            )));
        }
        if let Some(extra) = map.next_key::<String>()? {
            return Err(de::Error::custom(format!(
                "a texture has one kind; unexpected `{extra}` after `checker`"
            )));
        }
        Ok(DiffuseDesc::Checker(Checker {
            even: c.even.0,
            odd: c.odd.0,
            size: c.size.0,
        }))
    }
}

impl<'de> Deserialize<'de> for DiffuseDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(DiffuseVisitor)
    }
}

impl Serialize for DiffuseDesc {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        match self {
            DiffuseDesc::Solid(c) => Color(*c).serialize(s),
            DiffuseDesc::Checker(c) => {
                let mut m = s.serialize_map(Some(1))?;
                m.serialize_entry(
                    "checker",
                    &CheckerOut {
                        even: Color(c.even),
                        odd: Color(c.odd),
                        size: Finite(c.size),
                    },
                )?;
                m.end()
            }
            DiffuseDesc::Image(file) => {
                let mut m = s.serialize_map(Some(1))?;
                m.serialize_entry("image", file)?;
                m.end()
            }
        }
    }
}

#[derive(Serialize)]
struct CheckerOut {
    even: Color,
    odd: Color,
    size: Finite,
}

impl MaterialDesc {
    /// A `whitted` material with only a name, every coefficient missing.
    pub fn named(name: &str) -> Self {
        Self {
            name: Spanned::new(0..0, name.to_string()),
            kind: None,
            ka: None,
            kd: None,
            ks: None,
            shininess: None,
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
            emission: None,
            two_sided: None,
        }
    }

    /// The kind (`whitted` when not given).
    pub fn kind(&self) -> MaterialKind {
        self.kind
            .as_ref()
            .map_or(MaterialKind::Whitted, |k| *k.get_ref())
    }
}
